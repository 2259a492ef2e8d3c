// Edge collapse: p merged into q. The tets of the edge pq go; every other tet of p's ball gets q
// for p. With to_midpoint (two inner points), q also moves to the edge's metric midpoint, which
// keeps the new edges shorter where a collapse onto either end would make one too long. Made only
// when
//   - p may go: not a corner or a kept point; a surface point only along a surface edge (a ridge
//     point only along its ridge), so that the surface keeps its shape and labels;
//   - every changed tet stays positive (exact orient3d) and no quality falls below
//     min(the worst of the changed tets before, kMinCollapseQuality);
//   - no new edge (or moved one) is longer than kMaxCollapseLength: a collapse must not undo splits
//     (around a sliver: than p's longest edge);
//   - on the surface: q and p share no boundary neighbour but the two opposite pq (the surface
//     stays a manifold), and every boundary face that changes keeps its orientation within
//     kSurfaceTurn of what it was and fits the smooth surface as well as it did (surface_fit:
//     no fold).
// By the orientation test, the changed tets then fill the old ones' region exactly (each point of
// it is covered once: positive cones from q over the region's boundary), so the mesh stays valid.
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {
constexpr double kMinCollapseQuality = 0.3;
constexpr double kMaxCollapseLength = 1.4142;
constexpr double kSliverQuality = 0.1;
const double kSurfaceTurn = std::cos(20.0 * M_PI / 180.0);
}  // namespace

bool Remesher::collapse_allowed(uint32_t p, uint32_t q, const Shell& s) const {
  const uint8_t tp = mesh_.tag[p];
  if (tp & (ptag::kFrozen | ptag::kRemoved)) return false;
  const bool surface_edge = s.num_boundary > 0;
  if (!(tp & ptag::kBoundary)) return !surface_edge;
  if (!surface_edge || s.num_boundary != 2) return false;
  return bool(tp & ptag::kRidge) == mesh_.is_ridge(p, q);
}

bool Remesher::surface_collapse_fits(uint32_t p, uint32_t q, const Shell& s, const std::vector<uint32_t>& ball) {
  const uint32_t r0 = s.ring[s.bnd_ring[0]], r1 = s.ring[s.bnd_ring[1]];
  std::vector<uint32_t>& nb_p = created_;  // scratch: p's boundary neighbours
  nb_p.clear();
  for (uint32_t t : ball) {
    if (!mesh_.bnd[t]) continue;
    const uint32_t* w = mesh_.verts(t);
    const int ip = mesh_.local(t, p);
    const bool has_q = mesh_.local(t, q) >= 0;
    for (int i = 0; i < 4; ++i) {
      if (i == ip || !mesh_.is_bnd_face(t, i)) continue;
      const int* f = kFaceVertex[i];
      for (int j = 0; j < 3; ++j)
        if (w[f[j]] != p && w[f[j]] != q) nb_p.push_back(w[f[j]]);
      if (has_q) continue;
      // kFaceVertex turns the normal into the tet: negated, out of it.
      double before[3], after[3];
      uint32_t fv[3] = {w[f[0]], w[f[1]], w[f[2]]};
      const double* x[3] = {mesh_.p(fv[0]), mesh_.p(fv[1]), mesh_.p(fv[2])};
      geom::triangle_normal(x[0], x[1], x[2], before);
      for (int j = 0; j < 3; ++j)
        if (fv[j] == p) x[j] = mesh_.p(q);
      geom::triangle_normal(x[0], x[1], x[2], after);
      if (geom::dot(before, after) < kSurfaceTurn) return false;
      const bool hull = mesh_.adj[4 * size_t(t) + i] == kNone;
      for (double& c : before) c = -c;
      for (double& c : after) c = -c;
      const double fit_before = surface_fit(fv, before, hull);
      for (uint32_t& y : fv)
        if (y == p) y = q;
      if (surface_fit(fv, after, hull) < std::min(fit_before, kSurfaceFit)) return false;
    }
  }
  std::vector<uint32_t>& ball_q = ball2_;
  mesh_.ball(q, ball_q);
  mesh_.next_stamp();
  for (uint32_t x : nb_p) mesh_.mark_point(x);
  for (uint32_t t : ball_q) {
    if (!mesh_.bnd[t]) continue;
    const uint32_t* w = mesh_.verts(t);
    const int iq = mesh_.local(t, q);
    for (int i = 0; i < 4; ++i) {
      if (i == iq || !mesh_.is_bnd_face(t, i)) continue;
      for (int j = 0; j < 3; ++j) {
        const uint32_t x = w[kFaceVertex[i][j]];
        if (x != q && x != p && x != r0 && x != r1 && mesh_.point_marked(x)) return false;
      }
    }
  }
  return true;
}

bool Remesher::collapse_edge(uint32_t p, uint32_t q, uint32_t t_pq, bool to_midpoint) {
  Shell& s = shell_;
  if (!mesh_.shell(p, q, t_pq, s, 256) || !collapse_allowed(p, q, s)) return false;
  if (to_midpoint && ((mesh_.tag[p] | mesh_.tag[q]) & ptag::kBoundary)) return false;
  // Where q goes: it stays, or to the metric midpoint of pq.
  double pos[3], met[6];
  const double *qp = mesh_.p(q), *qm = mesh_.m(q);
  double det = mesh_.mdet[q];
  uint32_t hint = mesh_.hint[q];
  if (to_midpoint) {
    const double *pp = mesh_.p(p);
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = qp[k] - pp[k];
    const double lp = std::sqrt(quad_form(mesh_.m(p), d)), lq = std::sqrt(quad_form(qm, d));
    const double tpar = std::sqrt(lq) / (std::sqrt(lp) + std::sqrt(lq));
    for (int k = 0; k < 3; ++k) pos[k] = pp[k] + tpar * d[k];
    metric_.eval(pos, hint, met);
    det = metric_det(met);
    qp = pos;
    qm = met;
  }
  std::vector<uint32_t>& ball = ball_;
  mesh_.ball(p, ball);
  std::vector<uint32_t>& ball_q = moved_ball_;
  ball_q.clear();
  if (to_midpoint) {
    mesh_.ball(q, ball2_);
    for (uint32_t t : ball2_)
      if (mesh_.local(t, p) < 0) ball_q.push_back(t);
  }
  double old_min = 1.0;
  for (uint32_t t : ball) old_min = std::min(old_min, mesh_.qual[t]);
  for (uint32_t t : ball_q) old_min = std::min(old_min, mesh_.qual[t]);
  const double floor = std::min(old_min, kMinCollapseQuality);
  // Around a sliver (a tet of p's ball below kSliverQuality), the new edges may be as long as p's
  // longest: that ball is out of range already, and no new tet may fall below its worst (floor).
  // The sphere case's flat tets (mean ratio 1e-4..1e-2, inner points under the ball's chords)
  // were left because every collapse made an edge over sqrt 2.
  double max_length = kMaxCollapseLength;
  if (old_min < kSliverQuality) {
    for (uint32_t t : ball)
      for (int i = 0; i < 4; ++i) {
        const uint32_t y = mesh_.verts(t)[i];
        if (y != p) max_length = std::max(max_length, length(p, y));
      }
  }
  // Points already joined to q (when it stays): q, p and the ring of pq; others get a new edge.
  mesh_.next_stamp();
  mesh_.mark_point(q);
  mesh_.mark_point(p);
  if (!to_midpoint)
    for (uint32_t r : s.ring) mesh_.mark_point(r);
  newq_.clear();
  auto fits = [&](const uint32_t nw[4]) {
    const double* x[4];
    for (int i = 0; i < 4; ++i) x[i] = nw[i] == q ? qp : mesh_.p(nw[i]);
    if (predicates::orient3d(x[0], x[1], x[2], x[3]) <= 0) return false;
    const double qn = quality(nw, q, qp, qm, det);
    if (qn < floor) return false;
    newq_.push_back(qn);
    for (int i = 0; i < 4; ++i) {
      const uint32_t y = nw[i];
      if (mesh_.point_marked(y)) continue;
      mesh_.mark_point(y);
      if (ugawg_edge_length(qp, mesh_.p(y), qm, mesh_.m(y)) > max_length) return false;
    }
    return true;
  };
  for (uint32_t t : ball) {
    const uint32_t* w = mesh_.verts(t);
    const int iq = mesh_.local(t, q);
    if (iq >= 0) {
      // A tet of the edge: its faces opposite p and q merge; they must not both be surface.
      if (mesh_.is_bnd_face(t, mesh_.local(t, p)) && mesh_.is_bnd_face(t, iq)) return false;
      continue;
    }
    uint32_t nw[4] = {w[0], w[1], w[2], w[3]};
    nw[mesh_.local(t, p)] = q;
    if (!fits(nw)) return false;
  }
  for (uint32_t t : ball_q)
    if (!fits(mesh_.verts(t))) return false;
  if ((mesh_.tag[p] & ptag::kBoundary) && !surface_collapse_fits(p, q, s, ball)) return false;
  apply_collapse(p, q, ball);
  if (to_midpoint) {
    for (int k = 0; k < 3; ++k) mesh_.xyz[3 * size_t(q) + size_t(k)] = pos[k];
    mesh_.set_metric(q, met);
    mesh_.hint[q] = hint;
  }
  // The qualities, in the order `fits` saw the tets.
  size_t k = 0;
  for (uint32_t t : ball)
    if (!mesh_.dead(t)) mesh_.qual[t] = newq_[k++], mesh_.touch_tet(t);
  for (uint32_t t : ball_q) mesh_.qual[t] = newq_[k++], mesh_.touch_tet(t);
  ++stats_.collapses;
  if (mesh_.tag[p] & ptag::kBoundary) ++stats_.surface_collapses;
  return true;
}

void Remesher::apply_collapse(uint32_t p, uint32_t q, const std::vector<uint32_t>& ball) {
  const uint8_t tp = mesh_.tag[p];
  std::vector<uint32_t>& ridge_nb = created_;  // scratch
  ridge_nb.clear();
  if (tp & ptag::kRidge)
    for (uint32_t t : ball)
      for (int i = 0; i < 4; ++i) {
        const uint32_t x = mesh_.verts(t)[i];
        if (x != p && x != q && mesh_.is_ridge(p, x) &&
            std::find(ridge_nb.begin(), ridge_nb.end(), x) == ridge_nb.end())
          ridge_nb.push_back(x);
      }
  for (uint32_t t : ball) {
    const int iq = mesh_.local(t, q);
    const int ip = mesh_.local(t, p);
    if (iq < 0) {
      mesh_.tv[4 * size_t(t) + size_t(ip)] = q;
      continue;
    }
    // The faces opposite q and p meet: their neighbours A and B become each other's.
    const uint32_t A = mesh_.adj[4 * size_t(t) + iq], B = mesh_.adj[4 * size_t(t) + ip];
    const bool bA = mesh_.is_bnd_face(t, iq), bB = mesh_.is_bnd_face(t, ip);
    const int32_t label = bA ? mesh_.fref[4 * size_t(t) + iq] : mesh_.fref[4 * size_t(t) + ip];
    for (auto [from, to] : {std::pair<uint32_t, uint32_t>{A, B}, std::pair<uint32_t, uint32_t>{B, A}}) {
      if (from == kNone) continue;
      mesh_.adj[from] = to;
      if (bA || bB) {
        mesh_.bnd[adj_tet(from)] |= uint8_t(1u << adj_face(from));
        mesh_.fref[from] = label;
      }
    }
    const uint32_t keep = A != kNone ? adj_tet(A) : adj_tet(B);
    for (int i = 0; i < 4; ++i)
      if (i != ip) mesh_.ptet[mesh_.verts(t)[i]] = keep;
    mesh_.delete_tet(t);
  }
  for (uint32_t t : ball)
    if (!mesh_.dead(t))
      for (int i = 0; i < 4; ++i) mesh_.ptet[mesh_.verts(t)[i]] = t;
  mesh_.tag[p] |= ptag::kRemoved;
  mesh_.ptet[p] = kNone;
  if (tp & ptag::kRidge) {
    mesh_.set_ridge(p, q, false);
    for (uint32_t x : ridge_nb) {
      mesh_.set_ridge(p, x, false);
      mesh_.set_ridge(q, x, true);
    }
  }
}

size_t Remesher::collapse_sweep() {
  collect_edges(opt_.collapse_length, 1e300, edges_);
  std::sort(edges_.begin(), edges_.end(), [](const EdgeRec& x, const EdgeRec& y) { return x.length < y.length; });
  size_t made = 0;
  for (const EdgeRec& e : edges_) {
    if ((mesh_.tag[e.a] | mesh_.tag[e.b]) & ptag::kRemoved) continue;
    if (length(e.a, e.b) >= opt_.collapse_length) continue;
    uint32_t t = e.t;
    if (mesh_.dead(t) || mesh_.local(t, e.a) < 0 || mesh_.local(t, e.b) < 0) t = mesh_.edge_tet(e.a, e.b, ball_);
    if (t == kNone) continue;
    // The end with fewer constraints goes first.
    const bool a_first = (mesh_.tag[e.a] & 0x0f) <= (mesh_.tag[e.b] & 0x0f);
    const uint32_t p = a_first ? e.a : e.b, q = a_first ? e.b : e.a;
    if (collapse_edge(p, q, t) || collapse_edge(q, p, t) || collapse_edge(p, q, t, true)) {
      ++made;
    } else {
      ++stats_.collapse_refused;
    }
  }
  return made;
}

}  // namespace anitet::adapt

// Edge split: the shell of ab, each tet (a b x y) cut into (a m x y) and (m b x y) at the point m
// where the edge's two halves have equal metric lengths (the size taken to vary linearly along
// the edge); on the surface, m is on the surface edge's curve, on a ridge on the ridge curve.
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {

// A split point closer than this (metric length) to a point made earlier in the same sweep is
// put off to the next: splitting every long edge of a stretched tet at once crowded points that
// the collapses then removed (pass 2 of the UGAWG linear loop went to 70k tets and back to 43k).
constexpr double kSpacing = 0.7;

// The parameter of the point at the share s of ab's metric length (la, lb: its length in the
// metrics at a and b; the size taken to vary linearly along the edge), kept within 0.4 s and
// 1 - 0.4 (1 - s): s = 1/2 is the metric midpoint.
double metric_fraction(double la, double lb, double s) {
  if (!(la > 0.0) || !(lb > 0.0)) return s;
  const double r = la / lb;
  const double t = std::fabs(r - 1.0) < 1e-9 ? s : (std::pow(r, s) - 1.0) / (r - 1.0);
  return std::clamp(t, 0.4 * s, 1.0 - 0.4 * (1.0 - s));
}

// An edge length's distance from unit length, and that of the ends of [1/sqrt 2, sqrt 2].
double miss(double l) { return l > 0.0 ? std::fabs(std::log(l)) : HUGE_VAL; }
const double kInRange = 0.5 * std::log(2.0);

}  // namespace

// Where ab is cut: at its metric midpoint, unless a half would be out of range and its thirds
// would all be in range; then at the third whose piece is nearer unit length (the rest is cut
// by a later sweep). A wall's tangential edges in a strong normal metric (the sphere case: a
// tangential edge of length l has a normal part l^2/2R) have their lengths in range within a
// factor 1.4 in l: the icosphere's 0.1 edges cut in halves and halves again went from 2.55 to
// 0.67 (0.05 to 0.025), both out of [1/sqrt 2, sqrt 2], where thirds (0.033) are in it.
template <class Place>
double Remesher::split_parameter(uint32_t a, uint32_t b, double la, double lb, Place&& place, double pos[3],
                                 double met[6], uint32_t& hint) {
  const double tmid = metric_fraction(la, lb, 0.5);
  place(tmid, pos, false);
  metric_.eval(pos, hint, met);
  const double *pa = mesh_.p(a), *pb = mesh_.p(b), *ma = mesh_.m(a), *mb = mesh_.m(b);
  const double halves = std::max(miss(ugawg_edge_length(pa, pos, ma, met)), miss(ugawg_edge_length(pos, pb, met, mb)));
  if (halves <= kInRange) return tmid;
  double x[2][3], m[2][6];
  uint32_t h[2] = {hint, hint};
  double t[2];
  for (int i = 0; i < 2; ++i) {
    t[i] = metric_fraction(la, lb, (i + 1) / 3.0);
    place(t[i], x[i], false);
    metric_.eval(x[i], h[i], m[i]);
  }
  const double first = miss(ugawg_edge_length(pa, x[0], ma, m[0]));
  const double last = miss(ugawg_edge_length(x[1], pb, m[1], mb));
  const double thirds = std::max({first, last, miss(ugawg_edge_length(x[0], x[1], m[0], m[1]))});
  if (!(thirds <= kInRange)) return tmid;
  const int i = first <= last ? 0 : 1;
  std::copy(x[i], x[i] + 3, pos);
  std::copy(m[i], m[i] + 6, met);
  hint = h[i];
  ++stats_.splits_in_thirds;
  return t[i];
}

bool Remesher::split_edge(uint32_t a, uint32_t b, uint32_t t0) {
  Shell& s = shell_;
  if (!mesh_.shell(a, b, t0, s, 256)) return false;
  const bool surface = s.num_boundary > 0;
  // An edge from a kept surface point into the volume: its length cannot follow the metric (the
  // kept faces are as coarse as given), and splitting it crowds points against the kept faces
  // (UGAWG linear, --keep-surface: inner points at 1e-4 from them, 44% of the edges within 0.01
  // of a face out of range). The inner edges beside it are split instead.
  if (opt_.keep_surface && ((mesh_.tag[a] ^ mesh_.tag[b]) & ptag::kRequired)) return false;
  if (surface && (opt_.keep_surface || ((mesh_.tag[a] & ptag::kRequired) && (mesh_.tag[b] & ptag::kRequired))))
    return false;
  const double *pa = mesh_.p(a), *pb = mesh_.p(b);
  double ab[3];
  geom::sub(pb, pa, ab);
  double pos[3], n1[3] = {0, 0, 0}, n2[3] = {0, 0, 0}, tg[3] = {0, 0, 0};
  uint8_t tag = 0;
  // Where the point at parameter t of the edge goes: on the segment (inner), the ridge curve or
  // the surface edge's curve, with its normals and tangent.
  double fn[2][3], ta[3], tb[3];
  const bool ridge = surface && (s.num_boundary != 2 || mesh_.is_ridge(a, b));
  if (surface) {
    tag = ptag::kBoundary | (ridge ? ptag::kRidge : 0);
    // The boundary faces through ab (the first two): their normals choose the ends' sides.
    for (int f = 0; f < 2; ++f) {
      const uint32_t r = s.ring[std::min<size_t>(s.bnd_ring[size_t(std::min(f, s.num_boundary - 1))], s.ring.size() - 1)];
      geom::triangle_normal(pa, pb, mesh_.p(r), fn[f]);
    }
    double chord[3] = {ab[0], ab[1], ab[2]};
    geom::normalize(chord);
    for (int k = 0; k < 3; ++k) {
      ta[k] = (mesh_.tag[a] & (ptag::kRidge)) && !(mesh_.tag[a] & ptag::kFrozen) ? mesh_.tng[3 * size_t(a) + size_t(k)] : chord[k];
      tb[k] = (mesh_.tag[b] & (ptag::kRidge)) && !(mesh_.tag[b] & ptag::kFrozen) ? mesh_.tng[3 * size_t(b) + size_t(k)] : chord[k];
    }
  }
  auto place = [&](double t, double* x, bool geometry) {
    if (!surface) {
      for (int k = 0; k < 3; ++k) x[k] = pa[k] + t * ab[k];
    } else if (ridge) {
      geom::ridge_point(pa, ta, pb, tb, t, x, tg);
      if (!geometry) return;
      geom::surface_edge_normal(pa, side_normal(a, fn[0]), pb, side_normal(b, fn[0]), t, n1);
      geom::surface_edge_normal(pa, side_normal(a, fn[1]), pb, side_normal(b, fn[1]), t, n2);
    } else {
      const double *na = side_normal(a, fn[0]), *nb = side_normal(b, fn[0]);
      geom::surface_edge_point(pa, na, pb, nb, t, x);
      if (geometry) geom::surface_edge_normal(pa, na, pb, nb, t, n1);
    }
  };
  const double la = std::sqrt(quad_form(mesh_.m(a), ab)), lb = std::sqrt(quad_form(mesh_.m(b), ab));
  double met[6];
  uint32_t hint = mesh_.hint[a];
  const double tpar = split_parameter(a, b, la, lb, place, pos, met, hint);
  place(tpar, pos, true);
  if (!surface) return insert_on_inner_edge(s, pos, met, hint);
  // Put off when a point this sweep made is near (the split of a neighbouring edge).
  for (uint32_t r : s.ring) {
    double d[3];
    geom::sub(mesh_.p(r), pos, d);
    if (std::sqrt(std::sqrt(quad_form(mesh_.m(a), d) * quad_form(mesh_.m(b), d))) < (r >= first_new_ ? kSpacing : 0.0)) {
      ++stats_.split_refused;
      return false;
    }
  }
  // Every new tet positive.
  const size_t k = s.tets.size();
  for (size_t i = 0; i < k; ++i) {
    const double *x = mesh_.p(s.ring_at(i)), *y = mesh_.p(s.ring_at(i + 1));
    if (predicates::orient3d(pa, pos, x, y) <= 0 || predicates::orient3d(pos, pb, x, y) <= 0) {
      ++stats_.split_refused;
      return false;
    }
  }
  // The halves of the boundary faces through ab fit the smooth surface as well as they did.
  const PointGeometry g{uint32_t(mesh_.num_points()), tag, n1, (tag & ptag::kRidge) ? n2 : nullptr};
  for (const uint32_t t : s.tets) {
    if (!mesh_.bnd[t]) continue;
    const uint32_t* w = mesh_.verts(t);
    for (int f = 0; f < 4; ++f) {
      if (!mesh_.is_bnd_face(t, f) || w[f] == a || w[f] == b) continue;  // faces through ab only
      uint32_t fv[3] = {w[kFaceVertex[f][0]], w[kFaceVertex[f][1]], w[kFaceVertex[f][2]]};
      const bool hull = mesh_.adj[4 * size_t(t) + f] == kNone;
      double n[3];
      geom::triangle_normal(mesh_.p(fv[0]), mesh_.p(fv[1]), mesh_.p(fv[2]), n);
      for (double& c : n) c = -c;  // out of the tet
      const double before = std::min(surface_fit(fv, n, hull), kSurfaceFit);
      for (uint32_t end : {a, b}) {
        uint32_t half[3] = {fv[0], fv[1], fv[2]};
        const double* x[3];
        for (int j = 0; j < 3; ++j) {
          if (half[j] == end) half[j] = g.id;
          x[j] = half[j] == g.id ? pos : mesh_.p(half[j]);
        }
        geom::triangle_normal(x[0], x[1], x[2], n);
        for (double& c : n) c = -c;
        if (surface_fit(half, n, hull, &g) < before) {
          ++stats_.split_refused;
          return false;
        }
      }
    }
  }
  const uint32_t mid = mesh_.add_point(pos, met, tag, hint);
  for (int c = 0; c < 3; ++c) {
    mesh_.nrm[3 * size_t(mid) + size_t(c)] = n1[c];
    mesh_.nrm2[3 * size_t(mid) + size_t(c)] = n2[c];
    mesh_.tng[3 * size_t(mid) + size_t(c)] = tg[c];
  }
  mesh_.sync_marks();
  created_.resize(k);
  for (size_t i = 0; i < k; ++i) {
    const uint32_t t = s.tets[i];
    const int ia = mesh_.local(t, a), ib = mesh_.local(t, b);
    uint32_t w[4];
    std::copy(mesh_.verts(t), mesh_.verts(t) + 4, w);
    w[ia] = mid;
    const uint32_t t2 = mesh_.new_tet(w[0], w[1], w[2], w[3], mesh_.region[t]);
    mesh_.bnd[t2] = mesh_.bnd[t];
    for (int j = 0; j < 4; ++j) mesh_.fref[4 * size_t(t2) + j] = mesh_.fref[4 * size_t(t) + j];
    // t2 takes t's face opposite a; t and t2 meet across (m x y).
    const uint32_t across_a = mesh_.adj[4 * size_t(t) + ia];
    mesh_.adj[4 * size_t(t2) + ia] = across_a;
    if (across_a != kNone) mesh_.adj[across_a] = 4 * t2 + uint32_t(ia);
    mesh_.adj[4 * size_t(t) + ia] = 4 * t2 + uint32_t(ib);
    mesh_.adj[4 * size_t(t2) + ib] = 4 * t + uint32_t(ia);
    mesh_.bnd[t] &= uint8_t(~(1u << ia));
    mesh_.bnd[t2] &= uint8_t(~(1u << ib));
    mesh_.tv[4 * size_t(t) + size_t(ib)] = mid;
    created_[i] = t2;
  }
  // The halves t2 around the edge (m b): as the tets around ab were.
  for (size_t i = 0; i < k; ++i) {
    if (i + 1 == k && s.open) break;
    const size_t j = (i + 1) % k;
    const int lx = mesh_.local(s.tets[i], s.ring_at(i));
    const int ly = mesh_.local(s.tets[j], s.ring_at(j + 1));
    mesh_.adj[4 * size_t(created_[i]) + lx] = 4 * created_[j] + uint32_t(ly);
    mesh_.adj[4 * size_t(created_[j]) + ly] = 4 * created_[i] + uint32_t(lx);
  }
  mesh_.ptet[mid] = s.tets[0];
  mesh_.ptet[b] = created_[0];
  for (size_t i = 0; i < k; ++i) {
    update_quality(s.tets[i]);
    update_quality(created_[i]);
    mesh_.touch_tet(s.tets[i]);
    mesh_.touch_tet(created_[i]);
  }
  if (tag & ptag::kRidge) {
    mesh_.set_ridge(a, b, false);
    mesh_.set_ridge(a, mid, true);
    mesh_.set_ridge(mid, b, true);
  }
  ++stats_.splits;
  if (surface) ++stats_.surface_splits;
  return true;
}

size_t Remesher::split_sweep() {
  first_new_ = uint32_t(mesh_.num_points());
  collect_edges(-1.0, opt_.split_length, edges_);
  std::sort(edges_.begin(), edges_.end(), [](const EdgeRec& x, const EdgeRec& y) { return x.length > y.length; });
  size_t made = 0;
  for (const EdgeRec& e : edges_) {
    uint32_t t = e.t;
    if (mesh_.dead(t) || mesh_.local(t, e.a) < 0 || mesh_.local(t, e.b) < 0) t = mesh_.edge_tet(e.a, e.b, ball_);
    if (t == kNone) continue;
    made += split_edge(e.a, e.b, t);
  }
  return made;
}

}  // namespace anitet::adapt

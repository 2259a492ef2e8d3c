// Point insertion on an inner edge by the Delaunay kernel in the metric (as Mmg's and refine's
// anisotropic kernels): the cavity is the edge's shell, grown across inner faces to every tet
// whose circumsphere in the new point's metric holds the point; tets whose face on the cavity's
// boundary the point does not see (exact orient3d) are taken out again until it is star-shaped;
// the cavity is then replaced by the cones from the point over its boundary. Cutting the edge's
// shell alone (a split) leaves the stretched tets of an anisotropic mesh stretched; the cavity
// takes the neighbours the point should connect to. Refused when the point comes closer than
// kNear (in its metric) to a point of the cavity, or than kSpacing to a point the running sweep
// made.
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "metric/spd.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {

constexpr double kNear = 0.5;
constexpr double kSpacing = 0.7;
constexpr size_t kMaxCavity = 512;

// y = L^T x: lengths of y are lengths in M.
void map_point(const double l[6], const double x[3], double y[3]) {
  y[0] = l[0] * x[0] + l[1] * x[1] + l[3] * x[2];
  y[1] = l[2] * x[1] + l[4] * x[2];
  y[2] = l[5] * x[2];
}

}  // namespace

bool Remesher::insert_on_inner_edge(const Shell& s, const double pos[3], const double met[6], uint32_t hint) {
  double l[6];
  if (!metric::cholesky(met, l)) return false;
  if (incav_.size() < mesh_.num_slots()) incav_.resize(mesh_.num_slots(), 0);
  // A point of the cavity too near refuses the insertion: checked as each point comes in, so a
  // refusal costs little (they are most insertions tried in a stretched layer).
  auto too_near = [&](uint32_t x) {
    double d[3];
    const double* px = mesh_.p(x);
    for (int c = 0; c < 3; ++c) d[c] = px[c] - pos[c];
    return std::sqrt(quad_form(met, d)) < (x >= first_new_ ? kSpacing : kNear);
  };
  auto refuse = [&] {
    for (uint32_t t : cavity_) incav_[t] = 0;
    ++stats_.split_refused;
    return false;
  };
  std::vector<uint32_t>& cav = cavity_;
  cav.clear();
  mesh_.next_stamp();
  for (uint32_t t : s.tets) {
    mesh_.mark_tet(t);
    incav_[t] = 2;  // a seed: must stay
    cav.push_back(t);
  }
  for (uint32_t r : s.ring)
    if (too_near(r)) return refuse();
  // Growth: neighbours across inner faces whose circumsphere in the metric holds the point.
  for (size_t k = 0; k < cav.size() && cav.size() < kMaxCavity; ++k) {
    const uint32_t t = cav[k];
    for (int i = 0; i < 4; ++i) {
      const uint32_t a = mesh_.adj[4 * size_t(t) + i];
      if (a == kNone || mesh_.is_bnd_face(t, i)) continue;
      const uint32_t n = adj_tet(a);
      if (mesh_.tet_marked(n)) continue;
      mesh_.mark_tet(n);
      const uint32_t* w = mesh_.verts(n);
      double y[4][3];
      for (int j = 0; j < 4; ++j) {
        const double* x = mesh_.p(w[j]);
        const double d[3] = {x[0] - pos[0], x[1] - pos[1], x[2] - pos[2]};  // relative: better rounding
        map_point(l, d, y[j]);
      }
      const double origin[3] = {0, 0, 0};
      if (predicates::insphere(y[0], y[1], y[2], y[3], origin) > 0) {
        if (too_near(w[adj_face(a)])) return refuse();  // the point the tet brings in
        incav_[n] = 1;
        cav.push_back(n);
      }
    }
  }
  // Star-shaped: every boundary face of the cavity seen from the point.
  auto on_boundary = [&](uint32_t t, int i) {
    const uint32_t a = mesh_.adj[4 * size_t(t) + i];
    return a == kNone || mesh_.is_bnd_face(t, i) || !incav_[adj_tet(a)];
  };
  auto sees = [&](uint32_t t, int i) {
    const uint32_t* w = mesh_.verts(t);
    const double* x[4];
    for (int j = 0; j < 4; ++j) x[j] = j == i ? pos : mesh_.p(w[j]);
    return predicates::orient3d(x[0], x[1], x[2], x[3]) > 0;
  };
  bool ok = true;
  for (bool changed = true; changed && ok;) {
    changed = false;
    for (uint32_t t : cav) {
      if (!incav_[t]) continue;
      for (int i = 0; i < 4; ++i) {
        if (!on_boundary(t, i) || sees(t, i)) continue;
        if (incav_[t] == 2) {
          ok = false;
        } else {
          incav_[t] = 0;
          changed = true;
        }
        break;
      }
      if (!ok) break;
    }
  }
  size_t kept = 0;
  for (uint32_t t : cav)
    if (incav_[t]) cav[kept++] = t;
  for (uint32_t t : cav) incav_[t] = 0;
  cav.resize(kept);
  if (!ok) {
    ++stats_.split_refused;
    return false;
  }
  const uint32_t mid = mesh_.add_point(pos, met, 0, hint);
  mesh_.sync_marks();
  mesh_.next_stamp();
  for (uint32_t t : cav) mesh_.mark_tet(t);
  fresh_.clear();
  for (uint32_t t : cav)
    for (int i = 0; i < 4; ++i) {
      const uint32_t a = mesh_.adj[4 * size_t(t) + i];
      if (a != kNone && !mesh_.is_bnd_face(t, i) && mesh_.tet_marked(adj_tet(a))) continue;
      const uint32_t* w = mesh_.verts(t);
      TetVerts nt = {w[0], w[1], w[2], w[3]};
      nt[size_t(i)] = mid;
      fresh_.push_back(nt);
    }
  if (!replace(cav, fresh_)) {  // cannot happen for a star-shaped cavity; keep the mesh sound
    mesh_.tag[mid] |= ptag::kRemoved;
    ++stats_.split_refused;
    return false;
  }
  ++stats_.splits;
  return true;
}

}  // namespace anitet::adapt

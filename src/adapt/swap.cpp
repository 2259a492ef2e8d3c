// Swaps raising the worst quality of the tets they replace:
//   - edge removal: the k tets around an inner edge ab (k = 3 .. kMaxShell) replaced by the
//     2(k - 2) tets joining a and b to a triangulation of the ring, the one whose worst tet is
//     best (dynamic programming over the ring's triangulations);
//   - surface edge swap: for an edge ab of the surface between two faces (a b c) and (a b d) of
//     one label, not a ridge, the open shell replaced by tets joining a and b to a triangulation
//     of the ring c .. d that has the edge cd: the surface gets (a c d) and (b d c) for (a b c)
//     and (a b d). Made only where the surface stays as flat and as close to the points' normals
//     as it was (or within kFlat of flat);
//   - 2-3 flip: the two tets across an inner face replaced by three around the edge joining the
//     opposite points.
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {
constexpr size_t kMaxShell = 9;
constexpr double kGain = 1e-3;  // a swap must raise the worst quality by this much
const double kFlat = std::cos(8.0 * M_PI / 180.0);
}  // namespace

namespace {

// The triangulation of the polygon ring[0..n-1] maximizing the worst of tri_q(i, m, j) (i < m < j),
// by dynamic programming; its triangles in `tris`. Returns the worst quality.
template <class TriQ>
double best_triangulation(size_t n, TriQ&& tri_q, std::vector<std::array<uint32_t, 3>>& tris) {
  double best[kMaxShell + 2][kMaxShell + 2];
  int arg[kMaxShell + 2][kMaxShell + 2];
  for (size_t i = 0; i + 1 < n; ++i) best[i][i + 1] = 2.0;
  for (size_t len = 2; len < n; ++len)
    for (size_t i = 0; i + len < n; ++i) {
      const size_t j = i + len;
      best[i][j] = -2.0;
      arg[i][j] = -1;
      for (size_t m = i + 1; m < j; ++m) {
        const double q = std::min({tri_q(i, m, j), best[i][m], best[m][j]});
        if (q > best[i][j]) best[i][j] = q, arg[i][j] = int(m);
      }
    }
  tris.clear();
  std::vector<std::pair<size_t, size_t>> todo = {{0, n - 1}};
  while (!todo.empty()) {
    auto [i, j] = todo.back();
    todo.pop_back();
    if (j < i + 2) continue;
    const auto m = size_t(arg[i][j]);
    tris.push_back({uint32_t(i), uint32_t(m), uint32_t(j)});
    todo.push_back({i, m});
    todo.push_back({m, j});
  }
  return best[0][n - 1];
}

}  // namespace

bool Remesher::swap_edge(uint32_t a, uint32_t b, uint32_t t0) {
  Shell& s = shell_;
  if (!mesh_.shell(a, b, t0, s, kMaxShell)) return false;
  const size_t k = s.tets.size();
  const bool surface = s.num_boundary > 0;
  if (surface) {
    if (opt_.keep_surface || !s.open || s.num_boundary != 2 || k < 2 || mesh_.is_ridge(a, b)) return false;
    if (s.bnd_label[0] != s.bnd_label[1]) return false;
  } else if (s.open || k < 3) {
    return false;
  }
  double old_min = 1.0;
  for (uint32_t t : s.tets) old_min = std::min(old_min, mesh_.qual[t]);
  const size_t n = s.ring.size();  // polygon vertices: the ring (closed), or ring[0..k] (open)
  // Memo of the triangle qualities: both tets (r_i r_m r_j b) and (r_m r_i r_j a).
  double memo[kMaxShell + 2][kMaxShell + 2][kMaxShell + 2];
  for (size_t i = 0; i < n; ++i)
    for (size_t m = 0; m < n; ++m)
      for (size_t j = 0; j < n; ++j) memo[i][m][j] = -3.0;
  auto tri_q = [&](size_t i, size_t m, size_t j) {
    double& q = memo[i][m][j];
    if (q > -3.0) return q;
    const uint32_t ri = s.ring[i], rm = s.ring[m], rj = s.ring[j];
    const uint32_t t1[4] = {ri, rm, rj, b}, t2[4] = {rm, ri, rj, a};
    q = std::min(quality(t1), quality(t2));
    return q;
  };
  std::vector<std::array<uint32_t, 3>> tris;
  const double q = best_triangulation(n, tri_q, tris);
  if (!(q > old_min + kGain)) return false;
  fresh_.clear();
  for (const auto& tr : tris) {
    const uint32_t ri = s.ring[tr[0]], rm = s.ring[tr[1]], rj = s.ring[tr[2]];
    fresh_.push_back({ri, rm, rj, b});
    fresh_.push_back({rm, ri, rj, a});
  }
  for (const TetVerts& w : fresh_)
    if (predicates::orient3d(mesh_.p(w[0]), mesh_.p(w[1]), mesh_.p(w[2]), mesh_.p(w[3])) <= 0) return false;
  if (surface) {
    // The surface before, (a b r0) and (a b rk), and after, (r0 rk a) and (r0 rk b): as flat (the
    // signed cosine of the faces' normals out of the mesh) and as close to the surface normals
    // (surface_fit: no fold).
    const uint32_t r0 = s.ring.front(), rk = s.ring.back();
    // The unit normal of face (x y z) pointing away from w (a point of its tet).
    auto outward = [&](uint32_t x, uint32_t y, uint32_t z, uint32_t w, double nrm[3]) {
      geom::triangle_normal(mesh_.p(x), mesh_.p(y), mesh_.p(z), nrm);
      double d[3];
      geom::sub(mesh_.p(w), mesh_.p(x), d);
      if (geom::dot(nrm, d) > 0) nrm[0] = -nrm[0], nrm[1] = -nrm[1], nrm[2] = -nrm[2];
    };
    const uint32_t rm = s.ring[tris[0][1]];  // best_triangulation gives (0 m n-1) first
    double b0[3], b1[3], a0[3], a1[3];
    outward(a, b, r0, s.ring[1], b0);
    outward(a, b, rk, s.ring[k - 1], b1);
    outward(r0, rk, a, rm, a0);
    outward(r0, rk, b, rm, a1);
    const uint32_t fb0[3] = {a, b, r0}, fb1[3] = {a, b, rk}, fa0[3] = {r0, rk, a}, fa1[3] = {r0, rk, b};
    const double flat_before = geom::dot(b0, b1), flat_after = geom::dot(a0, a1);
    const double fit_before = std::min(surface_fit(fb0, b0, true), surface_fit(fb1, b1, true));
    const double fit_after = std::min(surface_fit(fa0, a0, true), surface_fit(fa1, a1, true));
    if (flat_after < std::min(flat_before, kFlat) || fit_after < std::min(fit_before, kSurfaceFit)) return false;
    // The new edges (the diagonals of the ring's triangulation, r0 rk among them) must be new: in
    // a thin layer, two ring points may be joined already outside the shell.
    for (const auto& tr : tris)
      for (int e = 0; e < 3; ++e) {
        const uint32_t i = tr[size_t(e)], j = tr[size_t((e + 1) % 3)];
        if (std::max(i, j) - std::min(i, j) < 2) continue;  // a side of the ring
        if (mesh_.edge_tet(s.ring[i], s.ring[j], ball2_) != kNone) return false;
      }
  }
  fresh_tets_ = s.tets;
  if (!replace(fresh_tets_, fresh_, surface, surface ? s.bnd_label[0] : 0)) return false;
  ++stats_.swaps;
  if (surface) ++stats_.surface_swaps;
  return true;
}

bool Remesher::swap_face(uint32_t t, int i) {
  if (mesh_.is_bnd_face(t, i)) return false;
  const uint32_t a = mesh_.adj[4 * size_t(t) + i];
  if (a == kNone) return false;
  const uint32_t n = adj_tet(a);
  if (mesh_.region[n] != mesh_.region[t]) return false;
  const uint32_t* w = mesh_.verts(t);
  const uint32_t d = w[i], e = mesh_.verts(n)[adj_face(a)];
  const uint32_t f0 = w[kFaceVertex[i][0]], f1 = w[kFaceVertex[i][1]], f2 = w[kFaceVertex[i][2]];
  fresh_ = {TetVerts{f0, f1, e, d}, TetVerts{f1, f2, e, d}, TetVerts{f2, f0, e, d}};
  const double old_min = std::min(mesh_.qual[t], mesh_.qual[n]);
  double q = 1.0;
  for (const TetVerts& x : fresh_) q = std::min(q, quality(x.data()));
  if (!(q > old_min + kGain)) return false;
  for (const TetVerts& x : fresh_)
    if (predicates::orient3d(mesh_.p(x[0]), mesh_.p(x[1]), mesh_.p(x[2]), mesh_.p(x[3])) <= 0) return false;
  fresh_tets_ = {t, n};
  if (!replace(fresh_tets_, fresh_)) return false;
  ++stats_.swaps;
  return true;
}

size_t Remesher::swap_sweep(double below) {
  size_t made = 0;
  const size_t slots = mesh_.num_slots();
  tried_.clear();  // each edge once per sweep
  for (uint32_t t = 0; t < slots; ++t) {
    if (mesh_.dead(t) || !(mesh_.qual[t] < below)) continue;
    bool done = false;
    for (int k = 0; k < 6 && !done; ++k) {
      const uint32_t* w = mesh_.verts(t);
      const uint32_t a = w[kEdgeVertex[k][0]], b = w[kEdgeVertex[k][1]];
      uint32_t& seen = tried_.find_or_insert(edge_key(a, b), 0);
      if (seen) continue;
      seen = 1;
      done = swap_edge(a, b, t);
    }
    for (int i = 0; i < 4 && !done; ++i) done = swap_face(t, i);
    made += done;
  }
  return made;
}

}  // namespace anitet::adapt

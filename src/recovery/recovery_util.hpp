// Small helpers shared by the two recovery strategies (internal header).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "predicates/predicates.hpp"
#include "recovery/recovery.hpp"

namespace anitet::recovery_detail {

inline uint64_t edge_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

using Tri = std::array<uint32_t, 3>;
inline Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}
struct TriHash {
  size_t operator()(const Tri& t) const {
    uint64_t h = t[0];
    h = h * 0x9e3779b97f4a7c15ull ^ t[1];
    h = h * 0x9e3779b97f4a7c15ull ^ t[2];
    return size_t(h ^ (h >> 29));
  }
};

inline void cross(const double* u, const double* v, double* w) {
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}
inline void sub(const double* a, const double* b, double* c) {
  for (int d = 0; d < 3; ++d) c[d] = a[d] - b[d];
}
inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double dist2(const double* a, const double* b) {
  double d[3];
  sub(a, b, d);
  return dot(d, d);
}

// Whether the line PQ passes strictly through the interior of triangle ABC (exact test); if so, x
// gets the crossing point with ABC's plane (in floating point, so only near the triangle).
inline bool line_crosses_triangle(const double* P, const double* Q, const double* A, const double* B,
                                  const double* C, double x[3]) {
  const int s0 = predicates::orient3d(P, Q, A, B);
  const int s1 = predicates::orient3d(P, Q, B, C);
  const int s2 = predicates::orient3d(P, Q, C, A);
  if (!((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0))) return false;
  double n[3], ab[3], ac[3], ap[3], aq[3];
  sub(B, A, ab);
  sub(C, A, ac);
  cross(ab, ac, n);
  sub(P, A, ap);
  sub(Q, A, aq);
  const double dp = dot(n, ap), dq = dot(n, aq);
  const double s = dp / (dp - dq);
  for (int d = 0; d < 3; ++d) x[d] = P[d] + s * (Q[d] - P[d]);
  return true;
}

// The Delaunay tetrahedralization of S's points into mesh (vertex i is S's vertex i), and with
// `box` of the 8 corners of a box around them as well (vertices n..n+7, kBoxCorners): then no point
// of S is on the convex hull. Points of S on a hull face (a flat face of a CAD part, its Steiner
// points on it) sit on ghost tets, which no flip and no forced cavity may touch: there the pieces
// of a missing edge were split down to rounding. Error::DuplicatePoint names two input vertices
// with the same coordinates.
constexpr uint32_t kBoxCorners = 8;
Status delaunay_of_surface_points(TetMesh& mesh, const SurfaceMesh& S, bool box);

// After the carving, which leaves them in no tet: removes the box corners (vertices n_in ..
// n_in + kBoxCorners - 1) from out's mesh and shifts the later vertex ids (Steiner points, S2).
Status drop_box_corners(RecoveryOutput& out, size_t n_in);

// Carving's last step: tets of component comp[t] get region region[comp[t]] when it is >= 0 and
// are deleted otherwise (their kept neighbours' facets then have no neighbour).
void keep_regions(TetMesh& mesh, const std::vector<int32_t>& comp, const std::vector<int32_t>& region);

// Sets (or clears) the constrained bit of edge (a b) in every tet of `ball` (tets around a) that
// has it; false when none has it.
bool set_edge_constrained(TetMesh& mesh, const std::vector<uint32_t>& ball, uint32_t a, uint32_t b, bool on);
// The same over the n tets at `tets`.
bool set_edge_constrained(TetMesh& mesh, const uint32_t* tets, size_t n, uint32_t a, uint32_t b, bool on);

// Live tets that are not ghosts.
size_t count_live_tets(const TetMesh& mesh);

}  // namespace anitet::recovery_detail

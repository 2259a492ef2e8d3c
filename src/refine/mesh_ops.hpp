// Tet shape measures shared by refinement (collapse checks) and optimization (the quantity it
// maximizes). The local topological operations they both use (vertex balls, edge rings,
// replace_tets) are in core/tet_ops.hpp, shared with boundary recovery.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"
#include "core/tet_ops.hpp"

namespace anitet::meshops {

// Radius ratio 3 r_in / R_circ of (a b c d), in floating point: 1 for the regular tet, <= 0 when
// the tet is flat or negatively oriented (so that it also ranks inverted candidates).
double radius_ratio(const double* a, const double* b, const double* c, const double* d);
double tet_radius_ratio(const TetMesh& mesh, uint32_t t);

// The shape measure the optimizer maximizes: min(radius ratio, smallest sine of the six dihedral
// angles / sin(acos(1/3))) -- 1 for the regular tet; the sine term also catches the tets with a
// small or a large dihedral angle that the radius ratio ranks fairly well. <= 0 when inverted.
double shape_quality(const double* a, const double* b, const double* c, const double* d);
double tet_shape_quality(const TetMesh& mesh, uint32_t t);

// Lowest shape_quality over the tets.
double min_quality(const TetMesh& mesh, const std::vector<uint32_t>& tets);

// ---- Shapes in a metric ----------------------------------------------------------------------
// The linear map x -> L^T x, M = L L^T (Cholesky; M as 6 doubles xx xy yy xz yz zz): lengths of
// mapped vectors are lengths in M, so the shape measures of a mapped tet are its shape in M.
// `identity` when M is isotropic up to a relative 1e-6: the measures above are scale invariant,
// so the tet is measured as it is (bit for bit the Euclidean figures). A mapped tet keeps its orientation (det L > 0).
struct MetricMap {
  bool identity = true;
  double l[6] = {1.0, 0.0, 1.0, 0.0, 0.0, 1.0};  // l00 l10 l11 l20 l21 l22
  static MetricMap of(const double m[6]);
  void apply(const double* x, double* y) const;
  // The inverse: x with L^T x = y (a step of y in the metric's space, back in space).
  void unapply(const double* y, double* x) const;
};

// shape_quality of (a b c d) measured in the metric of `map`.
double metric_shape_quality(const MetricMap& map, const double* a, const double* b, const double* c,
                            const double* d);
// Lowest metric_shape_quality over the tets, all measured in the metric of `map`.
double min_quality(const TetMesh& mesh, const std::vector<uint32_t>& tets, const MetricMap& map);

// ---- Edge collapse ----------------------------------------------------------------------------

// The tets a collapse of v onto w replaces, and their replacements: `old` is v's ball (from its
// tet tv) followed, when w moves, by w's other tets; `fresh` is `old` without the tets of edge vw,
// v renamed w, in the same order (so every fresh tet has w). False (no change to the mesh) when v
// and w share no tet.
// Refinement's coarsening and the optimizer's sliver collapses test `fresh` their own ways, then
// hand both to replace_tets.
bool collapse_tets(TetMesh& mesh, VertexTets& vt, uint32_t v, uint32_t tv, uint32_t w, bool w_moves,
                   std::vector<uint32_t>& old, std::vector<TetVerts>& fresh, std::vector<uint32_t>& ball_w);
// The same from v's ball, in `old` on entry, and w's when w moves (null otherwise); changes
// nothing.
bool collapse_replacement(const TetMesh& mesh, uint32_t v, uint32_t w, const std::vector<uint32_t>* ball_w,
                          std::vector<uint32_t>& old, std::vector<TetVerts>& fresh);

// The largest size of the metric M, 1 / sqrt(smallest eigenvalue): the Euclidean radius of the
// unit ball of M (h for I / h^2).
double metric_max_size(const double m[6]);

}  // namespace anitet::meshops

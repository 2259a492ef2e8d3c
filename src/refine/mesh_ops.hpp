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

}  // namespace anitet::meshops

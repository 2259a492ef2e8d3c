// Boundary-layer prisms as prism cells: stage 1 builds each BL prism ABC-A'B'C' as three tets
// (layers.hpp), which stay frozen through the later stages; this merges them back into one prism
// cell each, for the solvers whose finite volumes suffer from the split (a thin prism's tets have
// dual faces near 90 deg non-orthogonal).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

struct PrismMergeStats {
  size_t bl_tets = 0;    // tets of the BL regions before the merge
  size_t prisms = 0;     // prisms made, 3 of those tets each
  size_t kept_tets = 0;  // BL tets left as tets (no exact prism: see merge_bl_prisms)
  // Why: exact_prisms groups of three tets form a prism exactly (the other BL tets do not: the
  // tets around a column that stopped in its layer, or a partial push); of those, kept as tets
  // because a quad side lies on a BL cell that is no prism (beside_other_cells), or on a prism
  // kept as tets (beside_kept: so one stopped column keeps its whole layer, above it too, as tets).
  size_t exact_prisms = 0;
  size_t beside_other_cells = 0;
  size_t beside_kept = 0;
};

// Replaces each boundary-layer prism's three tets by one prism cell (VolumeMesh::prism,
// positively oriented, region kept in prism_region); the other tets keep their order.
// vertex_origin: 1 per vertex, the vertex it was pushed from (~0u: none), so that the vertices of
// one column of the layers (a wall vertex and its pushed copies) share a root and are numbered by
// depth. Among the tets of regions >= first_bl_region, the three tets of one prism are those with
// the same three columns and the same lowest depth; they become a prism only when exactly three
// such tets exist, their six vertices are two per column (one pushed from the other) and their
// faces are the prism's (the caps once, each quad side twice, split along a diagonal, two faces
// shared between them). A prism whose quad side would lie on a tet's faces (its neighbour kept as
// tets: a column that stopped in a layer, a partial push) is kept as tets too, so that every quad
// side is shared by two prisms or on the boundary (a quad facing two triangles would need a
// pyramid cell, which VolumeMesh has not), and so is a prism beside it, through the layer.
// Error::InvalidArgument for a vertex_origin of the wrong size or with a cycle, Error::BadIndex
// for an index out of range.
// tet_prism (may be null): 1 per tet of the mesh given, the prism it went into or -1 (kept).
Result<PrismMergeStats> merge_bl_prisms(VolumeMesh& mesh, const std::vector<uint32_t>& vertex_origin,
                                        int32_t first_bl_region, std::vector<int32_t>* tet_prism = nullptr);

}  // namespace anitet

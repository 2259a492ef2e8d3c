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
  size_t pyramids = 0;   // pyramids made, 2 of those tets each (0 without make_pyramids)
  size_t kept_tets = 0;  // BL tets left as tets: bl_tets - 3 prisms - 2 pyramids
  // Why: exact_prisms groups of three tets form a prism exactly and exact_pyramids pairs of tets
  // a pyramid (the other BL tets form neither: a partial push, a tet alone where two of a
  // triangle's three columns stopped); of those cells, kept as tets because a quad lies on
  // triangles of another cell (beside_other_cells: a tet, or a pyramid's side where a column
  // stalled behind its neighbours and went on later, so that the cells around it cannot all
  // meet quad to quad), or on a cell kept as tets (beside_kept: spreads through the layer).
  // Without pyramids, every column that stops in a layer keeps its layer as tets.
  size_t exact_prisms = 0;
  size_t exact_pyramids = 0;
  size_t beside_other_cells = 0;
  size_t beside_kept = 0;
};

// Replaces each boundary-layer prism's three tets by one prism cell (VolumeMesh::prism,
// positively oriented, region kept in prism_region), and, with make_pyramids, the two tets left
// where a column stopped in its layer by one pyramid cell (VolumeMesh::pyramid); the other tets
// keep their order.
// vertex_origin: 1 per vertex, the vertex it was pushed from (~0u: none), so that the vertices of
// one column of the layers (a wall vertex and its pushed copies) share a root and are numbered by
// depth. Among the tets of regions >= first_bl_region, the three tets of one prism are those with
// the same three columns and the same lowest depth; they become a prism only when exactly three
// such tets exist, their six vertices are two per column (one pushed from the other) and their
// faces are the prism's (the caps once, each quad side twice, split along a diagonal, two faces
// shared between them).
// A pyramid is two BL tets of one region in no such prism that share a face and have five
// vertices on three columns: two pairs, each one pushed from the other (the quad base), and the
// apex (the stopped vertex), the shared face being the apex and two opposite corners of the quad.
// It is made only when the base's two splits both give positive tets with the apex
// (orient3d_certified: the two tets and the two of the other diagonal), so that it is valid
// whichever diagonal a reader cuts it along; the base's warp is not bounded further (the quad is
// also the side of the prism beside it, which has it whatever is done here).
// A cell whose quad would lie on another cell's triangles (a tet's: a partial push, a pyramid
// refused; a pyramid's side) is kept as tets too, so that every quad is shared by two cells or on
// the boundary (a quad facing two triangles is no valid face pair), and so is a cell beside it.
// Error::InvalidArgument for a vertex_origin of the wrong size or with a cycle, Error::BadIndex
// for an index out of range.
// tet_prism (may be null): 1 per tet of the mesh given, the prism it went into or -1 (kept or in
// a pyramid). tet_pyramid (may be null): likewise for pyramids.
Result<PrismMergeStats> merge_bl_prisms(VolumeMesh& mesh, const std::vector<uint32_t>& vertex_origin,
                                        int32_t first_bl_region, std::vector<int32_t>* tet_prism = nullptr,
                                        bool make_pyramids = true, std::vector<int32_t>* tet_pyramid = nullptr);

}  // namespace anitet

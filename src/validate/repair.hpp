// Safe repairs of a surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.hpp"
#include "validate/topology.hpp"

namespace anitet::repair {

// Merges vertices whose coordinates are exactly equal (non-finite ones are never merged): the
// lowest id of each group is kept, the others are removed and the ids compacted in order.
// Returns the number of vertices removed; when > 0, vertex_map[old id] = new id. All triangle
// indices must be valid.
size_t merge_duplicate_vertices(SurfaceMesh& s, std::vector<uint32_t>& vertex_map);

// Reverses the orientation of the given triangles (swaps their last two corners).
void flip_triangles(SurfaceMesh& s, const std::vector<uint32_t>& tris);

// The shells (topology::analyse) whose every edge has two triangles but where some neighbours
// disagree on the orientation (a polygon soup whose triangles face either way): each such shell
// is made consistent, every edge used once in each direction, by flipping the triangles that
// disagree with its first triangle, or the others when they are fewer; which way the shell then
// faces is the shell orientation repair's business. A shell where no orientation agrees across
// all its edges (non-orientable: a Moebius band closed by another piece, a Klein bottle) is left
// as it is and reported with an edge where the propagation met itself. `edges` is kept true to the
// flipped triangles (their half-edges' corners renumbered).
struct ShellReorientation {
  uint32_t shell = 0;
  size_t flipped = 0;                 // triangles flipped (0 when not orientable)
  bool orientable = true;
  uint32_t edge_lo = 0, edge_hi = 0;  // not orientable: an edge where it fails (vertex ids)
};
std::vector<ShellReorientation> orient_shells_consistently(SurfaceMesh& s, topology::EdgeTable& edges,
                                                          const topology::Topology& topo);

}  // namespace anitet::repair

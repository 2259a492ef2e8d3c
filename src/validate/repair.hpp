// Safe repairs of a surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.hpp"

namespace anitet::repair {

// Merges vertices whose coordinates are exactly equal (non-finite ones are never merged): the
// lowest id of each group is kept, the others are removed and the ids compacted in order.
// Returns the number of vertices removed; when > 0, vertex_map[old id] = new id. All triangle
// indices must be valid.
size_t merge_duplicate_vertices(SurfaceMesh& s, std::vector<uint32_t>& vertex_map);

// Reverses the orientation of the given triangles (swaps their last two corners).
void flip_triangles(SurfaceMesh& s, const std::vector<uint32_t>& tris);

}  // namespace anitet::repair

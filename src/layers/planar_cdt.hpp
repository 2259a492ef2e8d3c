// A constrained triangulation of a polygonal region in the plane, for re-triangulating a planar
// piece of a slide patch around the boundary layer's columns (slide_patches.hpp).
//
// Orientations are exact (orient2d); the Delaunay flips use the lifted orient3d of the points
// (x, y, x^2 + y^2) with the lift rounded, which is exact for those lifted points: the flips then
// build the regular triangulation of a consistent lifted set, so they terminate and only the
// quality, never the validity, depends on the rounding.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/status.hpp"

namespace anitet::layers {

// `xy`: 2 per point. `segments`: directed edges (a, b) with the region on their left; together
// they bound the region (outer loops counter-clockwise, holes clockwise) and meet only at shared
// end points. Returns the triangles (3 point ids each, counter-clockwise) that cover the region
// exactly: every segment is an edge, every point inside the region or on its boundary a corner,
// points outside it unused. Error::InvalidArgument for a point given twice, a point strictly
// inside a segment, crossing segments or segments that do not close the region.
Result<std::vector<uint32_t>> triangulate_region(const std::vector<double>& xy,
                                                 const std::vector<std::pair<uint32_t, uint32_t>>& segments);

}  // namespace anitet::layers

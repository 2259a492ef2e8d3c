// The exact search for intersecting triangle pairs: BVH box pairs, then exact tests in parallel.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/bvh.hpp"
#include "core/surface_mesh.hpp"

namespace anitet {

// Every pair (i < j) of triangles with testable[i] and testable[j] that meet beyond their shared
// corners or edge (see tri_intersect.hpp), sorted. num_threads <= 0: TBB's default. The result
// does not depend on the thread count.
std::vector<std::pair<uint32_t, uint32_t>> find_intersecting_pairs(
    const SurfaceMesh& s, const TriangleBVH& bvh, const std::vector<uint8_t>& testable,
    int num_threads);

}  // namespace anitet

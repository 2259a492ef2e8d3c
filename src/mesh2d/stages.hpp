// Stages 1-2 and the coupling of the 2D method: the front layer T1 on the input's segments, the
// conforming Delaunay triangulation T2 of the domain bounded by the new front S1 (Steiner points
// on S1's edges only), and T1's triangles split along S1's recovered pieces (the paper's Table 1
// in 2D: a triangle vF of T1 on an S1 edge F recovered as pieces F_i becomes the fan vF_i),
// merged into one conforming triangulation whose edges tagged with input segment indices are the
// input's segments, whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "mesh2d/domain.hpp"
#include "mesh2d/front.hpp"
#include "mesh2d/pslg.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

struct StageStats {
  size_t t1_triangles = 0, s1_edges = 0, halvings = 0, closed = 0;
  size_t t2_triangles = 0, steiner_on_s1 = 0;
  size_t coupled = 0;      // T1 triangles split into fans
  size_t free_points = 0;  // input points on no segment, inserted
};

// The domain's front edges: each segment's sides with the domain on their left (2 vertices
// each), and their segments.
void front_edges(const Pslg& pslg, const Domain& domain, std::vector<uint32_t>& edges, std::vector<int32_t>& seg);

// Stages 1, 2 and the coupling: the conforming triangulation of the domain, the input's points
// first (in order), its segments tagged with their indices, then the input's free points.
Result<Triangulation> boundary_constrained_triangulation(const Pslg& pslg, const Domain& domain,
                                                         const FrontOptions& front_options, StageStats* stats);

}  // namespace anitet::mesh2d

// The quality figures the 2D mesher reports (its own measure; tests/tools/check2d.py is the
// independent one): angles, radius ratios 2r/R (1 for an equilateral triangle), the share of
// edges of metric length in [1/sqrt2, sqrt2] (in the mesh's per-vertex metric).
#pragma once

#include <cstddef>

#include "mesh2d/mesher2.hpp"

namespace anitet::mesh2d {

struct Quality2 {
  size_t vertices = 0, triangles = 0, edges = 0;
  double min_angle_deg = 0, max_angle_deg = 0;
  size_t free_triangles = 0;       // triangles with no vertex among the input's points
  double min_angle_free_deg = 0;   // their smallest angle (180 when there is none)
  double mean_radius_ratio = 0, min_radius_ratio = 0;
  double in_range = 0;             // share of edges in [1/sqrt2, sqrt2] (1 without a metric)
  double length_min = 0, length_max = 0;
};

Quality2 measure_quality(const TriMesh2& mesh);

}  // namespace anitet::mesh2d

// Stage 3b in 2D: edges longer than sqrt(2) in the metric are split at their metric midpoints
// (inserted through the kernel, in the metric when it is anisotropic: the metric Delaunay
// kernel; not next to another point), quality flips after each pass, edges
// shorter than 1/sqrt(2) collapsed (a free end onto the other, when the mesh stays valid, no new
// edge gets longer than sqrt(2) and the worst triangle around does not get worse), longest
// and shortest first, in passes until nothing changes. Input segments are never split (their
// points never moved or removed) unless split_segments.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/metric_measures.hpp"
#include "core/status.hpp"
#include "mesh2d/metric2.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

struct RefineOptions2 {
  bool split_segments = false;  // constrained edges may be split (the halves keep the tag)
  int max_passes = 60;
  double split_length = kUnitRangeMax;
  double collapse_length = kUnitRangeMin;
  // No split point closer than this to the points around it (metric lengths).
  double min_spacing = 0.6, min_spacing_anisotropic = 0.45;
  int anisotropic_smoothing = 2;  // length-smoothing sweeps after each split pass (anisotropic)
  double collapse_quality = 0.3;  // a collapse may lower the worst quality around to this
  bool flips = true;              // quality flips after each pass
};

struct RefineStats2 {
  size_t splits = 0, segment_splits = 0, collapses = 0, flips = 0;
  int passes = 0;
};

// fixed[v]: v may not move or go (the input's points); grows with the new points (0).
Status refine2(Triangulation& mesh, std::vector<uint8_t>& fixed, VertexMetrics& metrics, const RefineOptions2& options,
               RefineStats2* stats = nullptr);

// Share of the edges whose metric length lies in [1/sqrt2, sqrt2].
double share_in_range(const Triangulation& mesh, const VertexMetrics& metrics);

}  // namespace anitet::mesh2d

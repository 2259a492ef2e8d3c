// Stage 3c in 2D: CVT smoothing (the optimal-Delaunay-triangulation form of the 3D optimizer:
// each free point moves to the mean of its triangles' circumcentres, weighted by area times the
// metric's density det(M), when the worst triangle around it stays above a floor; in an
// anisotropic field, where the metric's directions turn and sizes change within an element,
// points move instead to lower the sum of log(metric length)^2 over their edges), quality flips (an edge flips when the worse of its two triangles gets better, quality
// measured in the metric), then a clean-up of the triangles still below a target angle: their
// points moved to the best of a few candidates, their shortest edge collapsed, or their
// circumcentre inserted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "mesh2d/metric2.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

struct OptimizeOptions2 {
  int sweeps = 6;               // CVT sweeps, each followed by flips
  bool cleanup = true;          // the clean-up of bad triangles
  double target_angle_deg = 30; // clean-up: isotropic triangles below this angle are bad
  double target_quality = 0.6;  // clean-up: anisotropic triangles below this metric quality
  int cleanup_rounds = 8;
  bool insert = true;           // the clean-up may insert circumcentres
  bool split_segments = false;  // and split segment pieces they encroach (Ruppert's rule)
  // Anisotropic fields: smoothing lowers the edges' log(length)^2 (a pattern search), keeping
  // triangles above min(their worst quality, this floor); no clean-up (it works on angles).
  double anisotropic_floor = 0.0;
};

struct OptimizeStats2 {
  size_t moves = 0, flips = 0, cleanup_moves = 0, cleanup_collapses = 0, cleanup_inserts = 0;
  size_t bad_left = 0;  // triangles with a free point still below the target
};

Status optimize2(Triangulation& mesh, std::vector<uint8_t>& fixed, VertexMetrics& metrics,
                 const OptimizeOptions2& options, OptimizeStats2* stats = nullptr);

// One sweep of metric-length smoothing (anisotropic fields): each free point moves by a pattern
// search to lower the sum over its edges of log(length)^2, its triangles staying valid and above
// min(their worst quality, floor). Returns the points moved.
size_t length_smoothing(Triangulation& mesh, std::vector<uint8_t>& fixed, VertexMetrics& metrics, double floor);

// Flips edges until no flip raises the worse quality of the two triangles, from a work list of
// the `seeds` triangles (null: all) and the triangles of each flip made (at most `rounds` visits
// per triangle of the list on average); returns the flips made.
size_t quality_flips(Triangulation& mesh, const VertexMetrics& metrics, int rounds = 20,
                     const std::vector<uint32_t>* seeds = nullptr);

}  // namespace anitet::mesh2d

// Anisotropic mesh adaptation (issue 46): a volume mesh and a metric in, a mesh whose edges have
// unit length in the metric and whose tets are regular in it out, by local operations on the
// given mesh (the way Mmg, refine and Feflo.a work): edges longer than sqrt 2 in the metric split,
// shorter than 1/sqrt 2 collapsed, edge and face swaps and vertex moves raising the worst quality
// in the metric, in cycles until few edges change. The output can be the input of the next call:
// a solver's adaptation loop runs with no other step.
//
// The surface is adapted with the volume (AdaptOptions::keep_surface off): its edges split,
// collapsed and swapped and its points moved to the metric like the volume's, every new or moved
// boundary point placed on the smooth surface through the input's boundary points and normals
// (surface_geometry.hpp), so curved walls become smoother, not faceted. Ridges (dihedral angle
// over ridge_angle_deg, borders between patch labels, edges of three or more boundary faces) are
// features: their points move along the ridge curve only, and corners (the ends of ridges, points
// where a ridge turns by more than ridge_angle_deg) never move. Patch labels stay with the faces.
// With keep_surface every input boundary triangle is a face of the output and no point is added,
// moved or removed on the surface (the boundary-constrained mode).
//
// The metric: one tensor (or size) per input vertex, interpolated at new points in log-Euclidean
// space in the input mesh (metric/field_transfer's rule), or a SizingField evaluated anywhere.
// Measures (core/metric_measures.hpp) are the UGAWG benchmark's. Single-threaded; deterministic.
// Errors as values (no exception leaves this module).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/sizing.hpp"
#include "core/metric_measures.hpp"
#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

struct AdaptOptions {
  bool keep_surface = false;     // the input's boundary triangles kept exactly
  double ridge_angle_deg = 45.0; // a dihedral angle between boundary faces over this: a ridge
  double split_length = kUnitRangeMax;    // edges longer than this are split
  double collapse_length = kUnitRangeMin;  // edges shorter than this are collapsed
  int max_cycles = 30;           // refinement/coarsening cycles at most
  int optimize_cycles = 3;       // swap and smoothing sweeps after them
  // AdaptMesh::check() of the working mesh after every sweep, a broken mesh an Error::Internal
  // naming the sweep (costly: for tests and debugging).
  bool check_each_sweep = false;
  // Called between sweeps with what runs and the fraction done (a rough estimate); returning
  // false cancels (Error::Cancelled). May be empty.
  std::function<bool(const std::string& stage, double fraction)> progress;
  // Called with one line per sweep (counts, tets, time), when set.
  std::function<void(const std::string& line)> log;
};

struct AdaptStats {
  size_t vertices_in = 0, tets_in = 0, vertices_out = 0, tets_out = 0;
  size_t boundary_triangles_in = 0, boundary_triangles_out = 0;
  size_t ridge_edges = 0, corners = 0;  // features found in the input
  int cycles = 0;
  size_t splits = 0, surface_splits = 0, collapses = 0, surface_collapses = 0;
  size_t swaps = 0, surface_swaps = 0, moves = 0, surface_moves = 0;
  size_t split_refused = 0, collapse_refused = 0;
  size_t splits_in_thirds = 0;  // splits cut at a third of the edge, not its midpoint (split.cpp)
  // Seconds: setup (checks, adjacency, features), each operation, output.
  double seconds_setup = 0, seconds_split = 0, seconds_collapse = 0, seconds_swap = 0, seconds_smooth = 0,
         seconds_output = 0, seconds_total = 0;
};

struct AdaptResult {
  VolumeMesh mesh;  // tets, regions, boundary triangles with their labels; vertex_metric: the
                    // metric at its vertices (6 per vertex)
  AdaptStats stats;
};

// The metric at the input's vertices: `vertex_metric` holds 1 (a size h > 0) or 6 (an SPD tensor
// xx xy yy xz yz zz) values per vertex of `in`. Errors: Error::InvalidArgument for a count that
// is not one record per vertex, a size <= 0 or a tensor that is not SPD (the message names the
// vertex, 1-based), an inverted or flat tet (named, 1-based), a face of three tets; EmptyInput
// without tets; Cancelled when the progress callback says so.
Result<AdaptResult> adapt_mesh(const VolumeMesh& in, const std::vector<double>& vertex_metric,
                               const AdaptOptions& options = {});
// The same with the metric of a field (a .vdb's, an analytic one) wherever a point goes.
Result<AdaptResult> adapt_mesh(const VolumeMesh& in, const SizingField& field, const AdaptOptions& options = {});

}  // namespace anitet

// The quality report of a tetrahedral mesh, optionally against the input surface it must keep.
// Validity decisions are exact (orient3d sign, exact point-on-triangle tests); shape measures are
// floating point (tet_measures.hpp). Field names follow /work/shared/tools/meshcheck.py, whose
// JSON keys the report's JSON reuses where they mean the same thing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

struct QualityOptions {
  // Relative tolerance (times the input surface's largest |coordinate|) for matching mesh
  // vertices to input vertices that were written with fewer digits; exact matches come first.
  double match_tolerance = 1e-9;
  int histogram_bins = 20;
  bool parallel = true;  // TBB over tets and vertices
  // Mesh vertices that lie exactly on the input surface (other than the input's own vertices)
  // are listed up to this many (all are counted).
  size_t max_listed = 10;
};

struct Stats {
  size_t count = 0;
  double mean = 0.0, min = 0.0, p01 = 0.0, max = 0.0;  // p01: 1st percentile, numpy's linear rule
};

struct QualitySplit {  // quality of a subset of the tets
  size_t tets = 0;
  Stats radius_ratio;
  Stats mean_ratio;
  double min_dihedral_deg = 0.0;
  double good_fraction = 0.0;  // radius ratio > 0.4
  double bad_fraction = 0.0;   // radius ratio < 0.1
};

struct RegionQuality {  // the tets of one region (VolumeMesh::region)
  int32_t region = 0;
  QualitySplit quality;
};

struct SurfaceMatchReport {
  bool present = false;  // an input surface was given
  size_t input_vertices = 0;
  size_t input_triangles = 0;   // distinct (as vertex sets)
  size_t matched_exact = 0;     // mesh vertices equal to an input vertex, coordinate for coordinate
  size_t matched_tolerance = 0; // matched only within the tolerance
  double tolerance_abs = 0.0;   // the absolute tolerance used
  size_t input_vertices_missing = 0;  // input vertices no mesh vertex matched
  size_t input_triangles_missing = 0; // input triangles that are not boundary faces of the mesh
  size_t boundary_faces_not_in_input = 0;
  size_t steiner_points_on_boundary = 0;  // boundary-face vertices that are no input vertex
  // Mesh vertices (used by a tet, not an input vertex) lying exactly on a closed input triangle.
  size_t vertices_on_input_surface = 0;
  std::vector<uint32_t> on_surface_examples;     // their mesh ids (at most max_listed)
  std::vector<uint32_t> on_surface_triangles;    // an input triangle each lies on
  std::vector<uint32_t> missing_triangle_examples;  // input triangle ids
  double surface_volume = 0.0;   // |enclosed volume| of the input (sum of signed tet volumes)
  double volume_rel_error = 0.0; // | |surface volume| - mesh volume | / |surface volume|
  double input_triangle_quality_min = 0.0;  // 2*sqrt(3)*|n| / sum l^2 (1 for equilateral)
  bool boundary_constrained = false;
  QualitySplit touching_surface;  // tets with a vertex that is an input vertex
  QualitySplit interior;          // the others
};

// The UGAWG measures (core/metric_measures.hpp) of a mesh that carries a metric
// (VolumeMesh::vertex_metric: a size or a tensor per vertex).
struct MetricQuality {
  bool present = false;
  size_t edges = 0;
  Stats edge_length;            // metric edge length (l_a - l_b) / ln(l_a / l_b)
  double in_range = 0.0;        // share of the edges with a length in [1/sqrt 2, sqrt 2]
  double shorter = 0.0, longer = 0.0;  // shares below and above that range
  // Histogram of the edge lengths: length_histogram[i] counts lengths in
  // [length_bin_edges[i], length_bin_edges[i + 1]) (the last bin open above).
  std::vector<double> length_bin_edges;
  std::vector<size_t> length_histogram;
  Stats mean_ratio;  // per tet, in the metric of its finest corner (largest det)
  std::vector<size_t> mean_ratio_histogram;  // over [0, 1], histogram_bins equal bins
};

struct QualityReport {
  size_t vertices = 0;
  size_t tets = 0;
  size_t unused_vertices = 0;
  size_t nonpositive_tets = 0;  // exact orient3d <= 0
  size_t inverted_tets = 0;     // exact orient3d < 0
  size_t flat_tets = 0;         // exact orient3d == 0
  // Valid (exact orient3d > 0) but flat to rounding: a double evaluation of the volume (a
  // solver's, a checker's) could find it zero or negative (predicates::orient3d_certified).
  size_t rounding_flat_tets = 0;
  std::vector<uint32_t> nonpositive_examples;  // tet ids (at most max_listed)
  size_t faces_shared_by_more_than_two = 0;
  size_t boundary_faces = 0;
  bool valid = false;  // no non-positive tet and no face shared by more than two tets
  double volume = 0.0; // sum of signed tet volumes

  Stats radius_ratio;
  Stats mean_ratio;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double dihedral_p01_deg = 0.0;  // 1st percentile of the per-tet minimum dihedral
  double good_fraction = 0.0;     // radius ratio > 0.4
  double bad_fraction = 0.0;      // radius ratio < 0.1
  size_t tets_dihedral_lt_5deg = 0;
  size_t tets_dihedral_lt_10deg = 0;
  std::vector<size_t> rr_histogram;  // radius ratio over [0, 1] in equal bins (1.0 in the last)
  // Quality per region, in increasing region order, only when the mesh has two regions or more
  // (a boundary layer is a region of its own: its thin tets are meant to be flat).
  std::vector<RegionQuality> by_region;

  SurfaceMatchReport surface;
  MetricQuality metric;  // when the mesh carries a vertex metric
  double seconds = 0.0;  // time spent computing
};

// The report. input_surface may be null. Fails (InvalidArgument / BadIndex / NonFiniteCoordinate)
// only when the mesh itself cannot be measured: a tet refers to a vertex that does not exist, or
// a used coordinate is NaN/Inf, or its vertex metric has a value count other than 1 or 6 per
// vertex, a size <= 0 or a tensor that is not SPD (the vertex named, 1-based); an empty mesh
// gives a report with zero tets. With a vertex metric, report.metric has the UGAWG measures.
Result<QualityReport> compute_quality_report(const VolumeMesh& mesh,
                                             const SurfaceMesh* input_surface,
                                             const QualityOptions& options = {});

// A readable multi-line report with a text histogram.
std::string quality_report_text(const QualityReport& report);
// Its part on the metric (the UGAWG measures and their histograms), as text and as the JSON
// report's "metric" object.
std::string metric_quality_text(const MetricQuality& metric, bool histograms = true);
std::string metric_quality_json(const MetricQuality& metric, int indent = 1);
// The report as a JSON object (meshcheck.py's keys where they mean the same), pretty-printed.
std::string quality_report_json(const QualityReport& report, int indent = 1);
// The radius-ratio histogram as CSV (lo,hi,count), as meshcheck.py --hist writes it.
std::string quality_histogram_csv(const QualityReport& report);

}  // namespace anitet

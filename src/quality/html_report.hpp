// The quality report as one self-contained HTML page (inline SVG and CSS, no script, no network):
// the summary table, histograms of the radius ratio, of every dihedral angle and of the edge
// lengths (all tets and tets touching the boundary), and three cut views (the tets crossed by
// the axis-aligned planes, drawn as their cross-sections and coloured by radius ratio).
//
// Everything is binned in one parallel pass over the tets (plus one over the edges), and each
// cut view draws at most max_polygons_per_view cross-sections, so the page of a 1M-tet mesh
// takes about a second.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "quality/quality_report.hpp"

namespace anitet {

struct HtmlReportOptions {
  std::string title = "anitet quality report";  // the page title (e.g. the mesh file name)
  std::string mesh_name;                         // shown in the table; may be empty
  std::string surface_name;                      // idem
  // Cut plane positions, as fractions of the mesh bounding box along x, y, z (0.5: the centre).
  std::array<double, 3> cut = {0.5, 0.5, 0.5};
  // When more tets cross a plane, the view draws the ones nearest the centre of the cut and says so.
  size_t max_polygons_per_view = 25000;
  int quality_bins = 20;   // radius ratio and mean ratio over [0, 1]
  int dihedral_bins = 36;  // dihedral angles over [0, 180] degrees
  int edge_bins = 30;      // edge lengths over [0, longest]
  // Rows of a "Meshing run" table (name, value as plain text), e.g. the stage timers of the run
  // that made the mesh; none: no such table.
  std::vector<std::pair<std::string, std::string>> run_rows;
};

struct HtmlReport {
  QualityReport report;  // the same report compute_quality_report gives
  std::string html;
  std::array<size_t, 3> cut_polygons_total = {0, 0, 0};  // tets crossed by each plane
  std::array<size_t, 3> cut_polygons_drawn = {0, 0, 0};
  size_t boundary_tets = 0;  // tets with a vertex on a boundary face of the mesh
  size_t edges = 0;
  bool metric_edge_lengths = false;  // the mesh carried a vertex metric: lengths are in it
  double seconds_quality = 0.0;      // the report itself
  double seconds_html = 0.0;         // histograms, cuts and the page
};

// Measures the mesh and writes the page. Fails like compute_quality_report, or with
// InvalidArgument for a cut fraction outside [0, 1] or a bin count < 1.
Result<HtmlReport> quality_report_html(const VolumeMesh& mesh, const SurfaceMesh* input_surface,
                                       const QualityOptions& quality_options,
                                       const HtmlReportOptions& html_options);

}  // namespace anitet

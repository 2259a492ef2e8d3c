// Internal pieces of the quality report shared by its .cpp files.
#pragma once

#include <cstdint>
#include <vector>

#include "quality/quality_report.hpp"

namespace anitet::quality_detail {

// Per-tet measures of the whole mesh, index = tet id.
struct TetData {
  std::vector<double> volume, radius_ratio, mean_ratio, min_dihedral;
  std::vector<double> max_dihedral_key;  // tet_measures_keyed's key: max_dihedral_from_key gives the angle
  std::vector<int8_t> orient;  // exact orient3d sign; 2: positive, not certified in doubles
};

// Statistics of the values. Empty gives zeros.
Stats make_stats(const std::vector<double>& values);
// The same of the values[i] whose select[i] == value (in index order).
Stats make_stats_where(const std::vector<double>& values, const std::vector<uint8_t>& select, uint8_t value);

// Quality of the tets whose select flag is set.
QualitySplit split_quality(const TetData& data, const std::vector<uint8_t>& select, uint8_t value);

// Fills out.surface: vertex matching, missing/extra boundary faces, Steiner points, exact
// on-surface vertices, volumes and the touching/interior split. boundary_faces holds 3 sorted
// vertex ids per boundary face; used marks the vertices used by a tet.
void match_surface(const VolumeMesh& mesh, const SurfaceMesh& surface,
                   const std::vector<uint32_t>& boundary_faces, const std::vector<uint8_t>& used,
                   const TetData& data, const QualityOptions& options, QualityReport& out);

// compute_quality_report, keeping the per-tet measures (data) and the boundary faces (3 sorted
// vertex ids each) for callers that draw more from them (html_report.cpp).
Result<QualityReport> compute_quality_report_keep(const VolumeMesh& mesh, const SurfaceMesh* input_surface,
                                                  const QualityOptions& options, TetData& data,
                                                  std::vector<uint32_t>& boundary);

// The UGAWG measures of a mesh with a vertex metric (1 or 6 values per vertex) into `out`;
// nothing without one. Errors as compute_quality_report says.
Status measure_metric(const VolumeMesh& mesh, int histogram_bins, bool parallel, MetricQuality& out);

}  // namespace anitet::quality_detail

// Text, JSON and CSV forms of the quality report.
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "quality/quality_report.hpp"

namespace anitet {

namespace {

std::string fmt(const char* format, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

nlohmann::ordered_json stats_json(const Stats& s) {
  return {{"mean", s.mean}, {"min", s.min}, {"p01", s.p01}, {"max", s.max}};
}

nlohmann::ordered_json split_json(const QualitySplit& q) {
  return {{"tets", q.tets},
          {"radius_ratio", stats_json(q.radius_ratio)},
          {"mean_ratio", stats_json(q.mean_ratio)},
          {"min_dihedral_deg", q.min_dihedral_deg},
          {"good_fraction_rr_gt_0.4", q.good_fraction},
          {"bad_fraction_rr_lt_0.1", q.bad_fraction}};
}

nlohmann::ordered_json metric_json(const MetricQuality& m) {
  nlohmann::ordered_json hist = nlohmann::ordered_json::array();
  for (size_t i = 0; i < m.length_histogram.size(); ++i) {
    const bool last = i + 1 == m.length_bin_edges.size();
    hist.push_back({{"lo", m.length_bin_edges[i]},
                    {"hi", last ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(m.length_bin_edges[i + 1])},
                    {"count", m.length_histogram[i]}});
  }
  return {{"edges", m.edges},
          {"edge_length", stats_json(m.edge_length)},
          {"edges_in_range", m.in_range},
          {"edges_shorter", m.shorter},
          {"edges_longer", m.longer},
          {"edge_length_histogram", hist},
          {"mean_ratio", stats_json(m.mean_ratio)},
          {"mean_ratio_histogram", m.mean_ratio_histogram}};
}

double bin_edge(size_t i, size_t bins) { return double(i) / double(bins); }

std::string stats_line(const char* name, const Stats& s) {
  return std::string(name) + "mean " + fmt("%.6f", s.mean) + "  min " + fmt("%.6f", s.min) +
         "  p01 " + fmt("%.6f", s.p01) + "  max " + fmt("%.6f", s.max) + "\n";
}

std::string split_line(const char* name, const QualitySplit& q) {
  if (q.tets == 0) return std::string(name) + "no tets\n";
  return std::string(name) + std::to_string(q.tets) + " tets, radius ratio mean " +
         fmt("%.4f", q.radius_ratio.mean) + " min " + fmt("%.4f", q.radius_ratio.min) +
         ", min dihedral " + fmt("%.2f", q.min_dihedral_deg) + " deg, good " +
         fmt("%.2f", 100.0 * q.good_fraction) + "%, bad " + fmt("%.2f", 100.0 * q.bad_fraction) + "%\n";
}

template <class T>
std::string id_list(const std::vector<T>& ids, size_t total) {
  std::string s;
  for (size_t i = 0; i < ids.size(); ++i) s += (i ? ", " : "") + std::to_string(ids[i]);
  if (total > ids.size()) s += ", ...";
  return s;
}

}  // namespace

std::string metric_quality_text(const MetricQuality& m, bool histograms) {
  std::ostringstream os;
  os << "in the metric (UGAWG measures): " << m.edges << " edges, " << fmt("%.2f", 100.0 * m.in_range)
     << "% of lengths in [1/sqrt2, sqrt2] (" << fmt("%.2f", 100.0 * m.shorter) << "% shorter, "
     << fmt("%.2f", 100.0 * m.longer) << "% longer)\n";
  os << stats_line("  edge length ", m.edge_length);
  os << stats_line("  mean ratio  ", m.mean_ratio);
  if (!histograms) return os.str();
  os << "  edge length histogram:\n";
  const size_t peak = std::max<size_t>(1, *std::max_element(m.length_histogram.begin(), m.length_histogram.end()));
  constexpr size_t kWidth = 40;
  for (size_t i = 0; i < m.length_histogram.size(); ++i) {
    const size_t c = m.length_histogram[i];
    const size_t bar = (c * kWidth + peak - 1) / peak;
    const std::string hi = i + 1 < m.length_bin_edges.size() ? fmt("%-6.4g", m.length_bin_edges[i + 1]) : "      ";
    os << "    " << fmt("%6.4g", m.length_bin_edges[i]) << "-" << hi << " |" << std::string(bar, '#')
       << std::string(kWidth - bar, ' ') << " " << c << "\n";
  }
  os << "  mean ratio histogram:\n";
  const size_t n = m.mean_ratio_histogram.size();
  const size_t qpeak = std::max<size_t>(1, *std::max_element(m.mean_ratio_histogram.begin(), m.mean_ratio_histogram.end()));
  for (size_t i = 0; i < n; ++i) {
    const size_t c = m.mean_ratio_histogram[i];
    const size_t bar = (c * kWidth + qpeak - 1) / qpeak;
    os << "    " << fmt("%.2f", bin_edge(i, n)) << "-" << fmt("%.2f", bin_edge(i + 1, n)) << " |" << std::string(bar, '#')
       << std::string(kWidth - bar, ' ') << " " << c << "\n";
  }
  return os.str();
}

std::string metric_quality_json(const MetricQuality& m, int indent) { return metric_json(m).dump(indent); }

std::string quality_report_json(const QualityReport& r, int indent) {
  nlohmann::ordered_json j;
  j["vertices"] = r.vertices;
  j["tets"] = r.tets;
  j["unused_vertices"] = r.unused_vertices;
  j["nonpositive_tets"] = r.nonpositive_tets;
  j["inverted_tets"] = r.inverted_tets;
  j["flat_tets"] = r.flat_tets;
  j["rounding_flat_tets"] = r.rounding_flat_tets;
  j["nonpositive_tet_examples"] = r.nonpositive_examples;
  j["faces_shared_by_more_than_two"] = r.faces_shared_by_more_than_two;
  j["boundary_faces"] = r.boundary_faces;
  j["volume"] = r.volume;
  j["quality"] = {{"radius_ratio", stats_json(r.radius_ratio)},
                  {"mean_ratio", stats_json(r.mean_ratio)},
                  {"min_dihedral_deg", r.min_dihedral_deg},
                  {"max_dihedral_deg", r.max_dihedral_deg},
                  {"dihedral_p01_deg", r.dihedral_p01_deg},
                  {"good_fraction_rr_gt_0.4", r.good_fraction},
                  {"bad_fraction_rr_lt_0.1", r.bad_fraction},
                  {"tets_dihedral_lt_5deg", r.tets_dihedral_lt_5deg},
                  {"tets_dihedral_lt_10deg", r.tets_dihedral_lt_10deg}};
  j["radius_ratio_histogram"] = r.rr_histogram;
  if (!r.by_region.empty()) {
    nlohmann::ordered_json regions = nlohmann::ordered_json::array();
    for (const RegionQuality& q : r.by_region) {
      nlohmann::ordered_json one = {{"region", q.region}};
      one.update(split_json(q.quality));
      regions.push_back(one);
    }
    j["quality_by_region"] = regions;
  }
  const SurfaceMatchReport& s = r.surface;
  if (s.present) {
    j["input_vertices"] = s.input_vertices;
    j["input_triangles"] = s.input_triangles;
    j["vertex_match"] = {{"mode", s.matched_tolerance > 0 ? "tolerance" : "exact"},
                         {"exact", s.matched_exact},
                         {"tolerance", s.matched_tolerance},
                         {"tolerance_abs", s.tolerance_abs}};
    j["input_vertices_missing"] = s.input_vertices_missing;
    j["input_triangles_missing"] = s.input_triangles_missing;
    j["input_triangles_missing_examples"] = s.missing_triangle_examples;
    j["boundary_faces_not_in_input"] = s.boundary_faces_not_in_input;
    j["steiner_points_on_boundary"] = s.steiner_points_on_boundary;
    j["vertices_on_input_surface"] = s.vertices_on_input_surface;
    nlohmann::ordered_json on = nlohmann::ordered_json::array();
    for (size_t i = 0; i < s.on_surface_examples.size(); ++i) {
      on.push_back({{"vertex", s.on_surface_examples[i]}, {"input_triangle", s.on_surface_triangles[i]}});
    }
    j["vertices_on_input_surface_examples"] = on;
    j["surface_volume"] = s.surface_volume;
    j["volume_rel_error"] = s.volume_rel_error;
    j["boundary_constrained"] = s.boundary_constrained;
    if (s.touching_surface.tets > 0) j["quality_touching_surface"] = split_json(s.touching_surface);
    if (s.interior.tets > 0) j["quality_interior"] = split_json(s.interior);
    j["input_triangle_quality_min"] = s.input_triangle_quality_min;
  }
  if (r.metric.present) j["metric"] = metric_json(r.metric);
  j["valid"] = r.valid;
  j["seconds"] = r.seconds;
  return j.dump(indent);
}

std::string quality_histogram_csv(const QualityReport& r) {
  std::string out = "lo,hi,count\n";
  const size_t n = r.rr_histogram.size();
  for (size_t i = 0; i < n; ++i) {
    out += fmt("%.2f", bin_edge(i, n)) + "," + fmt("%.2f", bin_edge(i + 1, n)) + "," +
           std::to_string(r.rr_histogram[i]) + "\n";
  }
  return out;
}

std::string quality_report_text(const QualityReport& r) {
  std::ostringstream os;
  os << "mesh: " << r.vertices << " vertices (" << r.unused_vertices << " unused), " << r.tets
     << " tets, " << r.boundary_faces << " boundary faces\n";
  os << "validity: " << (r.valid ? "VALID" : "INVALID") << " (exact orientation: " << r.nonpositive_tets
     << " non-positive tets [" << r.inverted_tets << " inverted, " << r.flat_tets << " flat]; "
     << r.faces_shared_by_more_than_two << " faces shared by more than two tets; " << r.rounding_flat_tets
     << " tets valid but flat to double rounding)\n";
  if (r.nonpositive_tets > 0) {
    os << "  non-positive tets: " << id_list(r.nonpositive_examples, r.nonpositive_tets) << "\n";
  }
  os << "volume: " << fmt("%.10g", r.volume) << "\n";
  if (r.tets > 0) {
    os << stats_line("radius ratio  ", r.radius_ratio);
    os << stats_line("mean ratio    ", r.mean_ratio);
    os << "dihedral      min " << fmt("%.4f", r.min_dihedral_deg) << " deg  p01 "
       << fmt("%.4f", r.dihedral_p01_deg) << " deg  max " << fmt("%.4f", r.max_dihedral_deg) << " deg\n";
    os << "good (rr > 0.4) " << fmt("%.2f", 100.0 * r.good_fraction) << "%   bad (rr < 0.1) "
       << fmt("%.2f", 100.0 * r.bad_fraction) << "%\n";
    os << "tets with min dihedral < 5 deg: " << r.tets_dihedral_lt_5deg
       << ", < 10 deg: " << r.tets_dihedral_lt_10deg << "\n";
    os << "radius ratio histogram:\n";
    const size_t n = r.rr_histogram.size();
    const size_t peak = std::max<size_t>(1, *std::max_element(r.rr_histogram.begin(), r.rr_histogram.end()));
    constexpr size_t kWidth = 50;
    for (size_t i = 0; i < n; ++i) {
      const size_t c = r.rr_histogram[i];
      size_t bar = (c * kWidth + peak - 1) / peak;  // any non-zero bin shows at least one mark
      os << "  " << fmt("%.2f", bin_edge(i, n)) << "-" << fmt("%.2f", bin_edge(i + 1, n)) << " |"
         << std::string(bar, '#') << std::string(kWidth - bar, ' ') << " " << c << "\n";
    }
    for (const RegionQuality& q : r.by_region) {
      const std::string name = "region " + std::to_string(q.region) + ": ";
      os << split_line(name.c_str(), q.quality);
    }
  }
  if (r.metric.present) os << metric_quality_text(r.metric);
  const SurfaceMatchReport& s = r.surface;
  if (s.present) {
    os << "input surface: " << s.input_vertices << " vertices, " << s.input_triangles << " triangles\n";
    os << "  vertex match: " << s.matched_exact << " exact";
    if (s.matched_tolerance > 0) {
      os << " + " << s.matched_tolerance << " within " << fmt("%.3g", s.tolerance_abs)
         << " (mesh written with fewer digits)";
    }
    os << "; input vertices not in the mesh: " << s.input_vertices_missing << "\n";
    os << "  input triangles missing from the boundary: " << s.input_triangles_missing;
    if (s.input_triangles_missing > 0) {
      os << " (triangles " << id_list(s.missing_triangle_examples, s.input_triangles_missing) << ")";
    }
    os << "\n  boundary faces not in the input: " << s.boundary_faces_not_in_input << "\n";
    os << "  Steiner points on the boundary: " << s.steiner_points_on_boundary << "\n";
    os << "  other mesh vertices exactly on the input surface: " << s.vertices_on_input_surface;
    for (size_t i = 0; i < s.on_surface_examples.size(); ++i) {
      os << (i ? ", " : " (") << "vertex " << s.on_surface_examples[i] << " on triangle "
         << s.on_surface_triangles[i];
    }
    if (!s.on_surface_examples.empty()) os << (s.vertices_on_input_surface > s.on_surface_examples.size() ? ", ...)" : ")");
    os << "\n  enclosed volume " << fmt("%.10g", s.surface_volume) << ", relative volume error "
       << fmt("%.3e", s.volume_rel_error) << "\n";
    os << "  worst input triangle quality " << fmt("%.4f", s.input_triangle_quality_min) << "\n";
    os << "  boundary constrained: " << (s.boundary_constrained ? "YES" : "NO") << "\n";
    os << split_line("  touching the surface: ", s.touching_surface);
    os << split_line("  interior:             ", s.interior);
  }
  os << "computed in " << fmt("%.3f", r.seconds) << " s\n";
  return os.str();
}

}  // namespace anitet

#include "pipeline/result_json.hpp"

#include <nlohmann/json.hpp>

namespace anitet {

std::string mesher_result_json(const MesherResult& r, int indent) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageReport& s : r.stages) stages.push_back({{"stage", s.name}, {"seconds", s.seconds}, {"tets", s.tets}, {"peak_bytes", s.peak_bytes}});
  const BoundaryLayerReport& bl = r.boundary_layer;
  nlohmann::json out = {
      {"seconds", r.seconds},
      {"stages", stages},
      {"tets_per_second", r.seconds > 0 ? double(r.mesh.num_tets()) / r.seconds : 0.0},
      {"estimated_tets", r.estimated_tets},
      {"layers", {{"layers_used", r.layers_used}, {"retries", r.layers_retries}}},
      {"recovery",
       {{"steiner_on_s1_edges", r.recovery.steiner_on_edges},
        {"steiner_on_s1_faces", r.recovery.steiner_on_faces},
        {"strategy", r.recovery.strategy},
        {"strategy_name", recovery_strategy_name(r.recovery.strategy)},
        {"seconds",
         {{"delaunay", r.recovery.seconds_delaunay},
          {"recovery", r.recovery.seconds_recovery},
          {"carving", r.recovery.seconds_carve}}}}},
      {"coupling", {{"edge_split_tets", r.couple.edge_split_tets}, {"faces_reconed", r.couple.faces_reconed}}},
      {"refine",
       {{"passes", r.refine.passes},
        {"stopped_at_pass_cap", r.refine.stopped_at_pass_cap},
        {"metric_not_spd", r.refine.metric_not_spd},
        {"splits", r.refine.splits},
        {"parallel_splits", r.refine.parallel_splits},
        {"collapses", r.refine.collapses},
        {"length_mean", r.refine.length_mean},
        {"length_in_range", r.refine.length_in_range},
        {"anisotropic_cycles", r.anisotropic_cycles},
        {"seconds",
         {{"edge_lists", r.refine.seconds_edges},
          {"split_choice", r.refine.seconds_choice},
          {"insertion", r.refine.seconds_insertion},
          {"collapses", r.refine.seconds_collapses},
          {"metric_flips", r.refine.seconds_flips}}}}},
      {"metric_quality",
       {{"tets", r.metric_quality.tets},
        {"radius_ratio_mean", r.metric_quality.mean},
        {"radius_ratio_min", r.metric_quality.min},
        {"below_0.1", r.metric_quality.below_01},
        {"below_0.4", r.metric_quality.below_04}}},
      {"boundary_layer",
       {{"layers", bl.layers},
        {"wall_vertices", bl.wall_vertices},
        {"tets", bl.tets},
        {"vertices", bl.vertices},
        {"full_columns", bl.full_columns},
        {"columns_reaching", bl.columns_reaching},
        {"nominal_columns", bl.nominal_columns},
        {"reduced_vertices", bl.reduced_vertices},
        {"reduced_share", r.layers.bl_reduced_share},
        {"first_height_min", bl.first_height_min},
        {"first_height_mean", bl.first_height_mean},
        {"first_height_max", bl.first_height_max},
        {"max_height_error", bl.max_height_error},
        {"growth_mean", bl.growth_mean},
        {"max_displacement", bl.max_displacement},
        {"layer_height_min", bl.layer_height_min},
        {"layer_height_mean", bl.layer_height_mean},
        {"layer_height_max", bl.layer_height_max},
        {"max_neighbour_growth", bl.max_neighbour_growth},
        {"dual_faces", bl.dual_faces},
        {"non_orthogonality_max", bl.non_orthogonality_max},
        {"non_orthogonality_mean", bl.non_orthogonality_mean},
        {"non_orthogonal_faces", bl.non_orthogonal_faces},
        {"skewness_max", bl.skewness_max},
        {"skew_faces", bl.skew_faces},
        {"transition_faces", bl.transition_faces},
        {"transition_ratio_mean", bl.transition_ratio_mean},
        {"transition_ratio_median", bl.transition_ratio_median},
        {"transition_ratio_p90", bl.transition_ratio_p90},
        {"transition_within_1_5", bl.transition_within_1_5},
        {"transition_edge_ratio_mean", bl.transition_edge_ratio_mean},
        {"stage1_seconds", r.layers.bl_seconds}}},
      {"optimize",
       {{"moves", r.optimize.moves},
        {"flips23", r.optimize.flips23},
        {"edge_removals", r.optimize.edge_removals},
        {"perturbations", r.optimize.perturbations},
        {"collapses", r.optimize.collapses},
        {"flat_found", r.optimize.flat_found},
        {"flat_left", r.optimize.flat_left},
        {"seconds",
         {{"setup", r.optimize.seconds_setup},
          {"cvt", r.optimize.seconds_cvt},
          {"flips", r.optimize.seconds_flips},
          {"slivers", r.optimize.seconds_slivers},
          {"certify", r.optimize.seconds_certify}}}}}};
  nlohmann::json slid = nlohmann::json::array();
  for (const SlidePatchChange& c : r.slide.changes)
    slid.push_back({{"label", c.label},
                    {"triangles_before", c.triangles_before},
                    {"triangles_after", c.triangles_after},
                    {"triangles_gained", int64_t(c.triangles_after) - int64_t(c.triangles_before)},
                    {"band_triangles", c.band_triangles},
                    {"dropped_vertices", c.dropped_vertices}});
  out["slide_patches"] = {{"patches", slid},
                          {"junction_vertices", r.slide.junction_vertices},
                          {"reduced_columns", r.slide.reduced_columns}};
  out["notices"] = nlohmann::json::array();
  for (const Notice& n : r.notices) out["notices"].push_back({{"kind", n.kind}, {"message", n.message}});
  return out.dump(indent);
}

}  // namespace anitet

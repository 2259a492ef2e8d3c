// `anitet mesh IN --stop-after layers -o OUT`: stage 1 alone. Writes T1 (the layers) to OUT with
// the input's triangles as boundary triangles under their own patch labels and S1 (the new
// front) under one extra label, S1 also as its own surface file, and prints the layers' figures
// and the quality report of T1 against the input.
#include <algorithm>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "core/sizing.hpp"
#include "exit_codes.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "layers/layers.hpp"
#include "layers/layers_check.hpp"
#include "pipeline/stage1.hpp"
#include "quality/quality_report.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

namespace {


nlohmann::json layers_json(const LayersOutput& r, const LayersCheck& check) {
  const LayersStats& s = r.stats;
  auto share = [](size_t part, size_t all) { return all ? double(part) / double(all) : 0.0; };
  nlohmann::json per_layer = nlohmann::json::array();
  for (const LayerStats& l : s.per_layer)
    per_layer.push_back({{"front_triangles_before", l.front_triangles_before},
                         {"face_tets", l.face_tets}, {"push_tets", l.push_tets},
                         {"halvings", l.halvings}, {"halved_columns", l.halved_columns},
                         {"boundary_layer", l.boundary_layer}, {"seconds", l.seconds}});
  return {{"tets", s.tets},
          {"s1_triangles", r.num_front_triangles()},
          {"new_vertices", s.new_vertices},
          {"face_tets", s.face_tets},
          {"push_tets", s.push_tets},
          {"faces", {{"tried", s.faces}, {"halved", s.faces_halved}, {"halvings", s.face_halvings},
                     {"max_halvings", s.max_face_halvings}, {"halved_share", share(s.faces_halved, s.faces)}}},
          {"pushes", {{"tried", s.pushes}, {"halved", s.pushes_halved}, {"halvings", s.push_halvings},
                      {"max_halvings", s.max_push_halvings}, {"halved_share", share(s.pushes_halved, s.pushes)},
                      {"deferred", s.deferred_pushes}, {"partial", s.partial_pushes},
                      {"by_two_tasks", s.task_pushes},
                      {"fallbacks", s.push_fallbacks}, {"stopped_vertices", s.stopped_vertices},
                      {"improved_vertices", s.improved_vertices}, {"smoothed_vertices", s.smoothed_vertices}}},
          {"epsilon_halving", {{"loops", s.halving_loops}, {"halved_columns", s.halved_columns},
                               {"halved_column_share", s.halved_column_share}}},
          {"boundary_layer", {{"layers", s.bl_layers}, {"wall_vertices", s.bl_wall_vertices},
                              {"pushes", s.bl_pushes}, {"reduced_pushes", s.bl_reduced_pushes},
                              {"reduced_vertices", s.bl_reduced_vertices},
                              {"reduced_share", s.bl_reduced_share},
                              {"max_height_error", s.bl_max_height_error},
                              {"min_height_ratio", s.bl_min_height_ratio},
                              {"seconds", s.bl_seconds}}},
          {"seconds", s.seconds},
          {"per_layer", per_layer},
          {"check", {{"ok", check.ok()}, {"mesh_valid", check.mesh_valid},
                     {"input_faces_present", check.input_faces_present},
                     {"boundary_is_s_and_s1", check.boundary_is_s_and_s1},
                     {"front_manifold", check.front_manifold}, {"front_off_input", check.front_off_input},
                     {"front_disjoint", check.front_disjoint},
                     {"volume_rel_error", check.volume_rel_error}, {"problems", check.problems}}}};
}

nlohmann::json worst_json(const WorstTets& w) {
  nlohmann::json tets = nlohmann::json::array();
  for (const WorstTet& t : w.tets)
    tets.push_back({{"tet", t.tet}, {"radius_ratio", t.radius_ratio}, {"layer", t.layer},
                    {"input_triangle", t.column}, {"input_triangle_quality", t.column_quality},
                    {"input_triangle_rank", t.column_rank}});
  return {{"tets", tets}, {"input_quality_min", w.input_quality_min},
          {"input_quality_median", w.input_quality_median}, {"median_rank", w.median_rank}};
}

}  // namespace

int run_mesh_layers(MeshArgs& args) {
  const std::string cmd = "anitet mesh";
  if (distributed_run()) {
    std::cerr << cmd << ": --stop-after layers is serial: run `anitet mesh`\n";
    return kExitNotImplemented;
  }
  if (const int code = check_output_paths(args); code != kExitOk) return code;
  CheckedSurface checked;
  if (const int code = load_and_validate("mesh", args.input, checked); code != kExitOk) return code;
  const int32_t front_label = front_patch_label(checked.surface);  // S1's patch in the output
  if (const int code = check_patch_names(args, checked, {front_label}); code != kExitOk) return code;

  LayersOptions options;
  options.layers = args.layers;
  options.scheme = args.layer_scheme == "faces" ? LayerScheme::kFacesThenPush : LayerScheme::kPushOnly;
  options.push_tasks_min_vertices = args.push_tasks_min_vertices;
  if (!args.bl_patches.empty()) {
    if (!(args.bl_first_height > 0.0)) {
      std::cerr << cmd << ": --bl-patches needs --bl-first-height (or --bl-yplus)\n";
      return kExitUsage;
    }
    options.boundary_layer.wall_patches.assign(args.bl_patches.begin(), args.bl_patches.end());
    options.boundary_layer.first_height = args.bl_first_height;
    options.boundary_layer.growth = args.bl_growth;
    options.boundary_layer.layers = args.bl_layers;
    options.boundary_layer.slide_patches.assign(args.bl_slide_patches.begin(), args.bl_slide_patches.end());
  }
  // With slide patches, stage 1 runs on the surface re-triangulated around the columns (as the
  // pipeline does).
  Result<Stage1Result> built = run_stage1(checked.surface, options);
  if (!built.ok()) {
    std::cerr << cmd << ": stage 1 (layers) failed on '" << args.input << "': " << built.status().message()
              << " [" << error_name(built.status().code()) << "]\n";
    return built.status().code() == Error::NotImplemented || built.status().code() == Error::InvalidArgument
               ? kExitUsage
               : kExitInternal;
  }
  const SurfaceMesh& surface = built->surface(checked.surface);
  const LayersOutput& r = built->layers;
  const LayersCheck& check = built->check;
  const VolumeMesh& vm = built->mesh;
  if (const int code = write_outputs(args, vm); code != kExitOk) return code;
  const std::string front_file = front_path(args.output);
  if (Status st = write_surface(front_surface(r), front_file); !st.ok()) {
    std::cerr << cmd << ": cannot write '" << front_file << "': " << st.message() << "\n";
    return kExitReadError;
  }

  Result<QualityReport> quality = compute_quality_report(vm, &surface);
  if (!quality.ok()) {
    std::cerr << cmd << ": cannot measure T1: " << quality.status().message() << "\n";
    return kExitInternal;
  }
  if (args.json) {
    nlohmann::json out = {{"input", args.input}, {"output", args.output}, {"front", front_file},
                          {"layers", options.layers}, {"scheme", args.layer_scheme},
                          {"stage1", layers_json(r, check)},
                          {"worst_tets", worst_json(worst_tets(surface, r, 10))},
                          {"quality", nlohmann::json::parse(quality_report_json(quality.value()))}};
    std::cout << out.dump(1) << "\n";
  } else if (!args.quiet) {
    const LayersStats& s = r.stats;
    std::cout << "stage 1 (layers): " << options.layers << " layer(s), scheme " << args.layer_scheme
              << ", " << s.tets << " tets, S1 " << r.num_front_triangles() << " triangles, "
              << s.seconds << " s\n"
              << "  pushes halved: " << s.pushes_halved << " of " << s.pushes << " (" << s.push_halvings
              << " halvings, at most " << s.max_push_halvings << "); vertices moved after their layer: "
              << s.improved_vertices << ", left in place: " << s.stopped_vertices
              << "; interior vertex moves after the last layer: " << s.smoothed_vertices;
    if (s.faces)
      std::cout << "; face tets halved: " << s.faces_halved << " of " << s.faces << " ("
                << s.face_halvings << " halvings)";
    std::cout << "\n  epsilon halving: " << s.halving_loops << " loops; columns (input triangles) "
              << "that needed it: " << s.halved_columns << " over " << s.per_layer.size()
              << " layer(s), " << 100.0 * s.halved_column_share << "%";
    if (s.bl_layers > 0)
      std::cout << "\n  boundary layer: " << s.bl_layers << " layers on " << s.bl_wall_vertices
                << " wall vertices (region " << options.boundary_layer.region << "), reduced vertices "
                << s.bl_reduced_vertices << " (" << 100.0 * s.bl_reduced_share << "%), reduced pushes "
                << s.bl_reduced_pushes << " of " << s.bl_pushes << ", max height error where not reduced "
                << s.bl_max_height_error << ", " << s.bl_seconds << " s";
    const WorstTets worst = worst_tets(surface, r, 10);
    if (!worst.tets.empty())
      std::cout << "\n  worst T1 tets: radius ratio " << worst.tets.front().radius_ratio << " (layer "
                << worst.tets.front().layer << ") on input triangle " << worst.tets.front().column
                << " of quality " << worst.tets.front().column_quality << " (input min "
                << worst.input_quality_min << ", median " << worst.input_quality_median
                << "); the 10 worst stand on input triangles of median quality rank "
                << 100.0 * worst.median_rank << "%";
    std::cout << "\n  audit: valid, every input triangle a face of T1, S1 closed and off S, volume error "
              << check.volume_rel_error << "\n"
              << "wrote T1 to " << args.output << " (S1 as patch " << front_label << "), S1 to "
              << front_file << "\n"
              << quality_report_text(quality.value());
  }
  return kExitOk;
}

}  // namespace anitet::cli

// anitet_layers_run: a developer driver for stage 1. Reads a surface, validates (and safely
// repairs) it, builds the layers, audits them (layers_check.hpp) and prints one JSON object;
// optionally writes T1 as a volume mesh (.mesh/.msh/.vtu) with S (patch 1) and S1 (patch 2) as
// boundary triangles, so that /work/shared/tools/meshcheck.py OUT --surface IN can cross-check it.
// Exit code: 0 when the layers were built and every check passed, 1 otherwise.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/sizing.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "layers/layers.hpp"
#include "layers/layers_check.hpp"
#include "validate/validate.hpp"

int main(int argc, char** argv) {
  using namespace anitet;
  CLI::App app{"Stage 1 of anitet: advancing-front layers along a surface"};
  std::string input, output;
  LayersOptions options;
  std::string scheme = "push";
  bool skip_check = false;
  bool skip_self_intersections = false;
  app.add_option("input", input, "surface file (.off .obj .stl .ply .mesh .msh)")->required();
  app.add_option("output", output, "write T1 here (.mesh .msh .vtu)");
  app.add_option("--layers", options.layers, "number of layers")->check(CLI::Range(1, 50));
  app.add_option("--scheme", scheme, "push (prism layers) or faces (paper: face tets then pushes)")
      ->check(CLI::IsMember({"push", "faces"}));
  app.add_option("--push-height", options.push_height, "push distance in sizes");
  app.add_option("--face-height", options.face_height, "face apex height, relative to regular");
  app.add_option("--max-halvings", options.max_halvings, "halving cap per tet or push");
  app.add_option("--shrink", options.shrink, "factor applied to a height that does not fit");
  app.add_option("--keep-margin", options.keep_margin, "visibility margin kept for neighbours");
  app.add_option("--smoothing", options.smoothing_passes, "tangential smoothing passes");
  bool fixed_height = false;
  app.add_flag("--fixed-height", fixed_height, "do not choose push heights by tet quality");
  app.add_flag("--no-check", skip_check, "skip the audit of the output");
  app.add_flag("--no-self-intersection-check", skip_self_intersections,
               "validate the input without the self-intersection search");
  CLI11_PARSE(app, argc, argv);
  options.choose_height = !fixed_height;
  options.scheme = scheme == "faces" ? LayerScheme::kFacesThenPush : LayerScheme::kPushOnly;

  nlohmann::json out;
  out["input"] = input;
  Result<SurfaceMesh> read = read_surface(input);
  if (!read.ok()) {
    out["error"] = read.status().message();
    std::cout << out.dump(1) << "\n";
    return 1;
  }
  SurfaceMesh surface = std::move(read).value();
  ValidationOptions vopt;
  vopt.check_self_intersections = !skip_self_intersections;
  ValidationReport report = validate_surface(surface, vopt);
  if (!report.ok()) {
    out["error"] = "invalid surface: " + report.status().message();
    std::cout << out.dump(1) << "\n";
    return 1;
  }
  out["triangles"] = surface.num_triangles();
  out["vertices"] = surface.num_vertices();

  IsotropicSurfaceSizing sizing(surface);
  Result<LayersOutput> built = build_layers(surface, sizing, options);
  if (!built.ok()) {
    out["error"] = std::string(error_name(built.status().code())) + ": " + built.status().message();
    std::cout << out.dump(1) << "\n";
    return 1;
  }
  const LayersOutput& r = built.value();
  const LayersStats& s = r.stats;
  out["layers"] = options.layers;
  out["scheme"] = scheme;
  out["tets"] = s.tets;
  out["s1_triangles"] = r.num_front_triangles();
  out["new_vertices"] = s.new_vertices;
  out["face_tets"] = s.face_tets;
  out["push_tets"] = s.push_tets;
  out["faces"] = {{"tried", s.faces}, {"halved", s.faces_halved}, {"halvings", s.face_halvings},
                  {"max_halvings", s.max_face_halvings},
                  {"halved_share", s.faces ? double(s.faces_halved) / double(s.faces) : 0.0}};
  out["pushes"] = {{"tried", s.pushes}, {"halved", s.pushes_halved}, {"halvings", s.push_halvings},
                   {"max_halvings", s.max_push_halvings},
                   {"halved_share", s.pushes ? double(s.pushes_halved) / double(s.pushes) : 0.0},
                   {"direction_fixes", s.direction_fixes},
                   {"lookahead_halvings", s.lookahead_halvings},
                   {"replans", s.replans},
                   {"deferred", s.deferred_pushes},
                   {"partial", s.partial_pushes}};
  out["fit_tests"] = s.fit_tests;
  out["fit_candidates"] = s.fit_candidates;
  out["tri_tests"] = s.tri_tests;
  out["seconds"] = s.seconds;
  nlohmann::json per_layer = nlohmann::json::array();
  for (const LayerStats& l : s.per_layer)
    per_layer.push_back({{"front_before", l.front_triangles_before}, {"face_tets", l.face_tets},
                         {"push_tets", l.push_tets}, {"seconds", l.seconds}});
  out["per_layer"] = per_layer;
  const LayersQuality q = layers_quality(r);
  out["radius_ratio"] = {{"mean", q.mean}, {"min", q.min}, {"below_0.05", q.below_0_05},
                         {"below_0.1", q.below_0_1}, {"above_0.4", q.above_0_4}};
  bool ok = true;
  if (!skip_check) {
    const LayersCheck c = check_layers(surface, r);
    out["check"] = {{"ok", c.ok()},
                    {"mesh_valid", c.mesh_valid},
                    {"input_faces_present", c.input_faces_present},
                    {"boundary_is_s_and_s1", c.boundary_is_s_and_s1},
                    {"front_manifold", c.front_manifold},
                    {"front_off_input", c.front_off_input},
                    {"front_disjoint", c.front_disjoint},
                    {"volume_rel_error", c.volume_rel_error},
                    {"problems", c.problems}};
    ok = c.ok();
  }
  if (!output.empty()) {
    VolumeMesh vm = r.mesh.to_volume_mesh(false);
    for (size_t t = 0; t < surface.num_triangles(); ++t) {
      vm.bnd_tri.insert(vm.bnd_tri.end(), &surface.tri[3 * t], &surface.tri[3 * t] + 3);
      vm.bnd_patch.push_back(1);
    }
    vm.bnd_tri.insert(vm.bnd_tri.end(), r.front_tri.begin(), r.front_tri.end());
    vm.bnd_patch.insert(vm.bnd_patch.end(), r.num_front_triangles(), 2);
    Status st = write_volume_mesh(vm, output);
    if (!st.ok()) {
      out["write_error"] = st.message();
      ok = false;
    }
  }
  std::cout << out.dump(1) << "\n";
  return ok ? 0 : 1;
}

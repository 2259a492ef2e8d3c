// `anitet mesh IN -o OUT`: the whole pipeline (validate, layers, recovery, coupling, refinement,
// optimization), then the
// mesh written and its quality report printed (the same as `anitet quality OUT --surface IN`).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/volume_io.hpp"
#include "pipeline/mesher.hpp"
#include "quality/quality_report.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

namespace {

// A one-line progress bar on stderr: stage name, fraction, elapsed time.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}
  bool update(const std::string& stage, double fraction) {
    if (!enabled_) return true;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 30, filled = static_cast<int>(fraction * width + 0.5);
    std::fprintf(stderr, "\r[%-*s] %3d%% %-10s %7.2f s", width, std::string(size_t(filled), '#').c_str(),
                 static_cast<int>(fraction * 100 + 0.5), stage.c_str(), elapsed);
    if (fraction >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
    return true;
  }

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

int run_mesh_pipeline(const MeshArgs& args) {
  const std::string cmd = "anitet mesh";
  CheckedSurface checked;
  if (const int code = load_and_validate("mesh", args.input, checked); code != kExitOk) return code;

  MesherOptions options;
  options.layers.layers = args.layers;
  options.layers.scheme = args.layer_scheme == "faces" ? LayerScheme::kFacesThenPush : LayerScheme::kPushOnly;
  options.refine.size_scale = args.size;
  options.run_refine = !args.no_refine;
  options.run_optimize = !args.no_optimize;
  ProgressBar bar(!args.quiet && !args.json && isatty(STDERR_FILENO));
  options.progress = [&bar](const std::string& stage, double fraction) { return bar.update(stage, fraction); };
  Result<MesherResult> run = Mesher(options).run_validated(checked.surface);
  if (!run.ok()) {
    std::cerr << cmd << ": meshing '" << args.input << "' failed: " << run.status().message() << " ["
              << error_name(run.status().code()) << "]\n";
    return run.status().code() == Error::NotImplemented ? kExitNotImplemented : kExitInternal;
  }
  const MesherResult& r = run.value();
  if (Status st = write_volume_mesh(r.mesh, args.output); !st.ok()) {
    std::cerr << cmd << ": cannot write '" << args.output << "': " << st.message() << "\n";
    return kExitReadError;
  }
  Result<QualityReport> quality = compute_quality_report(r.mesh, &checked.surface);
  if (!quality.ok()) {
    std::cerr << cmd << ": cannot measure the mesh: " << quality.status().message() << "\n";
    return kExitInternal;
  }
  if (args.json) {
    nlohmann::json stages = nlohmann::json::array();
    for (const StageReport& s : r.stages) stages.push_back({{"stage", s.name}, {"seconds", s.seconds}, {"tets", s.tets}});
    nlohmann::json out = {
        {"input", args.input}, {"output", args.output}, {"seconds", r.seconds}, {"stages", stages},
        {"tets_per_second", r.seconds > 0 ? double(r.mesh.num_tets()) / r.seconds : 0.0},
        {"recovery", {{"steiner_on_s1_edges", r.recovery.steiner_on_edges},
                      {"steiner_on_s1_faces", r.recovery.steiner_on_faces}}},
        {"coupling", {{"edge_split_tets", r.couple.edge_split_tets}, {"faces_reconed", r.couple.faces_reconed}}},
        {"refine", {{"passes", r.refine.passes}, {"splits", r.refine.splits}, {"collapses", r.refine.collapses},
                    {"length_mean", r.refine.length_mean}, {"length_in_range", r.refine.length_in_range}}},
        {"optimize", {{"moves", r.optimize.moves}, {"flips23", r.optimize.flips23},
                      {"edge_removals", r.optimize.edge_removals}, {"perturbations", r.optimize.perturbations}}},
        {"quality", nlohmann::json::parse(quality_report_json(quality.value()))}};
    std::cout << out.dump(1) << "\n";
  } else if (!args.quiet) {
    std::cout << "anitet mesh: " << args.input << " -> " << args.output << ": " << r.mesh.num_vertices()
              << " vertices, " << r.mesh.num_tets() << " tets in " << r.seconds << " s ("
              << (r.seconds > 0 ? double(r.mesh.num_tets()) / r.seconds : 0.0) << " tets/s)\n";
    for (const StageReport& s : r.stages)
      std::cout << "  stage " << s.name << ": " << s.seconds << " s, " << s.tets << " tets\n";
    std::cout << "  stage 2 Steiner points on S1: " << r.recovery.steiner_on_edges << " on edges, "
              << r.recovery.steiner_on_faces << " in faces; coupling split " << r.couple.edge_split_tets
              << " T1 tets and re-coned " << r.couple.faces_reconed << " S1 faces\n"
              << "  refinement: " << r.refine.passes << " passes, " << r.refine.splits << " splits, "
              << r.refine.collapses << " collapses (" << r.refine.split_rejected << " splits put off, "
              << r.refine.collapse_rejected << " collapses refused); normalized edge length mean " << r.refine.length_mean
              << ", " << 100.0 * r.refine.length_in_range << "% in [1/sqrt2, sqrt2]\n"
              << "  optimization: " << r.optimize.moves << " CVT moves, " << r.optimize.flips23 << " 2-3 flips, "
              << r.optimize.edge_removals << " edge removals, " << r.optimize.perturbations
              << " sliver perturbations; radius ratio min " << r.optimize.before.min << " -> "
              << r.optimize.after.min << ", mean " << r.optimize.before.mean << " -> " << r.optimize.after.mean
              << "\n"
              << quality_report_text(quality.value());
  }
  return kExitOk;
}

}  // namespace anitet::cli

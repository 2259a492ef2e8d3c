// anitet: the command-line tool. Subcommands: check-surface, quality, report, mesh, recover.
// cli_main is the whole tool; main_serial.cpp (`anitet`) and mpi/main_mpi.cpp (`anitet-mpi`)
// call it.
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "layers/layers.hpp"

namespace {

// Options that would do nothing in the combination given are refused, never ignored: each rule
// names an option that was given and what it needs.
int check_mesh_option_combinations(const CLI::App& cmd, const anitet::cli::MeshArgs& a) {
  using anitet::cli::kExitOk;
  using anitet::cli::kExitUsage;
  auto given = [&](const char* name) { return cmd.count(name) > 0; };
  struct Rule {
    const char* option;
    bool applies;
    const char* needs;
  };
  const bool bl = !a.bl_patches.empty(), layers_only = a.stop_after == "layers";
  const bool no_stage3 = a.no_refine && a.no_optimize;
  const Rule rules[] = {
      {"--bl-first-height", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-yplus", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-growth", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-layers", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-reynolds", !(a.bl_yplus > 0.0), "--bl-yplus (it turns y+ into a first height)"},
      {"--bl-ref-length", !(a.bl_yplus > 0.0), "--bl-yplus (it turns y+ into a first height)"},
      {"--background", a.metric.metric.empty(), "a .sol --metric (it is the mesh the .sol's values are at)"},
      {"--origin", !a.metric.geodetic, "--geodetic"},
      {"--geo-frame", !a.metric.geodetic, "--geodetic"},
      {"--geodetic-output", !a.metric.geodetic, "--geodetic"},
      {"--size", no_stage3 || layers_only, "refinement or optimization (it scales their sizing field)"},
      {"--anisotropic-cycles", a.no_refine || a.no_optimize || layers_only, "both refinement and optimization"},
      {"--no-refine", layers_only, "the whole pipeline (--stop-after layers stops before refinement)"},
      {"--no-optimize", layers_only, "the whole pipeline (--stop-after layers stops before optimization)"},
      {"--recovery", layers_only, "stage 2 (--stop-after layers stops before it)"},
      {"--attempts-seconds", layers_only, "stage 2 (--stop-after layers stops before it)"},
  };
  for (const Rule& r : rules) {
    if (r.applies && given(r.option)) {
      std::cerr << "anitet mesh: " << r.option << " would do nothing here: it needs " << r.needs << "\n";
      return kExitUsage;
    }
  }
  return kExitOk;
}

int run(int argc, char** argv) {
  using namespace anitet::cli;
  CLI::App app{"anitet: boundary-constrained tetrahedral mesh generator"};
  app.set_version_flag("--version", std::string("anitet ") + ANITET_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 internal error, 2 usage, 3 read/write error, 4 invalid input,\n"
      "5 not implemented yet.");

  CheckSurfaceArgs check;
  CLI::App* check_cmd = app.add_subcommand(
      "check-surface", "Read and validate a triangulated surface; report problems and safe repairs");
  check_cmd->add_option("IN", check.input, "Surface file (.off .obj .stl .ply .mesh .msh, or .su2: its boundary markers)")->required();
  check_cmd->add_option("-o,--output", check.output,
                        "Write the surface after the safe repairs (merged vertices, reoriented triangles and "
                        "shells) here when it is valid: .off, .obj, .stl (float: lossy) or .mesh (keeps patch labels)");
  check_cmd->add_flag("--json", check.json, "Print the report as JSON");

  QualityArgs quality;
  CLI::App* quality_cmd = app.add_subcommand(
      "quality", "Quality report of a tetrahedral mesh, optionally against its input surface");
  quality_cmd->add_option("MESH", quality.mesh, "Mesh file (.mesh .msh .vtu, TetGen .node/.ele)")->required();
  quality_cmd->add_option("--surface", quality.surface,
                          "Input surface: check that the mesh keeps it (boundary constrained)");
  quality_cmd->add_flag("--json", quality.json, "Print the report as JSON");
  quality_cmd->add_option("--hist", quality.hist_csv, "Write the radius-ratio histogram as CSV here");
  quality_cmd->add_option("--tol", quality.tolerance,
                          "Relative tolerance for matching mesh vertices to input vertices "
                          "written with fewer digits (exact matches come first)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  quality_cmd->add_flag("--strict", quality.strict,
                        "Exit 4 when the mesh is invalid or does not keep the surface");
  CLI::Option* report_opt = quality_cmd->add_option(
      "--report", quality.report_html, "Write a self-contained HTML report here (summary, histograms, cut views)");
  quality_cmd->add_option("--cut", quality.cut,
                          "Cut planes of the HTML report: x,y,z as fractions of the bounding box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->needs(report_opt);
  quality_cmd->add_option("--cut-max", quality.cut_max,
                          "Cross-sections drawn per cut view at most (the ones nearest the centre)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->needs(report_opt);
  quality_cmd->add_option("--metric", quality.metric_sol,
                          "Per-vertex Medit .sol of MESH (sizes or tensors, as `mesh --write-metric` "
                          "writes): the report's edge lengths are measured in it")
      ->needs(report_opt);

  // `report`: the HTML report of a mesh, as `quality --report` writes it (default MESHSTEM.html).
  QualityArgs report;
  CLI::App* report_cmd = app.add_subcommand(
      "report", "Write the self-contained HTML quality report of a mesh (histograms, cut views) and print the text report");
  report_cmd->add_option("MESH", report.mesh, "Mesh file (.mesh .msh .vtu, TetGen .node/.ele)")->required();
  report_cmd->add_option("--surface", report.surface, "Input surface: check that the mesh keeps it");
  report_cmd->add_option("-o,--output", report.report_html, "The HTML page (default: MESH with .html)");
  report_cmd->add_option("--cut", report.cut, "Cut planes: x,y,z as fractions of the bounding box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  report_cmd->add_option("--cut-max", report.cut_max, "Cross-sections drawn per cut view at most")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  report_cmd->add_option("--metric", report.metric_sol, "Per-vertex Medit .sol of MESH: edge lengths in it");

  MeshArgs mesh, recover;
  mesh.command = "mesh";
  recover.command = "recover";
  CLI::App* mesh_cmd = app.add_subcommand(
      "mesh", "Mesh the volume inside a closed surface, keeping it exactly: layers, Delaunay "
              "with boundary recovery, coupling, metric refinement/coarsening, CVT and sliver removal");
  CLI::App* recover_cmd = app.add_subcommand(
      "recover", "Delaunay mesh of the surface's points with the surface recovered conformingly (Steiner points on it)");
  for (auto [cmd, args] : {std::pair{mesh_cmd, &mesh}, std::pair{recover_cmd, &recover}}) {
    cmd->add_option("IN", args->input, "Closed surface file (.off .obj .stl .ply .mesh .msh, or .su2: its boundary markers as named patches)")->required();
    cmd->add_option("-o,--output", args->output,
                    "Output mesh: .mesh .msh .vtu, or for solvers .su2 (SU2), .cgns (CGNS), .exo/.e "
                    "(Exodus II), or a directory path ending in polyMesh (OpenFOAM, e.g. CASE/constant/polyMesh)")
        ->required();
    cmd->add_option("--also-write", args->also_write,
                    "Also write the same mesh to this file (any output format; repeat for more), e.g. "
                    "-o case.cgns --also-write case.su2 --also-write case.mesh");
    cmd->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");
    cmd->add_option("--recovery", args->recovery,
                    "Stage 2 recovery strategies: all (split constraints, then the fuzzy-face ones when it "
                    "fails), split (split constraints only: fast, every decision combinatorial) or fuzzy "
                    "(the fuzzy-face strategies only)")
        ->capture_default_str()
        ->check(CLI::IsMember({"all", "split", "fuzzy"}));
    cmd->add_option("--patch-names", args->patch_names_spec,
                    "Names of the input's patch labels in the output, LABEL=NAME,... (e.g. 1=wall,2=farfield); "
                    "unnamed labels are patch<label>. A name is 1-32 letters, digits or '_', starting with a "
                    "letter. Used as SU2 markers, OpenFOAM patches, CGNS and Exodus names, Gmsh physical names "
                    "(Medit: comments). A name containing 'farfield' or 'symmetry' (any case) sets the CGNS BC "
                    "(BCFarfield, BCSymmetryPlane) and OpenFOAM patch type (patch, symmetry); others are walls");
  }
  CLI::Option* mesh_report = mesh_cmd->add_option(
      "--report", mesh.report_html,
      "Also write the HTML quality report of the mesh here (summary with the stage timers, histograms, cut views)");
  mesh_cmd->add_option("--cut", mesh.report_cut, "Cut planes of the HTML report: x,y,z as fractions of the bounding box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0))
      ->needs(mesh_report);
  mesh_cmd->add_option("--stop-after", mesh.stop_after,
                       "Stop after a stage and write its result: 'layers' writes T1 (stage 1) to the "
                       "output, with S1 as one more patch, and S1 to OUTSTEM.front.off")
      ->check(CLI::IsMember({"layers"}));
  mesh_cmd->add_option("--layers", mesh.layers, "Number of advancing-front layers (stage 1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 50));
  mesh_cmd->add_option("--attempts-seconds", mesh.attempts_seconds,
                       "Wall time for stages 1-2 and the coupling, run again with other layer counts and "
                       "recovery strategies when S1 is not recovered; no new attempt starts after it (0: no limit)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  mesh_cmd->add_option("--layer-scheme", mesh.layer_scheme,
                       "Stage 1 scheme: push (prism layers, each front vertex pushed off in turn) or "
                       "faces (the paper's: a tet on every face, then vertex pushes)")
      ->capture_default_str()
      ->check(CLI::IsMember({"push", "faces"}));
  mesh_cmd->add_option("--push-tasks-min-vertices", mesh.push_tasks_min_vertices,
                       "Stage 1 pushes a layer on two tasks, one per side of a plane, when it has at least "
                       "this many front vertices (the same mesh on one core as on two); 0: every push one by "
                       "one, in vertex order")
      ->capture_default_str();
  const char* bl_group = "Boundary layer";
  mesh_cmd->add_option("--bl-patches", mesh.bl_patches,
                       "The input's patch labels (comma-separated) that are walls, each a whole shell: "
                       "n thin prism layers grow there first, then the ordinary --layers on the whole "
                       "front. BL tets keep their heights through the pipeline (frozen for refinement "
                       "and optimization) and get region bodies + body (1 for one body)")
      ->delimiter(',')
      ->group(bl_group);
  CLI::Option* first_height_opt =
      mesh_cmd->add_option("--bl-first-height", mesh.bl_first_height,
                           "First layer height h0 (length units; needed with --bl-patches unless --bl-yplus gives it)")
          ->check(CLI::PositiveNumber)
          ->group(bl_group);
  CLI::Option* reynolds_opt =
      mesh_cmd->add_option("--bl-reynolds", mesh.bl_reynolds, "Reynolds number Re = U L / nu, for --bl-yplus")
          ->check(CLI::PositiveNumber)
          ->group(bl_group);
  CLI::Option* ref_length_opt =
      mesh_cmd->add_option("--bl-ref-length", mesh.bl_ref_length,
                           "Reference length L of --bl-reynolds (length units), for --bl-yplus")
          ->check(CLI::PositiveNumber)
          ->group(bl_group);
  mesh_cmd->add_option("--bl-yplus", mesh.bl_yplus,
                       "Target y+ of the first layer: h0 from the flat-plate estimate Cf = 0.026 Re^(-1/7), "
                       "h0 = y+ L / (Re sqrt(Cf/2)); needs --bl-reynolds and --bl-ref-length, excludes "
                       "--bl-first-height; the h0 used is printed")
      ->check(CLI::PositiveNumber)
      ->needs(reynolds_opt)
      ->needs(ref_length_opt)
      ->excludes(first_height_opt)
      ->group(bl_group);
  mesh_cmd->add_option("--bl-growth", mesh.bl_growth, "Growth ratio r: layer i has height h0 r^i")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 10.0))
      ->group(bl_group);
  mesh_cmd->add_option("--bl-layers", mesh.bl_layers, "Number of boundary layers n")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000))
      ->group(bl_group);
  mesh_cmd->add_flag("--bl-sizing", mesh.bl_sizing,
                     "Refine the interior to continue the boundary layer's heights: the sizing field is "
                     "intersected with a metric of normal size h0 + (r - 1) d at distance d from the walls, "
                     "so the tets on the BL's top are about as thin as its last layer instead of jumping to "
                     "the surface's sizes. Anisotropic near the walls: refinement is slower. Needs "
                     "--bl-patches and --bl-growth above 1")
      ->group(bl_group);
  mesh_cmd->add_option("--size", mesh.size,
                       "Scale every target edge length of the sizing field (--metric's, or the paper's "
                       "grid from the surface's triangle sizes), after --hmin/--hmax/--hgrad: 0.5 = "
                       "twice as fine, 2 = twice as coarse")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group("Sizing");
  add_metric_options(*mesh_cmd, mesh.metric);
  mesh_cmd->add_flag("--no-refine", mesh.no_refine, "Skip refinement/coarsening by metric edge length");
  mesh_cmd->add_flag("--no-optimize", mesh.no_optimize, "Skip CVT smoothing, flips and sliver removal");
  mesh_cmd
      ->add_option("--anisotropic-cycles", mesh.anisotropic_cycles,
                   "With an anisotropic metric (--metric tensors, --bl-sizing): more rounds of refinement then "
                   "optimization after the first, which even the metric lengths and shapes further")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  mesh_cmd->add_flag("--json", mesh.json, "Print the report as JSON");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and a hint on stderr
    return kExitUsage;
  }

  if (mesh_cmd->parsed())
    if (const int code = check_mesh_option_combinations(*mesh_cmd, mesh); code != kExitOk) return code;
  if (mesh_cmd->parsed() && mesh.bl_yplus > 0.0) {
    anitet::Result<double> h0 = anitet::first_height_from_yplus(mesh.bl_yplus, mesh.bl_reynolds, mesh.bl_ref_length);
    if (!h0.ok()) {
      std::cerr << "anitet mesh: --bl-yplus: " << h0.status().message() << "\n";
      return kExitUsage;
    }
    mesh.bl_first_height = h0.value();
    if (!mesh.quiet && !mesh.json)
      std::cout << "anitet mesh: --bl-yplus " << mesh.bl_yplus << " at Re " << mesh.bl_reynolds << ", L "
                << mesh.bl_ref_length << ": first height h0 = " << mesh.bl_first_height
                << " (flat plate: Cf = 0.026 Re^(-1/7), h0 = y+ L / (Re sqrt(Cf/2)))\n";
  }
  if (check_cmd->parsed()) return run_check_surface(check);
  if (quality_cmd->parsed()) return run_quality(quality);
  if (report_cmd->parsed()) {
    if (report.report_html.empty()) {
      const std::filesystem::path p(report.mesh);
      report.report_html = (p.parent_path() / p.stem()).string() + ".html";
    }
    return run_quality(report);
  }
  if (mesh_cmd->parsed() && mesh.stop_after == "layers" &&
      (wants_sizing_field(mesh.metric) || mesh.metric.geodetic || !mesh.metric.background.empty())) {
    std::cerr << "anitet mesh: the sizing and geographic options (--metric, --background, --hmin, "
                 "--hmax, --hgrad, --write-metric, --write-sizing, --geodetic) apply to the whole "
                 "pipeline, not to --stop-after layers\n";
    return kExitUsage;
  }
  if (mesh_cmd->parsed() && mesh.stop_after == "layers" && !mesh.report_html.empty()) {
    std::cerr << "anitet mesh: --report applies to the whole pipeline; for stage 1 alone, run "
                 "`anitet report OUT` on its output\n";
    return kExitUsage;
  }
  if (mesh_cmd->parsed()) return mesh.stop_after == "layers" ? run_mesh_layers(mesh) : run_mesh_pipeline(mesh);
  if (recover_cmd->parsed()) return run_mesh(recover);
  std::cerr << app.help();
  return kExitUsage;
}

}  // namespace

namespace {

// Copies what passes through to another buffer, and keeps a copy (stderr) or a count (stdout).
class TeeBuffer final : public std::streambuf {
 public:
  TeeBuffer(std::streambuf* to, bool keep) : to_(to), keep_(keep) {}
  const std::string& text() const { return text_; }
  size_t count() const { return count_; }

 protected:
  int overflow(int c) override {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    const char ch = traits_type::to_char_type(c);
    return xsputn(&ch, 1) == 1 ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (keep_) text_.append(s, size_t(n));
    count_ += size_t(n);
    return to_->sputn(s, n);
  }
  int sync() override { return to_->pubsync(); }

 private:
  std::streambuf* to_;
  bool keep_;
  std::string text_;
  size_t count_ = 0;
};

// With --json, a failing command prints a JSON object too, never nothing: every message a
// command writes on stderr is kept, and when it ends with an exit code other than 0 without
// having printed anything on stdout, {"ok": false, "error": {...}} goes there. One mechanism for
// every command and every failure path, including the option parser's.
class JsonFailureGuard {
 public:
  explicit JsonFailureGuard(bool on) : on_(on), err_(std::cerr.rdbuf(), true), out_(std::cout.rdbuf(), false) {
    if (!on_) return;
    old_err_ = std::cerr.rdbuf(&err_);
    old_out_ = std::cout.rdbuf(&out_);
  }
  ~JsonFailureGuard() {
    if (!on_) return;
    std::cerr.rdbuf(old_err_);
    std::cout.rdbuf(old_out_);
  }
  void finish(int code) {
    if (!on_ || code == anitet::cli::kExitOk || out_.count() > 0) return;
    std::vector<std::string> lines;
    std::istringstream text(err_.text());
    for (std::string line; std::getline(text, line);)
      if (!line.empty()) lines.push_back(line);
    const nlohmann::json error = {{"exit_code", code},
                                  {"kind", anitet::cli::exit_code_name(code)},
                                  {"message", lines.empty() ? std::string(anitet::cli::exit_code_name(code)) : lines.front()},
                                  {"messages", lines}};
    std::cout << nlohmann::json({{"ok", false}, {"error", error}}).dump(1) << "\n";
    std::cout.flush();
  }

 private:
  bool on_;
  TeeBuffer err_, out_;
  std::streambuf* old_err_ = nullptr;
  std::streambuf* old_out_ = nullptr;
};

bool asks_for_json(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--json") return true;
  return false;
}

}  // namespace

int anitet::cli::cli_main(int argc, char** argv) {
  JsonFailureGuard guard(asks_for_json(argc, argv));
  int code = kExitInternal;
  try {
    code = run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::cerr << "anitet: out of memory\n";
  } catch (const std::exception& e) {
    std::cerr << "anitet: internal error: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "anitet: internal error\n";
  }
  guard.finish(code);
  return code;
}

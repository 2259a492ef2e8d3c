// anitet: the command-line tool. Each subcommand (check-surface, quality, report, mesh, recover)
// registers its options and runs in its own file (cmd_*.cpp); this file parses and dispatches.
// cli_main is the whole tool; main_serial.cpp (`anitet`) and mpi/main_mpi.cpp (`anitet-mpi`)
// call it.
#include <exception>
#include <iostream>
#include <new>
#include <sstream>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

#include "cli_util.hpp"
#include "cmd_mesh2d.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"

namespace {

const char* kExitCodes =
    "Exit codes:\n"
    "  0  success\n"
    "  1  internal error (a bug: please report it with the input)\n"
    "  2  usage: a bad option or value, a missing argument, an output format that cannot be written\n"
    "  3  read/write error: a file cannot be opened, read or written\n"
    "  4  invalid input: read but not valid (a malformed file, an open or self-intersecting surface,\n"
    "     ...); also quality --strict on an invalid mesh\n"
    "  5  not implemented in this build or version (.cgns/.exo without their library)";

// An option the parser did not know: say which, and the nearest the command has.
int unknown_option(const CLI::App& app, const CLI::App* cmd, int argc, char** argv, const CLI::ParseError& e) {
  for (int i = 1; cmd && i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
    const std::string name = arg.substr(0, arg.find('='));
    bool known = false;
    for (const CLI::Option* opt : cmd->get_options()) known = known || opt->check_lname(name.substr(2));
    if (!known) {
      std::cerr << "anitet " << cmd->get_name() << ": unknown option " << name << anitet::cli::suggest_option(*cmd, name)
                << "\nRun 'anitet " << cmd->get_name() << " --help' for the options.\n";
      return anitet::cli::kExitUsage;
    }
  }
  app.exit(e);  // CLI11's own message and hint on stderr
  return anitet::cli::kExitUsage;
}

int run(int argc, char** argv) {
  using namespace anitet::cli;
  CLI::App app{"anitet: tetrahedral meshes that keep the input surface exactly, for CFD and FEM solvers"};
  app.formatter(wrapping_formatter());
  app.set_version_flag("--version", std::string("anitet ") + ANITET_VERSION);
  app.require_subcommand(1);
  app.footer(std::string("Run 'anitet COMMAND --help' for a command's options and examples.\n\n") + kExitCodes);
  CheckSurfaceArgs check;
  QualityArgs quality, report;
  MeshArgs mesh, recover;
  CLI::App* check_cmd = add_check_surface_command(app, check);
  CLI::App* quality_cmd = add_quality_command(app, quality);
  CLI::App* report_cmd = add_report_command(app, report);
  CLI::App* mesh_cmd = add_mesh_command(app, mesh);
  CLI::App* recover_cmd = add_recover_command(app, recover);
  Mesh2dCommand mesh2d(app);
  // Every command: --threads, and the exit codes under its options.
  int threads = 0;
  for (CLI::App* cmd : {check_cmd, quality_cmd, report_cmd, mesh_cmd, recover_cmd}) {
    cmd->add_option("--threads", threads, "Threads to use (0: all cores); the mesh is the same on any number")
        ->check(in_range(0, 4096))
        ->group("General");
    cmd->footer(cmd->get_footer() + (cmd->get_footer().empty() ? "" : "\n\n") + kExitCodes);
  }
=======
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
  Mesh2dCommand mesh2d(app);

>>>>>>> 66e604e (app: `anitet mesh2d IN -o OUT` (app/cmd_mesh2d.cpp, one Mesh2dCommand that registers the subcommand; main.cpp gains three lines): .poly/.mesh/GeoJSON in, .mesh/.msh/.vtu/fort.14 out (--also-write), grouped --help under 100 columns with examples, --json, a progress bar, -q; sizing (--hsize, --size, --hmin/--hmax/--hgrad, --metric .sol with --background or .vdb, --distance-size, --bathymetry with the wavelength rule), geographic input (--geodetic, GeoJSON by default; ENU or UTM; --geodetic-output writes the input's points back exactly), ADCIRC labels (--open-labels); exit codes 2/3/4 by the failing stage. ProgressBar moved to app/progress_bar.hpp for both mesh commands; mesh2d/quality2 measures the report's figures)
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    const CLI::App* cmd = nullptr;
    for (CLI::App* c : {check_cmd, quality_cmd, report_cmd, mesh_cmd, recover_cmd})
      if (argc > 1 && c->get_name() == argv[1]) cmd = c;
    return unknown_option(app, cmd, argc, argv, e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and a hint on stderr
    return kExitUsage;
  }
  mesh.threads = recover.threads = threads;
  // Every stage of every command runs in one task arena of that size (the TBB work; the few
  // threads of anitet's own take the count into account too).
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  return arena.execute([&] {
    if (check_cmd->parsed()) return run_check_surface(check);
    if (quality_cmd->parsed()) return run_quality(quality);
    if (report_cmd->parsed()) return run_report(report);
    if (mesh_cmd->parsed()) return run_mesh(*mesh_cmd, mesh);
    if (recover_cmd->parsed()) return run_recover(recover);
    if (const int code = mesh2d.run_if_parsed(); code >= 0) return code;
    std::cerr << app.help();
    return kExitUsage;
  });
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
<<<<<<< HEAD
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

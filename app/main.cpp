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
  AdaptArgs adapt;
  MergeArgs merge;
  CLI::App* check_cmd = add_check_surface_command(app, check);
  CLI::App* quality_cmd = add_quality_command(app, quality);
  CLI::App* report_cmd = add_report_command(app, report);
  CLI::App* mesh_cmd = add_mesh_command(app, mesh);
  CLI::App* recover_cmd = add_recover_command(app, recover);
  CLI::App* adapt_cmd = add_adapt_command(app, adapt);
  Mesh2dCommand mesh2d(app);
  CLI::App* merge_cmd = add_merge_command(app, merge);
  // Every command: --threads, and the exit codes under its options.
  int threads = 0;
  for (CLI::App* cmd : {check_cmd, quality_cmd, report_cmd, mesh_cmd, recover_cmd, adapt_cmd, mesh2d.command(), merge_cmd}) {
    cmd->add_option("--threads", threads, "Threads to use (0: all cores); the mesh is the same on any number")
        ->check(in_range(0, 4096))
        ->group("General");
    cmd->footer(cmd->get_footer() + (cmd->get_footer().empty() ? "" : "\n\n") + kExitCodes);
  }
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
    for (CLI::App* c : {check_cmd, quality_cmd, report_cmd, mesh_cmd, recover_cmd, adapt_cmd, mesh2d.command(), merge_cmd})
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
    if (adapt_cmd->parsed()) return run_adapt(adapt);
    if (merge_cmd->parsed()) return run_merge(merge);
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

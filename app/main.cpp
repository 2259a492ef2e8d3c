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

#include "commands.hpp"
#include "exit_codes.hpp"

namespace {

int run(int argc, char** argv) {
  using namespace anitet::cli;
  CLI::App app{"anitet: boundary-constrained tetrahedral mesh generator"};
  app.set_version_flag("--version", std::string("anitet ") + ANITET_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 internal error, 2 usage, 3 read/write error, 4 invalid input,\n"
      "5 not implemented yet.");
  CheckSurfaceArgs check;
  QualityArgs quality, report;
  MeshArgs mesh, recover;
  CLI::App* check_cmd = add_check_surface_command(app, check);
  CLI::App* quality_cmd = add_quality_command(app, quality);
  CLI::App* report_cmd = add_report_command(app, report);
  CLI::App* mesh_cmd = add_mesh_command(app, mesh);
  CLI::App* recover_cmd = add_recover_command(app, recover);
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
  if (check_cmd->parsed()) return run_check_surface(check);
  if (quality_cmd->parsed()) return run_quality(quality);
  if (report_cmd->parsed()) return run_report(report);
  if (mesh_cmd->parsed()) return run_mesh(*mesh_cmd, mesh);
  if (recover_cmd->parsed()) return run_recover(recover);
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

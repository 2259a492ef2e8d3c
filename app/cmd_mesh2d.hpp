// `anitet mesh2d IN -o OUT`: the 2D mesher's subcommand (src/mesh2d). main.cpp only creates it
// beside the other subcommands and asks it to run once the command line is parsed.
#pragma once

#include <memory>

#include <CLI/CLI.hpp>

namespace anitet::cli {

class Mesh2dCommand {
 public:
  // Adds `mesh2d` and its options to the tool's command line.
  explicit Mesh2dCommand(CLI::App& app);
  ~Mesh2dCommand();
  // The exit code of `mesh2d` when it was the subcommand given, else -1.
  int run_if_parsed();
  CLI::App* command() const { return cmd_; }

  struct Args;

 private:
  CLI::App* cmd_ = nullptr;
  std::unique_ptr<Args> args_;
};

}  // namespace anitet::cli

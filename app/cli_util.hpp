// What every command of the tool shares: --help wrapped to 100 columns, number checks whose
// messages say what was expected ("--size must be > 0, got -1"), a suggestion for a misspelt
// option, times written for people, and a progress line on a terminal.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

namespace anitet::cli {

// --help: option descriptions wrapped to kHelpWidth columns, the names in a left column.
constexpr size_t kHelpWidth = 99;
std::shared_ptr<CLI::Formatter> wrapping_formatter();

// Checks of a number option: CLI11 prefixes the option's name ("--size must be > 0, got -1").
CLI::Validator positive();                       // > 0
CLI::Validator non_negative();                   // >= 0
CLI::Validator in_range(double lo, double hi);   // lo <= x <= hi (integers print as such)

// For an option CLI11 did not know ("--sizee"): " (did you mean --size?)" when one of `cmd`'s
// options is near it (edit distance 2 or less, or a prefix), else "".
std::string suggest_option(const CLI::App& cmd, const std::string& unknown);

// "0.32 s", "12.4 s", "1 min 12 s", "2 h 05 min".
std::string format_seconds(double seconds);

// One line on stderr, rewritten in place: "[#####    ]  48% refine, pass 3   0.71 s, 0.77 s left".
// Shown only on a terminal (not when piped) and never with -q or --json.
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled);
  // fraction of the whole run; `stage` names what runs now. Returns true (never cancels).
  bool update(const std::string& stage, double fraction);

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  size_t last_width_ = 0;
};

}  // namespace anitet::cli

// The commands' progress display.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace anitet::cli {

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

}  // namespace anitet::cli

#include "distributed/memory_trace.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace anitet::distributed {

void trace_memory(int rank, const char* phase) {
  static const bool on = std::getenv("ANITET_RANK_MEMORY") != nullptr;
  if (!on) return;
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return;
  char line[256];
  double rss = 0.0, hwm = 0.0;
  while (std::fgets(line, sizeof line, f)) {
    if (std::strncmp(line, "VmRSS:", 6) == 0) rss = std::atof(line + 6) / 1024.0;
    if (std::strncmp(line, "VmHWM:", 6) == 0) hwm = std::atof(line + 6) / 1024.0;
  }
  std::fclose(f);
  std::fprintf(stderr, "anitet-mpi: rank %d: %-28s RSS %7.0f MB, peak %7.0f MB\n", rank, phase, rss, hwm);
}

}  // namespace anitet::distributed

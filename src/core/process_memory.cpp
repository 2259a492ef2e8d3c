#include "core/process_memory.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace anitet {

double peak_resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0.0;
  char line[256];
  double kb = 0.0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atof(line + 6);
  std::fclose(f);
  return kb * 1024.0;
}

}  // namespace anitet

// A libFuzzer executable for one target, chosen at build time by ANITET_FUZZ_TARGET (its name).
#include <cstdio>
#include <cstdlib>

#include "fuzz_entry.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const anitet::fuzz::Target* const target = [] {
    const anitet::fuzz::Target* t = anitet::fuzz::find_target(ANITET_FUZZ_TARGET);
    if (t == nullptr) {
      std::fprintf(stderr, "no fuzz target %s\n", ANITET_FUZZ_TARGET);
      std::abort();
    }
    return t;
  }();
  target->entry(data, size);
  return 0;
}

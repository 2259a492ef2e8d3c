// Replays inputs through a fuzz target's entry without libFuzzer, for ctest under any compiler:
//   anitet_fuzz_replay TARGET PATH...
// Each PATH is a file or a directory (its regular files, recursively, in sorted order); a PATH
// that does not exist holds nothing (fuzz/regressions/TARGET exists only once a crasher was
// kept), but replaying no file at all is an error. A broken contract or a crash aborts the
// process, so the test fails and names the file being replayed.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <string>
#include <vector>

#include "fuzz_entry.hpp"

namespace fs = std::filesystem;

// libFuzzer fails an input whose code asks for more than -malloc_limit_mb (scripts/fuzz.sh:
// 2 GB at once): from a few KB that is a count trusted before it was checked. The replay fails
// the same way, also where the machine could have given the memory.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ANITET_REPLAY_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(ANITET_REPLAY_ASAN)
// ASan owns operator new; its allocation-size-too-big report aborts.
extern "C" const char* __asan_default_options() { return "max_allocation_size_mb=2048"; }
#else
namespace {
constexpr std::size_t kMallocLimit = std::size_t(2048) << 20;
void* checked_new(std::size_t size) {
  if (size > kMallocLimit) {
    std::fprintf(stderr, "replay: an allocation of %zu bytes (above 2 GB)\n", size);
    std::abort();
  }
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
}  // namespace
void* operator new(std::size_t size) { return checked_new(size); }
void* operator new[](std::size_t size) { return checked_new(size); }
#endif

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s TARGET PATH...\n", argv[0]);
    return 2;
  }
  const anitet::fuzz::Target* target = anitet::fuzz::find_target(argv[1]);
  if (target == nullptr) {
    std::fprintf(stderr, "no fuzz target %s\n", argv[1]);
    return 2;
  }
  std::vector<fs::path> files;
  for (int i = 2; i < argc; ++i) {
    const fs::path path(argv[i]);
    if (fs::is_directory(path)) {
      for (const fs::directory_entry& e : fs::recursive_directory_iterator(path)) {
        if (e.is_regular_file()) files.push_back(e.path());
      }
    } else if (fs::exists(path)) {
      files.push_back(path);
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "%s: no input to replay\n", target->name);
    return 1;
  }
  for (const fs::path& file : files) {
    std::fprintf(stderr, "%s: %s\n", target->name, file.c_str());
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (!in.good() && !in.eof()) {
      std::fprintf(stderr, "cannot read %s\n", file.c_str());
      return 2;
    }
    target->entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%s: %zu inputs replayed\n", target->name, files.size());
  return 0;
}

// The fuzz targets' entry points (issue 11), shared by the libFuzzer executables (fuzz_main.cpp,
// built with -DANITET_BUILD_FUZZERS=ON under clang) and the replay test (replay.cpp, any
// compiler), so that a crasher kept in fuzz/regressions/ runs through exactly the code that found it.
//
// Each entry feeds the bytes to one reader (or to the C ABI's surface input) and checks the
// reader's contract: a result with consistent arrays, or an error with a documented code and a
// message. A broken contract prints what broke and aborts, as a crash would.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace anitet::fuzz {

using Entry = void (*)(const uint8_t* data, size_t size);

struct Target {
  const char* name;  // fuzz/corpus/<name>, fuzz/regressions/<name>, executable fuzz_<name>
  Entry entry;
};

// Every target, in a fixed order.
const std::vector<Target>& targets();
// The target called `name`, or nullptr.
const Target* find_target(std::string_view name);

}  // namespace anitet::fuzz

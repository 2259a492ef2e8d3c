// Shared helpers for io_tests: data paths, temporary files, and the box of
// tests/data/io/make_test_files.py that every small test file describes.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "io/file_bytes.hpp"

namespace anitet::test {

inline std::string io_data(const std::string& file) {
  return std::string(ANITET_TEST_DATA_DIR) + "/io/" + file;
}

inline std::string load(const std::string& path) {
  Result<std::string> bytes = read_file_bytes(path);
  EXPECT_TRUE(bytes.ok()) << bytes.status().message();
  return bytes.ok() ? bytes.value() : std::string();
}

// A fresh directory for this process's output files, removed at exit.
inline const std::string& temp_dir() {
  static const std::string dir = [] {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/anitet_io_XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    const char* made = mkdtemp(buf.data());
    EXPECT_NE(made, nullptr) << "cannot create " << pattern;
    return made ? std::string(made) : std::string(".");
  }();
  static const bool cleanup = [] {
    std::atexit([] {
      std::error_code ignored;
      if (dir != ".") std::filesystem::remove_all(dir, ignored);
    });
    return true;
  }();
  (void)cleanup;
  return dir;
}

inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The box: [0, 1.5] x [0, 0.1] x [-0.25, 2], vertex i has bit k of i set when coordinate k is max.
inline double box_coord(int v, int k) {
  static const double lo[3] = {0.0, 0.0, -0.25};
  static const double hi[3] = {1.5, 0.1, 2.0};
  return ((v >> k) & 1) ? hi[k] : lo[k];
}
inline std::vector<double> box_xyz() {
  std::vector<double> xyz;
  for (int v = 0; v < 8; ++v) {
    for (int k = 0; k < 3; ++k) xyz.push_back(box_coord(v, k));
  }
  return xyz;
}
inline const std::vector<uint32_t> kBoxTets = {0, 1, 3, 7, 1, 0, 5, 7, 2, 0, 3, 7,
                                               0, 2, 6, 7, 0, 4, 5, 7, 4, 0, 6, 7};
inline const std::vector<int32_t> kBoxRegions = {1, 1, 1, 2, 2, 2};
inline const std::vector<uint32_t> kBoxTris = {0, 6, 2, 4, 6, 0, 1, 3, 7, 1, 7, 5,
                                               0, 5, 4, 1, 5, 0, 2, 6, 7, 2, 7, 3,
                                               0, 3, 1, 2, 3, 0, 4, 5, 7, 4, 7, 6};
inline const std::vector<int32_t> kBoxPatches = {1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6};

}  // namespace anitet::test

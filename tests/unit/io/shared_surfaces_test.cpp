// Every shared test surface reads with the triangle and vertex counts of SOURCES.md (vertices
// after the exact merging of STL corners; unreferenced vertices count). Prints read times.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <string>

#include "io/surface_io.hpp"

namespace anitet {
namespace {

struct SharedSurface {
  const char* file;
  size_t triangles;
  size_t vertices;
};

const SharedSurface kSurfaces[] = {
    {"decimated-knight.off", 1000, 502}, {"tray_bottom.stl", 4520, 2216},
    {"bimba_low.off", 5000, 2502},       {"kitten.off", 5000, 2500},
    {"adis16480.stl", 7436, 3672},       {"femur.off", 7798, 3897},
    {"casting.off", 10224, 5096},        {"elephant.obj", 12064, 6034},
    {"fandisk.off", 12946, 6475},        {"airplane.obj", 17456, 8730},
    {"turbine.off", 18460, 9210},        {"rocker-arm.obj", 20088, 10044},
    {"hammer.obj", 60160, 30082},        {"armadillo.obj", 86482, 43243},
    {"skull.obj", 100002, 49999},        {"stanford-bunny.obj", 69451, 35947},
    {"bimba_selfx.obj", 17710, 8857},    {"counter.stl", 83750, 41837},
    {"dragon.ply", 100000, 50002},
};

// Names the file in test listings instead of dumping the struct's bytes.
void PrintTo(const SharedSurface& s, std::ostream* os) { *os << s.file; }

class SharedSurfaces : public ::testing::TestWithParam<SharedSurface> {};

TEST_P(SharedSurfaces, ReadWithDocumentedCounts) {
  const SharedSurface& s = GetParam();
  const std::string path = std::string(ANITET_SURFACES_DIR) + "/" + s.file;
  struct stat info;
  if (stat(path.c_str(), &info) != 0) GTEST_SKIP() << path << " is not available";
  const auto start = std::chrono::steady_clock::now();
  Result<SurfaceMesh> mesh = read_surface(path);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->num_triangles(), s.triangles);
  EXPECT_EQ(mesh->num_vertices(), s.vertices);
  EXPECT_EQ(mesh->patch.size(), s.triangles);
  EXPECT_TRUE(check_surface_arrays(mesh.value()).ok());
  std::printf("[ read    ] %-20s %8.1f ms (%.1f MB)\n", s.file, ms, info.st_size / 1e6);
  RecordProperty("read_ms", std::to_string(ms));
}

INSTANTIATE_TEST_SUITE_P(AllFiles, SharedSurfaces, ::testing::ValuesIn(kSurfaces),
                         [](const ::testing::TestParamInfo<SharedSurface>& param) {
                           std::string name = param.param.file;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace anitet

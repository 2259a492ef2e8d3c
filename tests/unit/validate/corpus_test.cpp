// The shared corpus (/work/shared/data/surfaces, see SOURCES.md there): the clean surfaces pass,
// the bad ones report their known defects. Counts from SOURCES.md (numpy and CGAL 5.5).
#include <gtest/gtest.h>

#include <cctype>
#include <iostream>
#include <string>
#include <vector>

#include "io/surface_io.hpp"
#include "validate/validate.hpp"

namespace anitet {
namespace {

ValidationReport validate_file(const std::string& name, SurfaceMesh* out = nullptr) {
  Result<SurfaceMesh> read = read_surface(std::string(ANITET_SURFACES_DIR) + "/" + name);
  EXPECT_TRUE(read.ok()) << name << ": " << read.status().message();
  if (!read.ok()) return ValidationReport{};
  SurfaceMesh s = std::move(read).value();
  ValidationReport r = validate_surface(s);
  if (out) *out = std::move(s);
  return r;
}

size_t triangles_in_shells(const ValidationReport& r) {
  size_t n = 0;
  for (const ShellInfo& sh : r.shells) n += sh.num_triangles;
  return n;
}

class CleanSurface : public testing::TestWithParam<const char*> {};

TEST_P(CleanSurface, PassesValidation) {
  SurfaceMesh s;
  const ValidationReport r = validate_file(GetParam(), &s);
  EXPECT_TRUE(r.ok()) << GetParam() << "\n" << r.summary();
  EXPECT_TRUE(r.intersecting_pairs.empty());
  EXPECT_EQ(triangles_in_shells(r), s.num_triangles());
  EXPECT_GE(r.num_regions, 1u);
  bool flipped = false;
  for (const ShellInfo& sh : r.shells) {
    EXPECT_TRUE(sh.closed);
    EXPECT_EQ(sh.depth % 2 == 0, sh.signed_volume > 0) << GetParam();
    flipped = flipped || sh.flipped;
  }
  // casting.off is the one stored inward (SOURCES.md): it must be reported as reoriented.
  EXPECT_EQ(flipped, std::string(GetParam()) == "casting.off") << r.summary();
}

INSTANTIATE_TEST_SUITE_P(Corpus, CleanSurface,
                         testing::Values("decimated-knight.off", "tray_bottom.stl",
                                         "bimba_low.off", "kitten.off", "adis16480.stl",
                                         "femur.off", "casting.off", "elephant.obj",
                                         "fandisk.off", "airplane.obj", "turbine.off",
                                         "rocker-arm.obj", "hammer.obj", "armadillo.obj",
                                         "skull.obj"),
                         [](const testing::TestParamInfo<const char*>& param) {
                           std::string n = param.param;
                           for (char& c : n) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return n;
                         });

TEST(CorpusDefects, StanfordBunnyIsOpen) {
  const ValidationReport r = validate_file("stanford-bunny.obj");
  EXPECT_EQ(r.status().code(), Error::OpenBoundary) << r.summary();
  EXPECT_EQ(r.count(Error::OpenBoundary), 223u);
  ASSERT_NE(r.find("unreferenced_vertex"), nullptr);
  EXPECT_EQ(r.find("unreferenced_vertex")->count, 1113u);
  EXPECT_EQ(r.count(Error::NonManifoldEdge), 0u);
  EXPECT_EQ(r.count(Error::InconsistentOrientation), 0u);
  std::cout << r.summary();
}

TEST(CorpusDefects, BimbaSelfIntersects) {
  const ValidationReport r = validate_file("bimba_selfx.obj");
  EXPECT_EQ(r.status().code(), Error::SelfIntersection) << r.summary();
  EXPECT_EQ(r.count(Error::SelfIntersection), 10u);
  EXPECT_EQ(r.intersecting_pairs.size(), 10u);
  std::cout << r.summary();
}

TEST(CorpusDefects, CounterHasIntersectingShells) {
  const ValidationReport r = validate_file("counter.stl");
  EXPECT_EQ(r.shells.size(), 6u) << r.summary();
  EXPECT_GT(r.count(Error::IntersectingShells), 0u);
  EXPECT_EQ(r.intersecting_pairs.size(), 2272u);
  std::cout << r.summary();
}

// SOURCES.md counts 46 intersecting pairs (CGAL). Triangles 17361 and 17365 have the same
// vertices in opposite orders (a two-triangle pocket hanging on the non-manifold edge 2986-9117).
// Once CGAL makes the mesh manifold it no longer sees that the pocket shares corners with the 9
// triangles around 2986 and 9117, so each pocket triangle "touches" them (2 x 9 = 18 pairs), and
// the pocket pair itself counts (1). Here shared corners are recognised and duplicates are
// reported as duplicates: 46 - 18 - 1 = 27 pairs, all among CGAL's (checked with CGAL 5.5).
TEST(CorpusDefects, DragonDefects) {
  const ValidationReport r = validate_file("dragon.ply");
  EXPECT_EQ(r.count(Error::DuplicateTriangle), 1u) << r.summary();
  EXPECT_EQ(r.find("duplicate_triangle")->examples[0].triangles,
            (std::vector<uint32_t>{17365, 17361}));
  EXPECT_EQ(r.count(Error::NonManifoldEdge), 1u);
  // The non-manifold edge is used twice in each direction (SOURCES.md's "inconsistent").
  EXPECT_EQ(r.count(Error::InconsistentOrientation), 1u);
  EXPECT_EQ(r.count(Error::OpenBoundary), 0u);
  EXPECT_EQ(r.count(Error::SelfIntersection), 27u);
  EXPECT_EQ(r.intersecting_pairs.size(), 27u);
  std::cout << r.summary();
}

}  // namespace
}  // namespace anitet

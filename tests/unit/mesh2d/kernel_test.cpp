// The 2D kernel: Delaunay of point sets (empty circles, exact checks), insertion on edges and
// constrained edges, flips, conforming recovery of segments.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "mesh2d/conforming.hpp"
#include "mesh2d/triangulation.hpp"
#include "predicates/predicates.hpp"

namespace anitet::mesh2d {
namespace {

// Every triangle's circumcircle is empty of the other used vertices (brute force).
void expect_delaunay(const Triangulation& m, uint32_t corner) {
  for (uint32_t t = 0; t < m.num_slots(); ++t) {
    if (!m.alive(t)) continue;
    for (uint32_t v = 0; v < corner; ++v) {
      if (m.vtri[v] == kNone || m.index_of(t, v) >= 0) continue;
      ASSERT_LE(predicates::incircle(m.point(m.v(t, 0)), m.point(m.v(t, 1)), m.point(m.v(t, 2)), m.point(v)), 0)
          << "triangle " << t << " vertex " << v;
    }
  }
}

TEST(Mesh2dKernel, DelaunayOfRandomAndGridPoints) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> xy;
  for (int i = 0; i < 300; ++i) xy.push_back(u(rng)), xy.push_back(u(rng));
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) xy.push_back(i * 0.1), xy.push_back(j * 0.1);  // cocircular quadruples
  std::vector<uint32_t> all(xy.size() / 2);
  std::iota(all.begin(), all.end(), 0u);
  uint32_t corner = 0;
  Result<Triangulation> dt = delaunay_in_box(xy, all, &corner);
  ASSERT_TRUE(dt.ok()) << dt.status().message();
  EXPECT_EQ(corner, xy.size() / 2);
  ASSERT_TRUE(check_triangulation(dt.value()).ok()) << check_triangulation(dt.value()).message();
  // Euler: a triangulated box with n + 4 points has 2(n + 4) - 2 - 4 triangles.
  EXPECT_EQ(dt->num_triangles(), 2 * (all.size() + 4) - 6);
  expect_delaunay(dt.value(), corner);
}

TEST(Mesh2dKernel, DuplicatePointsAreRefused) {
  const std::vector<double> xy = {0, 0, 1, 0, 0, 1, 1, 0};
  Result<Triangulation> dt = delaunay_in_box(xy, {0, 1, 2, 3}, nullptr);
  ASSERT_FALSE(dt.ok());
  EXPECT_EQ(dt.status().code(), Error::DuplicatePoint);
}

TEST(Mesh2dKernel, InsertOnConstrainedEdgeSplitsItsTag) {
  const std::vector<double> xy = {0, 0, 2, 0, 1, 1, 1, -1};
  uint32_t corner = 0;
  Result<Triangulation> dt = delaunay_in_box(xy, {0, 1, 2, 3}, &corner);
  ASSERT_TRUE(dt.ok());
  Triangulation& m = dt.value();
  ASSERT_TRUE(recover_segments(m, {0, 1}, {7}).ok());
  Kernel kernel(m);
  const double mid[2] = {1, 0};
  const Location loc = kernel.locate(mid, m.vtri[0]);
  ASSERT_EQ(loc.kind, Location::OnEdge);
  EXPECT_EQ(kernel.insert(mid, loc), kNone);  // not without split_constraints
  const uint32_t v = kernel.insert(mid, loc, nullptr, true);
  ASSERT_NE(v, kNone);
  ASSERT_TRUE(check_triangulation(m).ok()) << check_triangulation(m).message();
  uint32_t t;
  int k;
  ASSERT_TRUE(m.find_edge(0, v, t, k) || m.find_edge(v, 0, t, k));
  EXPECT_EQ(m.edge_tag(t, k), 7);
  ASSERT_TRUE(m.find_edge(v, 1, t, k) || m.find_edge(1, v, t, k));
  EXPECT_EQ(m.edge_tag(t, k), 7);
  std::vector<uint32_t> chain;
  ASSERT_TRUE(chain_vertices(m, 0, 1, 7, chain).ok());
  EXPECT_EQ(chain, (std::vector<uint32_t>{0, v, 1}));
}

TEST(Mesh2dKernel, ConformingRecoveryOfCrossingFreeSegments) {
  // A zig-zag of long segments through a cloud of points: every one becomes a chain of edges.
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> xy = {0, 0.5, 0.25, 0.1, 0.5, 0.9, 0.75, 0.1, 1, 0.5};
  for (int i = 0; i < 400; ++i) xy.push_back(u(rng)), xy.push_back(u(rng) * 0.8 + 0.1);
  std::vector<uint32_t> all(xy.size() / 2);
  std::iota(all.begin(), all.end(), 0u);
  uint32_t corner = 0;
  Result<Triangulation> dt = delaunay_in_box(xy, all, &corner);
  ASSERT_TRUE(dt.ok());
  // Drop cloud points on the segments' lines is unlikely with random doubles.
  const std::vector<uint32_t> seg = {0, 1, 1, 2, 2, 3, 3, 4};
  ConformingStats stats;
  ASSERT_TRUE(recover_segments(dt.value(), seg, {0, 1, 2, 3}, &stats).ok());
  EXPECT_GT(stats.steiner, 0u);
  ASSERT_TRUE(check_triangulation(dt.value()).ok());
  std::vector<uint32_t> chain;
  for (int s = 0; s < 4; ++s) {
    ASSERT_TRUE(chain_vertices(dt.value(), seg[2 * size_t(s)], seg[2 * size_t(s) + 1], s, chain).ok());
    for (uint32_t v : chain)  // every piece's vertex lies on the segment (to rounding)
      EXPECT_NEAR(std::fabs(predicates::orient2d(dt->point(seg[2 * size_t(s)]), dt->point(seg[2 * size_t(s) + 1]), dt->point(v))), 0, 1);
  }
  std::vector<uint32_t> face;
  EXPECT_EQ(label_faces(dt.value(), face), 1u);  // the zig-zag is open: one face
}

TEST(Mesh2dKernel, FlipKeepsTheTriangulationValid) {
  const std::vector<double> xy = {0, 0, 1, 0, 1.2, 1, 0, 1};
  Result<Triangulation> m = build_triangulation(xy, {0, 1, 2, 0, 2, 3});
  ASSERT_TRUE(m.ok());
  Kernel kernel(m.value());
  uint32_t t;
  int k;
  ASSERT_TRUE(m->find_edge(0, 2, t, k));
  ASSERT_TRUE(kernel.flip(t, k));
  ASSERT_TRUE(check_triangulation(m.value()).ok()) << check_triangulation(m.value()).message();
  EXPECT_TRUE(m->find_edge(1, 3, t, k) || m->find_edge(3, 1, t, k));
}

}  // namespace
}  // namespace anitet::mesh2d

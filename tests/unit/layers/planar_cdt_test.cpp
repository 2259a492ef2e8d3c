// The planar constrained triangulation that re-triangulates slide patches: the region covered
// exactly (area, every segment an edge, triangles counter-clockwise), holes left empty, bad
// input refused.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "layers/planar_cdt.hpp"

namespace anitet::layers {
namespace {

double area(const std::vector<double>& xy, const std::vector<uint32_t>& tri) {
  double a = 0.0;
  for (size_t i = 0; i < tri.size(); i += 3) {
    const double* p = &xy[2 * tri[i]];
    const double* q = &xy[2 * tri[i + 1]];
    const double* r = &xy[2 * tri[i + 2]];
    const double s = 0.5 * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
    EXPECT_GT(s, 0.0);
    a += s;
  }
  return a;
}

// Every segment is a directed edge of exactly one triangle; every inner edge of two.
void expect_conforming(const std::vector<uint32_t>& tri, const std::vector<std::pair<uint32_t, uint32_t>>& seg) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t i = 0; i < tri.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++directed[{tri[i + k], tri[i + (k + 1) % 3]}];
  for (const auto& s : seg) {
    EXPECT_EQ(directed[s], 1) << s.first << " " << s.second;
    EXPECT_EQ(directed.count({s.second, s.first}), 0u);
  }
  std::set<std::pair<uint32_t, uint32_t>> boundary(seg.begin(), seg.end());
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    if (!boundary.count(e)) {
      EXPECT_EQ(directed.count({e.second, e.first}), 1u) << e.first << " " << e.second;
    }
  }
}

TEST(PlanarCdt, SquareWithHoleAndInnerPoints) {
  // Outer square 0..4 counter-clockwise, inner square 1..3 clockwise (a hole), random points in
  // the ring and in the hole (those unused).
  std::vector<double> xy = {0, 0, 4, 0, 4, 4, 0, 4, 1, 1, 1, 3, 3, 3, 3, 1};
  std::vector<std::pair<uint32_t, uint32_t>> seg = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.05, 3.95);
  size_t in_hole = 0;
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    xy.insert(xy.end(), {x, y});
    in_hole += x > 1 && x < 3 && y > 1 && y < 3;
  }
  Result<std::vector<uint32_t>> tri = triangulate_region(xy, seg);
  ASSERT_TRUE(tri.ok()) << tri.status().message();
  EXPECT_NEAR(area(xy, tri.value()), 12.0, 1e-12);
  expect_conforming(tri.value(), seg);
  std::set<uint32_t> used(tri->begin(), tri->end());
  EXPECT_EQ(used.size(), 8 + 200 - in_hole);
}

TEST(PlanarCdt, ThinBandAndCollinearPoints) {
  // A strip 1 x 1e-4 on the bottom of a unit square, its top a constraint chain of collinear
  // points: the segments are recovered however thin the triangles.
  std::vector<double> xy;
  const int n = 20;
  for (int i = 0; i <= n; ++i) xy.insert(xy.end(), {double(i) / n, 1e-4});
  xy.insert(xy.end(), {1, 1, 0, 1, 0.5, 0.5, 0.3, 0.2, 0.7, 0.8});
  std::vector<std::pair<uint32_t, uint32_t>> seg;
  for (uint32_t i = 0; i < uint32_t(n); ++i) seg.emplace_back(i, i + 1);
  seg.emplace_back(n, n + 1);
  seg.emplace_back(n + 1, n + 2);
  seg.emplace_back(n + 2, 0);
  Result<std::vector<uint32_t>> tri = triangulate_region(xy, seg);
  ASSERT_TRUE(tri.ok()) << tri.status().message();
  EXPECT_NEAR(area(xy, tri.value()), 1.0 - 1e-4, 1e-12);
  expect_conforming(tri.value(), seg);
}

TEST(PlanarCdt, RefusesBadInput) {
  const std::vector<double> square = {0, 0, 1, 0, 1, 1, 0, 1};
  // Not closed.
  EXPECT_FALSE(triangulate_region(square, {{0, 1}, {1, 2}, {2, 3}}).ok());
  // A point on a segment.
  std::vector<double> on = square;
  on.insert(on.end(), {0.5, 0.0});
  EXPECT_FALSE(triangulate_region(on, {{0, 1}, {1, 2}, {2, 3}, {3, 0}}).ok());
  // A point twice.
  std::vector<double> twice = square;
  twice.insert(twice.end(), {1, 1});
  EXPECT_FALSE(triangulate_region(twice, {{0, 1}, {1, 2}, {2, 3}, {3, 0}}).ok());
  // Crossing segments (a bow tie).
  EXPECT_FALSE(triangulate_region(square, {{0, 2}, {2, 1}, {1, 3}, {3, 0}}).ok());
}

}  // namespace
}  // namespace anitet::layers

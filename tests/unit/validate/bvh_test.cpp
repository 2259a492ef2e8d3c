#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "core/bvh.hpp"

namespace anitet {
namespace {

struct Soup {
  std::vector<double> xyz;
  std::vector<uint32_t> tri;
};

// Random small triangles in a unit box (boxes overlap often enough to matter).
Soup random_soup(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(0.0, 1.0), off(-0.05, 0.05);
  Soup s;
  for (size_t t = 0; t < n; ++t) {
    const double c[3] = {pos(rng), pos(rng), pos(rng)};
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d) s.xyz.push_back(c[d] + off(rng));
      s.tri.push_back(static_cast<uint32_t>(3 * t + k));
    }
  }
  return s;
}

bool overlap(const Box3& a, const Box3& b) {
  for (int k = 0; k < 3; ++k) {
    if (a.lo[k] > b.hi[k] || b.lo[k] > a.hi[k]) return false;
  }
  return true;
}

TEST(TriangleBVH, OverlappingPairsMatchBruteForce) {
  for (size_t n : {0u, 1u, 2u, 5u, 37u, 600u}) {
    const Soup s = random_soup(n, 7 + unsigned(n));
    TriangleBVH bvh;
    bvh.build(s.xyz.data(), s.tri.data(), n);
    ASSERT_EQ(bvh.num_triangles(), n);
    std::vector<std::pair<uint32_t, uint32_t>> got, want;
    bvh.overlapping_pairs([&](uint32_t i, uint32_t j) {
      EXPECT_LT(i, j);
      got.emplace_back(i, j);
      return true;
    });
    for (uint32_t i = 0; i < n; ++i) {
      for (uint32_t j = i + 1; j < n; ++j) {
        if (overlap(bvh.triangle_box(i), bvh.triangle_box(j))) want.emplace_back(i, j);
      }
    }
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << "n = " << n;
    if (n == 600) {
      EXPECT_GT(want.size(), 100u);  // the test has something to find
    }
  }
}

TEST(TriangleBVH, QueryMatchesBruteForceAndStopsEarly) {
  const Soup s = random_soup(500, 3);
  TriangleBVH bvh;
  bvh.build(s.xyz.data(), s.tri.data(), 500);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(-0.1, 1.1);
  for (int q = 0; q < 50; ++q) {
    Box3 box;
    for (int k = 0; k < 3; ++k) {
      const double a = pos(rng), b = pos(rng);
      box.lo[k] = std::min(a, b);
      box.hi[k] = std::min(a, b) + 0.2 * std::fabs(a - b);
    }
    std::vector<uint32_t> got, want;
    bvh.query(box, [&](uint32_t t) {
      got.push_back(t);
      return true;
    });
    for (uint32_t t = 0; t < 500; ++t) {
      if (overlap(bvh.triangle_box(t), box)) want.push_back(t);
    }
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want);
  }
  Box3 all{{-1, -1, -1}, {2, 2, 2}};
  int visits = 0;
  bvh.query(all, [&](uint32_t) { return ++visits < 3; });
  EXPECT_EQ(visits, 3);
  visits = 0;
  bvh.overlapping_pairs([&](uint32_t, uint32_t) { return ++visits < 5; });
  EXPECT_EQ(visits, 5);
}

TEST(TriangleBVH, TouchingBoxesCount) {
  // Two triangles whose boxes touch in one plane (x = 1): closed boxes overlap.
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 0, 0, 2, 0, 0, 1, 1, 0};
  const std::vector<uint32_t> tri = {0, 1, 2, 3, 4, 5};
  TriangleBVH bvh;
  bvh.build(xyz.data(), tri.data(), 2);
  int pairs = 0;
  bvh.overlapping_pairs([&](uint32_t, uint32_t) { return ++pairs > 0; });
  EXPECT_EQ(pairs, 1);
  EXPECT_EQ(bvh.triangle_box(1).lo[0], 1.0);
  EXPECT_EQ(bvh.triangle_box(1).hi[0], 2.0);
}

}  // namespace
}  // namespace anitet

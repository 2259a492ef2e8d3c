#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "delaunay/spatial_sort.hpp"
#include "test_points.hpp"

namespace anitet::delaunay_detail {
namespace {

// Every cell of a 2^bits grid gets its own position, and cells at consecutive positions share a
// face: the defining properties of a Hilbert curve.
TEST(HilbertIndex, VisitsEveryCellOnceThroughFaceNeighbours) {
  for (int bits = 1; bits <= 4; ++bits) {
    const uint32_t side = 1u << bits;
    const size_t cells = size_t(side) * side * side;
    std::vector<int64_t> cell_at(cells, -1);
    for (uint32_t x = 0; x < side; ++x)
      for (uint32_t y = 0; y < side; ++y)
        for (uint32_t z = 0; z < side; ++z) {
          const uint64_t h = hilbert_index(x, y, z, bits);
          ASSERT_LT(h, cells);
          ASSERT_EQ(cell_at[h], -1) << "two cells at position " << h;
          cell_at[h] = (int64_t(x) * side + y) * side + z;
        }
    for (size_t h = 1; h < cells; ++h) {
      const int64_t a = cell_at[h - 1], b = cell_at[h];
      const int64_t dist = std::llabs(a / (side * side) - b / (side * side)) +
                           std::llabs((a / side) % side - (b / side) % side) +
                           std::llabs(a % side - b % side);
      EXPECT_EQ(dist, 1) << "bits " << bits << ", positions " << h - 1 << " and " << h;
    }
  }
}

TEST(BrioOrder, IsADeterministicPermutation) {
  const std::vector<double> xyz = test::random_cube(5000, 7);
  BrioOptions options;
  const std::vector<uint32_t> a = brio_order(xyz.data(), 5000, options);
  const std::vector<uint32_t> b = brio_order(xyz.data(), 5000, options);
  EXPECT_EQ(a, b);
  std::vector<uint32_t> sorted = a;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < 5000; ++i) ASSERT_EQ(sorted[i], i);
  options.seed = 99;
  EXPECT_NE(brio_order(xyz.data(), 5000, options), a);
}

// Inside a round, consecutive points are close: the mean step along the order is far below the
// mean distance between random points (~0.66 in the unit cube).
TEST(BrioOrder, RoundsAreSpatiallyCoherent) {
  const size_t n = 20000;
  const std::vector<double> xyz = test::random_cube(n, 3);
  const std::vector<uint32_t> order = brio_order(xyz.data(), n, BrioOptions{});
  double total = 0;
  for (size_t k = n / 2 + 1; k < n; ++k) {  // the last round
    const double* p = &xyz[3 * size_t(order[k - 1])];
    const double* q = &xyz[3 * size_t(order[k])];
    total += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]));
  }
  EXPECT_LT(total / double(n / 2 - 1), 0.1);
}

// hilbert_sort on its own (for later stages that insert batches of points): a permutation whose
// consecutive points are close.
TEST(HilbertSort, OrdersABatchAlongTheCurve) {
  const size_t n = 5000;
  const std::vector<double> xyz = test::random_cube(n, 4);
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = n - 1 - i;
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  hilbert_sort(xyz.data(), order.data(), n, lo, hi);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i);
  double total = 0;
  for (size_t k = 1; k < n; ++k) {
    const double* p = &xyz[3 * size_t(order[k - 1])];
    const double* q = &xyz[3 * size_t(order[k])];
    total += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]));
  }
  EXPECT_LT(total / double(n - 1), 0.1);
}

}  // namespace
}  // namespace anitet::delaunay_detail

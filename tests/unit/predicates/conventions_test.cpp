// Sign conventions, symmetries, counters and non-finite inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <thread>

#include "generators.hpp"
#include "predicates/predicates.hpp"
#include "reference.hpp"

namespace anitet::predicates::testing {
namespace {

const double kO[3] = {0, 0, 0}, kX[3] = {1, 0, 0}, kY[3] = {0, 1, 0}, kZ[3] = {0, 0, 1};

TEST(PredicatesConventions, Orientation) {
  EXPECT_EQ(orient2d(kO, kX, kY), 1);  // counter-clockwise
  EXPECT_EQ(orient2d(kO, kY, kX), -1);
  EXPECT_EQ(orient2d(kO, kX, kX), 0);
  EXPECT_EQ(orient3d(kO, kX, kY, kZ), 1);  // (b-a) x (c-a) . (d-a) = +1
  EXPECT_EQ(orient3d(kO, kY, kX, kZ), -1);
  const double in_plane[3] = {3, -7, 0};
  EXPECT_EQ(orient3d(kO, kX, kY, in_plane), 0);
}

TEST(PredicatesConventions, Insphere) {
  // Circumsphere of the positive tet O,X,Y,Z: center (1/2,1/2,1/2), radius^2 3/4.
  const double inside[3] = {0.25, 0.25, 0.25}, outside[3] = {2, 2, 2}, on[3] = {1, 1, 0};
  ASSERT_EQ(orient3d(kO, kX, kY, kZ), 1);
  EXPECT_EQ(insphere(kO, kX, kY, kZ, inside), 1);
  EXPECT_EQ(insphere(kO, kX, kY, kZ, outside), -1);
  EXPECT_EQ(insphere(kO, kX, kY, kZ, on), 0);
  // A negative tet flips the answer.
  EXPECT_EQ(insphere(kO, kY, kX, kZ, inside), -1);
  auto lift = [](const double* p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2]; };
  for (const double* e : {inside, outside, on}) {
    EXPECT_EQ(orient4d(kO, kX, kY, kZ, e, lift(kO), lift(kX), lift(kY), lift(kZ), lift(e)),
              -insphere(kO, kX, kY, kZ, e));
  }
  // orient4d is the 4D orientation of the lifted points: e lifted far up is on the positive side.
  EXPECT_EQ(orient4d(kO, kX, kY, kZ, inside, 0, 0, 0, 0, 1), 1);
  EXPECT_EQ(orient4d(kO, kX, kY, kZ, inside, 0, 0, 0, 0, -1), -1);
}

TEST(PredicatesConventions, Incircle) {
  // Circle of the counter-clockwise O, X, Y: centre (1/2, 1/2), radius^2 1/2.
  const double inside[2] = {0.5, 0.5}, outside[2] = {2, 2}, on[2] = {1, 1};
  EXPECT_EQ(incircle(kO, kX, kY, inside), 1);
  EXPECT_EQ(incircle(kO, kX, kY, outside), -1);
  EXPECT_EQ(incircle(kO, kX, kY, on), 0);
  EXPECT_EQ(incircle(kO, kY, kX, inside), -1);  // clockwise flips the answer
  EXPECT_EQ(detail::incircle_exact(kO, kX, kY, inside), 1);
  EXPECT_EQ(detail::incircle_exact(kO, kX, kY, outside), -1);
  const double nan[2] = {std::numeric_limits<double>::quiet_NaN(), 0};
  EXPECT_EQ(incircle(kO, kX, kY, nan), 0);
}

int permutation_parity(const std::array<int, 5>& p) {
  int inversions = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j)
      if (p[size_t(i)] > p[size_t(j)]) ++inversions;
  return inversions % 2 == 0 ? 1 : -1;
}

// insphere and orient4d are alternating functions of their five points (orient3d of its four):
// exact evaluation must respect that on every permutation, degenerate or not.
TEST(PredicatesConventions, AlternatingUnderPermutation) {
  Rng rng(11);
  const int n = 3000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    const auto pts = cospherical_case(rng);
    double h[5];
    for (int j = 0; j < 5; ++j)
      h[j] = pts[size_t(j)][0] * pts[size_t(j)][0] + pts[size_t(j)][1] * pts[size_t(j)][1] +
             pts[size_t(j)][2] * pts[size_t(j)][2];
    std::array<int, 5> perm = {0, 1, 2, 3, 4};
    const int s0 = insphere(pts[0].data(), pts[1].data(), pts[2].data(), pts[3].data(),
                            pts[4].data());
    const int o0 = orient4d(pts[0].data(), pts[1].data(), pts[2].data(), pts[3].data(),
                            pts[4].data(), h[0], h[1], h[2], h[3], h[4]);
    const int r0 = orient3d(pts[0].data(), pts[1].data(), pts[2].data(), pts[3].data());
    do {
      const double* q[5];
      double hq[5];
      for (int j = 0; j < 5; ++j) {
        q[j] = pts[size_t(perm[size_t(j)])].data();
        hq[j] = h[perm[size_t(j)]];
      }
      const int parity = permutation_parity(perm);
      ASSERT_EQ(parity * insphere(q[0], q[1], q[2], q[3], q[4]), s0);
      ASSERT_EQ(parity * orient4d(q[0], q[1], q[2], q[3], q[4], hq[0], hq[1], hq[2], hq[3], hq[4]),
                o0);
      if (perm[4] == 4) {
        ASSERT_EQ(parity * orient3d(q[0], q[1], q[2], q[3]), r0);
      }
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
}

TEST(PredicatesCounters, CountCallsAndExactFallbacks) {
  reset_thread_counters();
  const double in_plane[3] = {3, -7, 0};
  orient3d(kO, kX, kY, kZ);
  EXPECT_EQ(thread_counters().orient3d_calls, 1u);
  EXPECT_EQ(thread_counters().orient3d_exact, 0u);
  orient3d(kO, kX, kY, in_plane);
  EXPECT_EQ(thread_counters().orient3d_calls, 2u);
  EXPECT_EQ(thread_counters().orient3d_exact, 1u);
  const double on[3] = {1, 1, 0}, inside[3] = {0.25, 0.25, 0.25};
  insphere(kO, kX, kY, kZ, inside);
  insphere(kO, kX, kY, kZ, on);
  EXPECT_EQ(thread_counters().insphere_calls, 2u);
  EXPECT_EQ(thread_counters().insphere_exact, 1u);
  EXPECT_EQ(thread_counters().sos_ties, 0u);
  EXPECT_NE(insphere_sos(kO, kX, kY, kZ, on, 0, 1, 2, 3, 4), 0);
  EXPECT_EQ(thread_counters().sos_ties, 1u);
  EXPECT_NE(insphere_sos(kO, kX, kY, kZ, inside, 0, 1, 2, 3, 4), 0);
  EXPECT_EQ(thread_counters().sos_ties, 1u);
  orient2d(kO, kX, kY);
  orient2d(kO, kX, kX);
  EXPECT_EQ(thread_counters().orient2d_calls, 2u);
  EXPECT_EQ(thread_counters().orient2d_exact, 1u);
  orient4d(kO, kX, kY, kZ, on, 0, 1, 1, 1, 2);
  EXPECT_EQ(thread_counters().orient4d_calls, 1u);
  EXPECT_EQ(thread_counters().orient4d_exact, 1u);
  reset_thread_counters();
  EXPECT_EQ(thread_counters().orient3d_calls, 0u);
}

TEST(PredicatesCounters, PerThread) {
  reset_thread_counters();
  orient3d(kO, kX, kY, kZ);
  uint64_t other_calls = 99;
  std::thread worker([&] {
    orient3d(kO, kX, kY, kZ);
    orient3d(kO, kX, kY, kZ);
    other_calls = thread_counters().orient3d_calls;
  });
  worker.join();
  EXPECT_EQ(other_calls, 2u);
  EXPECT_EQ(thread_counters().orient3d_calls, 1u);
}

// orient3d_certified: a point off a tilted plane by rounding only is valid for the exact test but
// not certified; a clear one is; a certified sign never disagrees with the exact one.
TEST(PredicatesConventions, Orient3dCertified) {
  const double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1};
  const double third = 1.0 / 3.0;  // rounded down: (t, t, t) is off the plane x + y + z = 1
  const double near[3] = {third, third, third};
  ASSERT_NE(orient3d(a, b, c, near), 0);
  EXPECT_EQ(orient3d_certified(a, b, c, near), 0);
  const double above[3] = {third, third, third + 1e-3}, below[3] = {third, third, third - 1e-3};
  EXPECT_EQ(orient3d_certified(a, b, c, above), orient3d(a, b, c, above));
  EXPECT_EQ(orient3d_certified(a, b, c, below), orient3d(a, b, c, below));
  EXPECT_NE(orient3d_certified(a, b, c, above), 0);
  uint64_t seed = 12345;
  auto unit = [&seed] {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return double(seed >> 11) * 0x1p-53;
  };
  int certified = 0;
  for (int i = 0; i < 20000; ++i) {
    double p[4][3];
    for (auto& q : p)
      for (double& x : q) x = unit();
    // Every other tet nearly flat: its last point moved onto the plane of the first three.
    if (i % 2) {
      const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
      const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
      for (int k = 0; k < 3; ++k) p[3][k] = p[0][k] + 0.3 * u[k] + 0.4 * v[k];
    }
    const int s = orient3d_certified(p[0], p[1], p[2], p[3]);
    if (s != 0) {
      ++certified;
      EXPECT_EQ(s, orient3d(p[0], p[1], p[2], p[3]));
    }
  }
  EXPECT_GT(certified, 9000);
  EXPECT_LT(certified, 11000);
}

TEST(PredicatesConventions, NonFiniteGivesZero) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf, -inf}) {
    for (int k = 0; k < 3; ++k) {
      double p[3] = {0.3, 0.2, 0.1};
      p[k] = bad;
      if (k < 2) {  // orient2d reads x and y only
        EXPECT_EQ(orient2d(kO, kX, p), 0);
        EXPECT_EQ(orient2d(p, kX, kY), 0);
      }
      EXPECT_EQ(orient3d(kO, kX, kY, p), 0);
      EXPECT_EQ(orient3d(p, kX, kY, kZ), 0);
      EXPECT_EQ(insphere(kO, kX, kY, kZ, p), 0);
      EXPECT_EQ(insphere(p, kX, kY, kZ, kO), 0);
      EXPECT_EQ(orient4d(kO, kX, kY, kZ, p, 0, 1, 2, 3, 4), 0);
    }
    const double q[3] = {0.3, 0.2, 0.1};
    EXPECT_EQ(orient4d(kO, kX, kY, kZ, q, 0, 1, bad, 3, 4), 0);
    const double both[3] = {bad, bad, bad};
    EXPECT_EQ(orient3d(both, both, kY, kZ), 0);
  }
}

}  // namespace
}  // namespace anitet::predicates::testing

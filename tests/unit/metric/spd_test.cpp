#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "metric/combine.hpp"
#include "metric/spd.hpp"
#include "test_util.hpp"

namespace anitet {
namespace metric {
namespace {

using test::random_spd;

TEST(Spd, LogExpRoundTrip) {
  std::mt19937_64 rng(1);
  for (int n = 0; n < 1000; ++n) {
    double m[6], l[6], back[6];
    random_spd(rng, 1e-3, 1e2, m);
    ASSERT_TRUE(sym_log(m, l));
    sym_exp(l, back);
    EXPECT_LT(test::max_rel_diff(back, m), 1e-11);
  }
}

TEST(Spd, ExpMatchesEigenDecomposition) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-8.0, 8.0);
  for (int n = 0; n < 1000; ++n) {
    double l[6], e[6], val[3], vec[9], ref[6];
    for (double& x : l) x = u(rng);
    sym_exp(l, e);
    sym_eigen(l, val, vec);
    const int idx[6][2] = {{0, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}, {2, 2}};
    for (int c = 0; c < 6; ++c) {
      ref[c] = 0.0;
      for (int k = 0; k < 3; ++k)
        ref[c] += std::exp(val[k]) * vec[3 * k + idx[c][0]] * vec[3 * k + idx[c][1]];
    }
    EXPECT_LT(test::max_rel_diff(e, ref), 1e-12);
  }
}

TEST(Spd, LogRejectsNonSpd) {
  const double indefinite[6] = {1, 2, 1, 0, 0, 1};
  const double nan[6] = {1, 0, 1, 0, 0, NAN};
  double l[6];
  EXPECT_FALSE(sym_log(indefinite, l));
  EXPECT_FALSE(sym_log(nan, l));
  EXPECT_FALSE(is_spd(indefinite));
}

TEST(Spd, IntersectionIsContainedInBothAndTight) {
  std::mt19937_64 rng(3);
  for (int n = 0; n < 1000; ++n) {
    double a[6], b[6], m[6];
    random_spd(rng, 1e-2, 1e1, a);
    random_spd(rng, 1e-2, 1e1, b);
    ASSERT_TRUE(intersect(a, b, m));
    ASSERT_TRUE(is_spd(m));
    // Contained in both unit balls: M - A and M - B positive semi-definite ...
    const double da = test::min_eig_diff(m, a), db = test::min_eig_diff(m, b);
    EXPECT_GT(da, -1e-10);
    EXPECT_GT(db, -1e-10);
    // ... and the largest such ellipsoid: it touches both (a zero eigenvalue in each difference)
    // unless one input contains the other.
    EXPECT_LT(std::min(da, db), 1e-9);
  }
}

TEST(Spd, IntersectionOfNestedMetricsIsTheInnerOne) {
  std::mt19937_64 rng(4);
  for (int n = 0; n < 1000; ++n) {
    double a[6], extra[6], b[6], m1[6], m2[6];
    random_spd(rng, 1e-2, 1e1, a);
    random_spd(rng, 1e-1, 1e1, extra);
    for (int i = 0; i < 6; ++i) b[i] = a[i] + extra[i];  // b's ball lies inside a's
    ASSERT_TRUE(intersect(a, b, m1));
    ASSERT_TRUE(intersect(b, a, m2));
    EXPECT_LT(test::max_rel_diff(m1, b), 1e-10);
    EXPECT_LT(test::max_rel_diff(m2, b), 1e-10);
    ASSERT_TRUE(intersect(a, a, m1));
    EXPECT_LT(test::max_rel_diff(m1, a), 1e-10);
  }
}

TEST(Spd, IntersectionOfIsotropicMetricsTakesTheSmallerSize) {
  double a[6] = {4, 0, 4, 0, 0, 4}, b[6] = {1, 0, 1, 0, 0, 1}, m[6];
  ASSERT_TRUE(intersect(a, b, m));
  EXPECT_LT(test::max_rel_diff(m, a), 1e-15);
}

TEST(Spd, ClampSizesKeepsDirections) {
  // Sizes 0.01 and 100 along x and y, 1 along z; bounds [0.1, 10].
  const double m[6] = {1e4, 0, 1e-4, 0, 0, 1}, want[6] = {1e2, 0, 1e-2, 0, 0, 1};
  double c[6];
  ASSERT_TRUE(clamp_sizes(m, 0.1, 10.0, c));
  EXPECT_LT(test::max_rel_diff(c, want), 1e-12);
}

}  // namespace
}  // namespace metric
}  // namespace anitet


namespace anitet {
namespace metric {
namespace {

TEST(Combine, IntersectionAndBoundsOfFields) {
  AnalyticField fine([](const double p[3], double m[6]) { isotropic_metric(0.1 + p[0], m); });
  AnalyticField stretched([](const double*, double m[6]) {
    const double s[6] = {1.0 / (0.05 * 0.05), 0, 1.0, 0, 0, 1.0};  // 0.05 along x, 1 elsewhere
    std::copy(s, s + 6, m);
  });
  IntersectionField both({&fine, &stretched});
  BoundedField bounded(both, 0.08, 0.5);
  const double p[3] = {0.2, 0, 0};
  double m[6], a[6], b[6];
  both.metric(p, m);
  fine.metric(p, a);
  stretched.metric(p, b);
  EXPECT_GT(test::min_eig_diff(m, a), -1e-12);
  EXPECT_GT(test::min_eig_diff(m, b), -1e-12);
  EXPECT_NEAR(1.0 / std::sqrt(m[0]), 0.05, 1e-12);  // the stretched field's x size
  EXPECT_NEAR(1.0 / std::sqrt(m[2]), 0.3, 1e-12);   // the fine field's size elsewhere
  bounded.metric(p, m);
  EXPECT_NEAR(1.0 / std::sqrt(m[0]), 0.08, 1e-12);  // hmin
  EXPECT_NEAR(1.0 / std::sqrt(m[5]), 0.3, 1e-12);
}

}  // namespace
}  // namespace metric
}  // namespace anitet

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>
#include <algorithm>

#include "quality/tet_measures.hpp"

namespace anitet {
namespace {

const double kPi = 3.14159265358979323846;
double deg(double rad) { return rad * 180.0 / kPi; }

// Reference radius ratio computed differently from the library: circumcentre by Cramer's rule,
// inradius from 3V / total face area.
double reference_radius_ratio(const double* a, const double* b, const double* c, const double* d) {
  double e[3][3], rhs[3];
  const double* q[3] = {b, c, d};
  for (int i = 0; i < 3; ++i) {
    rhs[i] = 0.0;
    for (int k = 0; k < 3; ++k) {
      e[i][k] = q[i][k] - a[k];
      rhs[i] += 0.5 * e[i][k] * e[i][k];
    }
  }
  auto det3 = [](double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double det = det3(e);
  double centre[3];
  for (int k = 0; k < 3; ++k) {
    double m[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) m[i][j] = j == k ? rhs[i] : e[i][j];
    centre[k] = det3(m) / det;
  }
  const double circum = std::sqrt(centre[0] * centre[0] + centre[1] * centre[1] + centre[2] * centre[2]);
  auto area = [](const double* p, const double* r, const double* s) {
    const double u[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]}, v[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  };
  const double total = area(b, c, d) + area(a, c, d) + area(a, b, d) + area(a, b, c);
  const double inr = 3.0 * std::fabs(det / 6.0) / total;
  return 3.0 * inr / circum;
}

TEST(TetMeasures, RegularTetIsOne) {
  const double a[3] = {1, 1, 1}, b[3] = {1, -1, -1}, c[3] = {-1, 1, -1}, d[3] = {-1, -1, 1};
  const TetMeasures m = tet_measures(a, b, c, d);
  const double s = std::sqrt(8.0);  // edge length
  EXPECT_NEAR(std::fabs(m.volume), s * s * s / (6.0 * std::sqrt(2.0)), 1e-14);
  EXPECT_NEAR(m.radius_ratio, 1.0, 1e-14);
  EXPECT_NEAR(m.mean_ratio, 1.0, 1e-14);
  EXPECT_NEAR(m.min_dihedral_deg, deg(std::acos(1.0 / 3.0)), 1e-12);
  EXPECT_NEAR(m.max_dihedral_deg, deg(std::acos(1.0 / 3.0)), 1e-12);
}

TEST(TetMeasures, CornerTetHandComputed) {
  // (0,0,0) (1,0,0) (0,1,0) (0,0,1): V = 1/6, sum l^2 = 9, r_in = 1/(3+sqrt 3), R = sqrt(3)/2.
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0, 0, 1};
  const TetMeasures m = tet_measures(a, b, c, d);
  EXPECT_NEAR(m.volume, 1.0 / 6.0, 1e-16);
  EXPECT_NEAR(m.radius_ratio, std::sqrt(3.0) - 1.0, 1e-15);
  EXPECT_NEAR(m.mean_ratio, 12.0 * std::cbrt(0.25) / 9.0, 1e-15);  // (3V)^(2/3) = 0.5^(2/3)
  EXPECT_NEAR(m.min_dihedral_deg, deg(std::acos(1.0 / std::sqrt(3.0))), 1e-12);
  EXPECT_NEAR(m.max_dihedral_deg, 90.0, 1e-12);
}

TEST(TetMeasures, InvertedHasNegativeVolumeSameShape) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0.2, 0.3, 0.7};
  const TetMeasures pos = tet_measures(a, b, c, d);
  const TetMeasures neg = tet_measures(b, a, c, d);
  EXPECT_GT(pos.volume, 0.0);
  EXPECT_DOUBLE_EQ(neg.volume, -pos.volume);
  EXPECT_NEAR(neg.radius_ratio, pos.radius_ratio, 1e-15);
  EXPECT_NEAR(neg.mean_ratio, pos.mean_ratio, 1e-15);
  EXPECT_NEAR(neg.min_dihedral_deg, pos.min_dihedral_deg, 1e-12);
  EXPECT_NEAR(neg.max_dihedral_deg, pos.max_dihedral_deg, 1e-12);
  EXPECT_DOUBLE_EQ(tet_signed_volume(b, a, c, d), neg.volume);
}

TEST(TetMeasures, FlatTetIsZero) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0.3, 0.3, 0};
  const TetMeasures m = tet_measures(a, b, c, d);
  EXPECT_EQ(m.volume, 0.0);
  EXPECT_EQ(m.radius_ratio, 0.0);
  EXPECT_EQ(m.mean_ratio, 0.0);
  EXPECT_NEAR(m.min_dihedral_deg, 0.0, 1e-12);
  EXPECT_NEAR(m.max_dihedral_deg, 180.0, 1e-12);
}

TEST(TetMeasures, SliverHasGoodEdgesButNoVolume) {
  // Four points near the equator of the unit sphere: edges fine, radius ratio tiny.
  const double h = 1e-3;
  const double a[3] = {1, 0, h}, b[3] = {0, 1, -h}, c[3] = {-1, 0, h}, d[3] = {0, -1, -h};
  const TetMeasures m = tet_measures(a, b, c, d);
  EXPECT_LT(m.radius_ratio, 0.01);
  EXPECT_GT(m.radius_ratio, 0.0);
  EXPECT_LT(m.mean_ratio, 0.05);  // (volume)^(2/3): falls slower than the radius ratio
  EXPECT_LT(m.min_dihedral_deg, 1.0);
  EXPECT_GT(m.max_dihedral_deg, 179.0);
  EXPECT_NEAR(m.radius_ratio, reference_radius_ratio(a, b, c, d), 1e-9);
  // Hand computed: |det| = 8h, so 3V = 4h; side edges 2 + 4h^2 each, diagonals 4 each.
  const double l2sum = 4 * (2.0 + 4 * h * h) + 2 * 4.0;  // four side edges, two diagonals
  EXPECT_NEAR(m.mean_ratio, 12.0 * std::pow(4.0 * h, 2.0 / 3.0) / l2sum, 1e-15);
}

TEST(TetMeasures, AgreesWithIndependentFormulaOnRandomTets) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    double p[4][3];
    for (auto& q : p)
      for (double& x : q) x = u(rng);
    const TetMeasures m = tet_measures(p[0], p[1], p[2], p[3]);
    const double ref = reference_radius_ratio(p[0], p[1], p[2], p[3]);
    // Cramer's rule loses accuracy on flat tets: compare relative to how flat the tet is.
    EXPECT_NEAR(m.radius_ratio, ref, 1e-10 / std::max(ref, 1e-3)) << "tet " << k;
    EXPECT_LE(m.radius_ratio, 1.0 + 1e-12);
    EXPECT_LE(m.mean_ratio, 1.0 + 1e-12);
    EXPECT_LE(m.min_dihedral_deg, m.max_dihedral_deg);
    EXPECT_LE(m.min_dihedral_deg, deg(std::acos(1.0 / 3.0)) + 1e-9);  // the regular tet maximises it
  }
}

TEST(TetMeasures, KeyedMeasuresOrderTheLargestDihedralsAsTheirAngles) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::pair<double, double>> key_angle;
  for (int k = 0; k < 1000; ++k) {
    double p[4][3];
    for (auto& q : p)
      for (double& x : q) x = u(rng);
    const TetMeasures m = tet_measures(p[0], p[1], p[2], p[3]);
    double key = -1.0;
    const TetMeasures n = tet_measures_keyed(p[0], p[1], p[2], p[3], key);
    EXPECT_EQ(n.volume, m.volume);
    EXPECT_EQ(n.radius_ratio, m.radius_ratio);
    EXPECT_EQ(n.mean_ratio, m.mean_ratio);
    EXPECT_EQ(n.min_dihedral_deg, m.min_dihedral_deg);
    EXPECT_GE(key, 0.0);
    EXPECT_LE(key, 2.0);
    EXPECT_NEAR(max_dihedral_from_key(key), m.max_dihedral_deg, 1e-11) << "tet " << k;
    key_angle.emplace_back(key, m.max_dihedral_deg);
  }
  std::sort(key_angle.begin(), key_angle.end());
  for (size_t k = 1; k < key_angle.size(); ++k) EXPECT_LE(key_angle[k - 1].second, key_angle[k].second + 1e-11);
  // The ends: 0, 90 and 180 degrees.
  EXPECT_EQ(max_dihedral_from_key(0.0), 0.0);
  EXPECT_NEAR(max_dihedral_from_key(1.0), 90.0, 1e-13);
  EXPECT_NEAR(max_dihedral_from_key(2.0), 180.0, 1e-13);
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0}, d[3] = {0.3, 0.3, 0};
  double flat_key = 0.0;
  tet_measures_keyed(a, b, c, d, flat_key);
  EXPECT_NEAR(max_dihedral_from_key(flat_key), 180.0, 1e-12);
}

TEST(TetMeasures, NearlyFlatTetsStayBelowTheirBound) {
  // Four points on a circle of radius 0.1 at 1000 from the origin, lifted by at most 1e-13: the
  // volume and the circumradius product are both rounding noise (the ratio once came out 75).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586), lift(-1e-13, 1e-13);
  size_t positive = 0;
  for (int k = 0; k < 2000; ++k) {
    double p[4][3];
    for (auto& q : p) {
      const double t = angle(rng);
      q[0] = 1000.0 + 0.1 * std::cos(t);
      q[1] = 1000.0 + 0.1 * std::sin(t);
      q[2] = 1000.0 + lift(rng);
    }
    const TetMeasures m = tet_measures(p[0], p[1], p[2], p[3]);
    positive += m.radius_ratio > 0.0;
    EXPECT_GE(m.radius_ratio, 0.0) << "tet " << k;
    EXPECT_LT(m.radius_ratio, 1e-6) << "tet " << k;  // flat: 6 r / l_max is at most ~1e-9 here
  }
  EXPECT_GT(positive, 0u);
  // Three corners within 3e-12 of each other, 0.18 from the fourth (a stage 1 tet of the airplane
  // with 15 BL layers): the Heron form of R gave a radius ratio of 75.
  const double a[3] = {-6.29441166845605, -0.6266023338334077, 2.060429610114084};
  const double b[3] = {-6.463989589033079, -0.5857328680914512, 2.0234233880687387};
  const double c[3] = {-6.463989589032781, -0.5857328680896993, 2.023423388065967};
  const double d[3] = {-6.463989589033034, -0.5857328680911862, 2.0234233880683172};
  const TetMeasures m = tet_measures(a, b, c, d);
  EXPECT_GE(m.radius_ratio, 0.0);
  EXPECT_LT(m.radius_ratio, 1e-5);
}

TEST(TetMeasures, ScaleAndTranslationInvariant) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0.1, 0}, c[3] = {0.2, 1, 0.1}, d[3] = {0.3, 0.2, 0.9};
  const TetMeasures m = tet_measures(a, b, c, d);
  const double s = 1e-6, t = 1e3;
  double A[3], B[3], C[3], D[3];
  for (int k = 0; k < 3; ++k) {
    A[k] = t + s * a[k];
    B[k] = t + s * b[k];
    C[k] = t + s * c[k];
    D[k] = t + s * d[k];
  }
  const TetMeasures n = tet_measures(A, B, C, D);
  EXPECT_NEAR(n.radius_ratio, m.radius_ratio, 1e-6);  // translation by 1e9 sizes costs digits
  EXPECT_NEAR(n.mean_ratio, m.mean_ratio, 1e-6);
  EXPECT_NEAR(n.min_dihedral_deg, m.min_dihedral_deg, 1e-4);
}

}  // namespace
}  // namespace anitet

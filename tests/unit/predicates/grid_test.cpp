// Exhaustive degenerate configurations (a cube's corners, the 3x3x3 grid) under translations
// and scalings, and inputs of extreme magnitude (the GMP path, subnormals, overflowing lifts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "generators.hpp"
#include "predicates/exact.hpp"
#include "predicates/predicates.hpp"
#include "reference.hpp"

namespace anitet::predicates::testing {
namespace {

std::vector<P3> grid3(const Frame& f) {
  std::vector<P3> pts;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      for (int z = 0; z < 3; ++z) pts.push_back(f.apply({double(x), double(y), double(z)}));
  return pts;
}

std::vector<P3> cube_corners(const Frame& f) {
  std::vector<P3> pts;
  for (int i = 0; i < 8; ++i) pts.push_back(f.apply({double(i & 1), double((i >> 1) & 1), double(i >> 2)}));
  return pts;
}

const Frame kFrames[] = {
    {1, {0, 0, 0}},         {1e-4, {0, 0, 0}},        {1e4, {0, 0, 0}},
    {1, {1e6, -1e6, 1e6}},  {1e-4, {1e6, 1e6, 1e6}},  {0.1, {0, 0, 0}},
    {0x1p-40, {0, 0, 0}},   {3, {-2e6, 1e6, 5e5}},
};

// A cube stays exactly a cube under any of the frames (each axis takes two values), so all its
// corners stay cospherical and its 12 planar quadruples stay coplanar.
TEST(PredicatesGrids, CubeCornersAreCosphericalUnderEveryFrame) {
  for (const Frame& f : kFrames) {
    const auto p = cube_corners(f);
    reset_thread_counters();
    int coplanar = 0;
    for (int a = 0; a < 8; ++a)
      for (int b = a + 1; b < 8; ++b)
        for (int c = b + 1; c < 8; ++c)
          for (int d = c + 1; d < 8; ++d) {
            const int o = orient3d(p[a].data(), p[b].data(), p[c].data(), p[d].data());
            EXPECT_EQ(o, ref_orient3d(p[a].data(), p[b].data(), p[c].data(), p[d].data()));
            coplanar += o == 0;
            for (int e = 0; e < 8; ++e) {
              if (e == a || e == b || e == c || e == d) continue;
              EXPECT_EQ(insphere(p[a].data(), p[b].data(), p[c].data(), p[d].data(), p[e].data()),
                        0)
                  << "frame scale " << f.scale << " shift " << f.shift[0];
            }
          }
    EXPECT_EQ(coplanar, 12);  // 6 faces and 6 diagonal rectangles
    EXPECT_GT(thread_counters().insphere_exact, 0u);
    EXPECT_EQ(thread_counters().insphere_exact, thread_counters().insphere_calls);
  }
}

TEST(PredicatesGrids, Grid3x3x3AllQuadruplesAndQuintuples) {
  for (const Frame& f : {kFrames[0], kFrames[4], kFrames[5]}) {
    const auto p = grid3(f);
    const int n = int(p.size());
    reset_thread_counters();
    int zeros3 = 0, zeros5 = 0, bad = 0;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        for (int c = b + 1; c < n; ++c)
          for (int d = c + 1; d < n; ++d) {
            const double *pa = p[a].data(), *pb = p[b].data(), *pc = p[c].data(),
                         *pd = p[d].data();
            const int o = orient3d(pa, pb, pc, pd);
            bad += o != ref_orient3d(pa, pb, pc, pd);
            zeros3 += o == 0;
            for (int e = d + 1; e < n; ++e) {
              const int s = insphere(pa, pb, pc, pd, p[e].data());
              bad += s != ref_insphere(pa, pb, pc, pd, p[e].data());
              zeros5 += s == 0;
            }
          }
    EXPECT_EQ(bad, 0) << "frame scale " << f.scale;
    if (f.scale == 1) {  // the exact integer grid
      EXPECT_GT(zeros3, 1000);
      EXPECT_GT(zeros5, 10000);
    }
    EXPECT_GT(thread_counters().orient3d_exact, 1000u);
    EXPECT_GT(thread_counters().insphere_exact, 10000u);
  }
}

// Integer inputs around the lattice stage's size limit (it must decide exactly or defer):
// cospherical and coplanar integer points scaled by k, then moved by one unit.
TEST(PredicatesGrids, LargeIntegerLatticesAtTheLatticeStageLimit) {
  Rng rng(23);
  const std::vector<P3> sphere = integer_sphere(50);
  int decided = 0, bad = 0;
  const int n = 40000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    // Differences up to 14k: k <= 36 fits the insphere limit (9 bits), larger k does not.
    const double k = double(rng.coin() ? rng.integer(1, 40) : rng.integer(1, 700));
    std::array<P3, 5> p;
    for (auto& q : p) {
      q = sphere[size_t(rng.integer(0, int(sphere.size()) - 1))];
      for (auto& x : q) x *= k;
    }
    if (rng.coin()) p[size_t(rng.integer(0, 4))][size_t(rng.integer(0, 2))] += rng.coin() ? 1 : -1;
    const double* q[5] = {p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()};
    const int want5 = ref_insphere(q[0], q[1], q[2], q[3], q[4]);
    const int want3 = ref_orient3d(q[0], q[1], q[2], q[3]);
    int got = 0;
    if (detail::insphere_lattice(q[0], q[1], q[2], q[3], q[4], got)) {
      ++decided;
      bad += got != want5;
    }
    if (detail::orient3d_lattice(q[0], q[1], q[2], q[3], got)) bad += got != want3;
    double h[5];
    for (int j = 0; j < 5; ++j) h[j] = double(rng.integer(-3000, 3000));
    const int want4 = ref_orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]);
    if (detail::orient4d_lattice(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4], got))
      bad += got != want4;
    bad += insphere(q[0], q[1], q[2], q[3], q[4]) != want5;
    bad += orient3d(q[0], q[1], q[2], q[3]) != want3;
    bad += orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]) != want4;
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(decided, n / 4);
}

// Integer tets with large entries and volume +-1: rows b = (F(n+1), F(n), x), c = (F(n), F(n-1),
// y), d = alpha b + beta c + (0, 0, 1) have det = F(n+1)F(n-1) - F(n)^2 = +-1 (Fibonacci) for any
// x, y, alpha, beta. The formula's terms reach 2^60 while the determinant is 1, so neither the
// filter nor the lattice stage may trust plain doubles here.
TEST(PredicatesGrids, UnimodularTetsWithLargeEntries) {
  Rng rng(24);
  double fib[40] = {0, 1};
  for (int i = 2; i < 40; ++i) fib[i] = fib[i - 1] + fib[i - 2];
  int bad = 0, lattice_decided = 0;
  for (int n = 3; n < 37; ++n) {
    for (int t = 0; t < 300 / kCaseDivisor; ++t) {
      const double x = std::floor(rng.uniform(-fib[n], fib[n]));
      const double y = std::floor(rng.uniform(-fib[n], fib[n]));
      const double alpha = rng.integer(-2, 2), beta = rng.integer(-2, 2);
      P3 b = {fib[n + 1], fib[n], x}, c = {fib[n], fib[n - 1], y}, d;
      for (int k = 0; k < 3; ++k) d[size_t(k)] = alpha * b[size_t(k)] + beta * c[size_t(k)];
      d[2] += 1;
      // Random axis order and a random integer translation.
      const int perm = rng.integer(0, 2);
      const P3 shift = lattice_point(rng, -1000, 1000);
      P3 a = shift;
      for (P3* q : {&b, &c, &d}) {
        std::rotate(q->begin(), q->begin() + perm, q->end());
        for (int k = 0; k < 3; ++k) (*q)[size_t(k)] += shift[size_t(k)];
      }
      const int want = ref_orient3d(a.data(), b.data(), c.data(), d.data());
      bad += orient3d(a.data(), b.data(), c.data(), d.data()) != want;
      bad += orient3d(b.data(), a.data(), c.data(), d.data()) != -want;
      int got = 0;
      if (detail::orient3d_lattice(a.data(), b.data(), c.data(), d.data(), got)) {
        ++lattice_decided;
        bad += got != want;
      }
    }
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(lattice_decided, 0);
}

// Magnitudes outside the expansion range (GMP path), subnormals, lifts that overflow in double.
TEST(PredicatesExtremes, AgreeWithExactEverywhere) {
  Rng rng(21);
  const int exps[] = {-1074, -1060, -1000, -700, -400, -300, -200, -160, -152, -148, -60,
                      0,     60,    150,   185,  195,  250,  320,  400,  600,  900,  1000};
  int out_of_range = 0, bad = 0;
  const int n = 20000 / kCaseDivisor;
  for (int t = 0; t < n; ++t) {
    // Each point gets its own magnitude, or all share one, over a degenerate or random shape.
    const bool shared = rng.coin();
    const int e0 = exps[rng.integer(0, 21)];
    std::array<P3, 5> p = rng.coin() ? cospherical_case(rng) : std::array<P3, 5>{};
    if (p[0][0] == 0 && p[1][0] == 0)
      for (auto& q : p) q = lattice_point(rng, -3, 3);
    double h[5];
    for (int j = 0; j < 5; ++j) {
      const int e = shared ? e0 : exps[rng.integer(0, 21)];
      for (auto& x : p[size_t(j)]) x = std::ldexp(x, e >= 900 ? e - 30 : e);  // stay finite
      h[j] = std::ldexp(rng.uniform(-1, 1), exps[rng.integer(0, 21)]);
    }
    const double* q[5] = {p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()};
    out_of_range += !detail::insphere_in_range(q);
    bad += orient2d(q[0], q[1], q[2]) != ref_orient2d(q[0], q[1], q[2]);
    bad += orient3d(q[0], q[1], q[2], q[3]) != ref_orient3d(q[0], q[1], q[2], q[3]);
    bad += insphere(q[0], q[1], q[2], q[3], q[4]) != ref_insphere(q[0], q[1], q[2], q[3], q[4]);
    bad += orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]) !=
           ref_orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]);
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(out_of_range, n / 4);
}

// Exactly degenerate shapes scaled to the ends of the double range must still give 0.
TEST(PredicatesExtremes, DegenerateAtEveryScale) {
  for (const int e : {-1074, -1070, -1040, -1000, -600, -160, 0, 160, 500, 900, 1010}) {
    auto s = [e](double x) { return std::ldexp(x, e); };
    const double a[3] = {s(0), s(0), s(0)}, b[3] = {s(4), s(0), s(0)}, c[3] = {s(0), s(4), s(0)};
    const double d[3] = {s(4), s(4), s(0)}, top[3] = {s(4), s(4), s(4)};
    const double mid[3] = {s(2), s(2), s(0)};
    EXPECT_EQ(orient2d(a, b, mid), ref_orient2d(a, b, mid)) << e;
    EXPECT_EQ(orient2d(a, d, mid), 0) << e;
    EXPECT_EQ(orient3d(a, b, c, d), 0) << e;
    EXPECT_EQ(orient3d(a, b, c, top), 1) << e;
    EXPECT_EQ(insphere(a, b, c, top, d), 0) << e;  // corners of a cube
    EXPECT_EQ(insphere(a, b, c, top, mid), ref_insphere(a, b, c, top, mid)) << e;
    EXPECT_EQ(orient4d(a, b, c, top, d, s(1), s(1), s(1), s(1), s(1)), 0) << e;
  }
}

}  // namespace
}  // namespace anitet::predicates::testing

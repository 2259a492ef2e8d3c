// Agreement of every predicate, and of each of its exact paths on its own, with exact integer
// determinants on random near-degenerate inputs (>= 10^6 cases in total in Release).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "generators.hpp"
#include "predicates/exact.hpp"
#include "predicates/predicates.hpp"
#include "reference.hpp"

namespace anitet::predicates::testing {
namespace {

// Collects mismatches and reports the first few with hex-float inputs (reproducible).
class Mismatches {
 public:
  void check(int got, int want, const char* what, const double* v, int n) {
    if (got == want) return;
    if (++count_ <= 5) {
      std::string s;
      char buf[64];
      for (int i = 0; i < n; ++i) {
        std::snprintf(buf, sizeof buf, "%a ", v[i]);
        s += buf;
      }
      ADD_FAILURE() << what << " got " << got << " want " << want << " for " << s;
    }
  }
  int count() const { return count_; }

 private:
  int count_ = 0;
};

void report_fraction(const char* name, uint64_t exact, uint64_t calls) {
  std::printf("[ stats    ] %s: %llu calls, %llu exact (%.3f%%)\n", name,
              static_cast<unsigned long long>(calls), static_cast<unsigned long long>(exact),
              100.0 * double(exact) / double(calls ? calls : 1));
}

TEST(PredicatesRandom, Orient2dMatchesExact) {
  Rng rng(2);
  Mismatches bad;
  reset_thread_counters();
  const int n = 250000 / kCaseDivisor;
  for (int i = 0; i < n; ++i) {
    P3 a = random_point(rng, -1, 1), b = random_point(rng, -1, 1), c;
    const int kind = rng.integer(0, 5);
    if (kind <= 1) {
      const double t = rng.uniform(-2, 3);
      c = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0};
    } else if (kind <= 3) {
      a = lattice_point(rng, -9, 9);
      b = lattice_point(rng, -9, 9);
      const int t = rng.integer(-3, 3);
      c = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), 0};
    } else {
      c = random_point(rng, -1, 1);
    }
    const Frame f = random_frame(rng);
    a = f.apply(a);
    b = f.apply(b);
    c = f.apply(c);
    if (kind == 3) c[1] = nudge(c[1], rng);
    const double v[6] = {a[0], a[1], b[0], b[1], c[0], c[1]};
    const int want = ref_orient2d(a.data(), b.data(), c.data());
    bad.check(orient2d(a.data(), b.data(), c.data()), want, "orient2d", v, 6);
    if (detail::orient2d_in_range(a.data(), b.data(), c.data()))
      bad.check(detail::orient2d_expansion(a.data(), b.data(), c.data()), want, "expansion", v, 6);
    if (i % 16 == 0) bad.check(detail::orient2d_gmp(a.data(), b.data(), c.data()), want, "gmp", v, 6);
  }
  EXPECT_EQ(bad.count(), 0);
  const PredicateCounters& k = thread_counters();
  EXPECT_EQ(k.orient2d_calls, uint64_t(n));
  EXPECT_GT(k.orient2d_exact, uint64_t(n / 5));  // the exact path was exercised, a lot
  report_fraction("orient2d near-degenerate", k.orient2d_exact, k.orient2d_calls);
}

// Four near-cocircular 2D points: on a rounded circle, on an exact integer circle (maybe a few
// ulps off), three collinear, or generic; then a random frame.
std::array<P3, 4> cocircular_case(Rng& rng) {
  static const int kRadii2[] = {25, 50, 65, 85};
  std::array<P3, 4> p;
  const int kind = rng.integer(0, 9);
  if (kind <= 2) {
    const P3 c = random_point(rng, -1, 1);
    const double r = rng.uniform(0.1, 10);
    for (auto& q : p) {
      const double th = rng.uniform(0, 6.283185307179586);
      q = {c[0] + r * std::cos(th), c[1] + r * std::sin(th), 0};
    }
  } else if (kind <= 6) {
    std::vector<P3> circle;
    const int r2 = kRadii2[rng.integer(0, 3)];
    for (int x = -10; x <= 10; ++x)
      for (int y = -10; y <= 10; ++y)
        if (x * x + y * y == r2) circle.push_back({double(x), double(y), 0});
    const P3 c = lattice_point(rng, -5, 5);
    for (auto& q : p) {
      const P3& s = circle[size_t(rng.integer(0, int(circle.size()) - 1))];
      q = {s[0] + c[0], s[1] + c[1], 0};
    }
  } else if (kind == 7) {
    const P3 a = lattice_point(rng, -8, 8), b = lattice_point(rng, -8, 8);
    p = {a, b, combo(a, b, b, rng.integer(-3, 3), 0), lattice_point(rng, -8, 8)};
  } else {
    for (auto& q : p) q = random_point(rng, -1, 1);
  }
  const Frame f = random_frame(rng);
  for (auto& q : p) q = f.apply(q);
  if (kind == 6) p[3][size_t(rng.integer(0, 1))] = nudge(p[3][0], rng);
  return p;
}

TEST(PredicatesRandom, IncircleMatchesExact) {
  Rng rng(6);
  Mismatches bad;
  reset_thread_counters();
  const int n = 200000 / kCaseDivisor;
  for (int i = 0; i < n; ++i) {
    const auto p = cocircular_case(rng);
    const double v[8] = {p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], p[3][0], p[3][1]};
    const int want = ref_incircle(p[0].data(), p[1].data(), p[2].data(), p[3].data());
    bad.check(incircle(p[0].data(), p[1].data(), p[2].data(), p[3].data()), want, "incircle", v, 8);
    if (i % 4 == 0)
      bad.check(detail::incircle_exact(p[0].data(), p[1].data(), p[2].data(), p[3].data()), want,
                "incircle exact", v, 8);
  }
  EXPECT_EQ(bad.count(), 0);
  const PredicateCounters& k = thread_counters();
  EXPECT_EQ(k.incircle_calls, uint64_t(n));
  EXPECT_GT(k.incircle_exact, uint64_t(n / 5));
  report_fraction("incircle near-cocircular", k.incircle_exact, k.incircle_calls);
}

TEST(PredicatesRandom, Orient3dMatchesExact) {
  Rng rng(3);
  Mismatches bad;
  reset_thread_counters();
  int dd_decided = 0, lattice_decided = 0;
  const int n = 300000 / kCaseDivisor;
  for (int i = 0; i < n; ++i) {
    const auto p = coplanar_case(rng);
    const double* a = p[0].data();
    const double* b = p[1].data();
    const double* c = p[2].data();
    const double* d = p[3].data();
    const double* v = p[0].data();  // the 12 coordinates are contiguous
    const int want = ref_orient3d(a, b, c, d);
    bad.check(orient3d(a, b, c, d), want, "orient3d", v, 12);
    int lattice = 0;
    if (detail::orient3d_lattice(a, b, c, d, lattice)) {
      ++lattice_decided;
      bad.check(lattice, want, "lattice", v, 12);
    }
    if (const int dd = detail::orient3d_double_double(a, b, c, d)) {
      ++dd_decided;
      bad.check(dd, want, "double-double", v, 12);
    }
    if (detail::orient3d_in_range(a, b, c, d))
      bad.check(detail::orient3d_expansion(a, b, c, d), want, "expansion", v, 12);
    if (i % 16 == 0) bad.check(detail::orient3d_gmp(a, b, c, d), want, "gmp", v, 12);
  }
  EXPECT_EQ(bad.count(), 0);
  const PredicateCounters& k = thread_counters();
  EXPECT_EQ(k.orient3d_calls, uint64_t(n));
  EXPECT_GT(k.orient3d_exact, uint64_t(n / 5));
  EXPECT_GT(dd_decided, n / 20);
  EXPECT_GT(lattice_decided, n / 20);
  report_fraction("orient3d near-degenerate", k.orient3d_exact, k.orient3d_calls);
}

TEST(PredicatesRandom, InsphereMatchesExact) {
  Rng rng(4);
  Mismatches bad;
  reset_thread_counters();
  int diff_path = 0, dd_decided = 0, lattice_decided = 0;
  const int n = 300000 / kCaseDivisor;
  for (int i = 0; i < n; ++i) {
    const auto p = cospherical_case(rng);
    const double* q[5] = {p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()};
    const double* v = p[0].data();
    const int want = ref_insphere(q[0], q[1], q[2], q[3], q[4]);
    bad.check(insphere(q[0], q[1], q[2], q[3], q[4]), want, "insphere", v, 15);
    int lattice = 0;
    if (detail::insphere_lattice(q[0], q[1], q[2], q[3], q[4], lattice)) {
      ++lattice_decided;
      bad.check(lattice, want, "lattice", v, 15);
    }
    if (const int dd = detail::insphere_double_double(q[0], q[1], q[2], q[3], q[4])) {
      ++dd_decided;
      bad.check(dd, want, "double-double", v, 15);
    }
    if (detail::insphere_in_range(q)) {
      if (i % 3 == 0)  // the general expansion is the slowest path: a third of the cases
        bad.check(detail::insphere_expansion(q[0], q[1], q[2], q[3], q[4]), want, "expansion", v,
                  15);
      if (detail::differences_exact(q, nullptr)) {
        ++diff_path;
        bad.check(detail::insphere_expansion_diff(q[0], q[1], q[2], q[3], q[4]), want,
                  "expansion on differences", v, 15);
      }
    }
    if (i % 16 == 0) bad.check(detail::insphere_gmp(q[0], q[1], q[2], q[3], q[4]), want, "gmp", v, 15);
  }
  EXPECT_EQ(bad.count(), 0);
  EXPECT_GT(diff_path, n / 10);
  EXPECT_GT(dd_decided, n / 20);
  EXPECT_GT(lattice_decided, n / 20);
  const PredicateCounters& k = thread_counters();
  EXPECT_EQ(k.insphere_calls, uint64_t(n));
  EXPECT_GT(k.insphere_exact, uint64_t(n / 5));
  report_fraction("insphere near-degenerate", k.insphere_exact, k.insphere_calls);
}

TEST(PredicatesRandom, Orient4dMatchesExact) {
  Rng rng(5);
  Mismatches bad;
  reset_thread_counters();
  int dd_decided = 0, lattice_decided = 0;
  const int n = 200000 / kCaseDivisor;
  for (int i = 0; i < n; ++i) {
    auto p = cospherical_case(rng);
    double h[5];
    const int kind = rng.integer(0, 4);
    if (kind == 0) {  // paraboloid lift: near-degenerate where the points are near-cospherical
      for (int j = 0; j < 5; ++j) h[j] = p[j][0] * p[j][0] + p[j][1] * p[j][1] + p[j][2] * p[j][2];
    } else if (kind <= 2) {  // heights from an affine function: a degenerate lifted hyperplane
      const bool lattice = kind == 2;
      double g[4];
      for (auto& x : g) x = lattice ? rng.integer(-4, 4) : rng.uniform(-3, 3);
      for (int j = 0; j < 5; ++j) {
        if (lattice) p[size_t(j)] = lattice_point(rng, -6, 6);
        h[j] = g[0] * p[j][0] + g[1] * p[j][1] + g[2] * p[j][2] + g[3];
      }
      if (lattice && rng.coin()) h[rng.integer(0, 4)] = nudge(h[0], rng);
    } else if (kind == 3) {
      for (auto& x : h) x = rng.uniform(-1e3, 1e3);
    } else {
      for (auto& x : h) x = rng.uniform(0, 1) * 0x1p-20;
    }
    const double* q[5] = {p[0].data(), p[1].data(), p[2].data(), p[3].data(), p[4].data()};
    double v[20];
    for (int j = 0; j < 15; ++j) v[j] = p[size_t(j / 3)][size_t(j % 3)];
    for (int j = 0; j < 5; ++j) v[15 + j] = h[j];
    const int want = ref_orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]);
    bad.check(orient4d(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]), want,
              "orient4d", v, 20);
    int lattice = 0;
    if (detail::orient4d_lattice(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4],
                                 lattice)) {
      ++lattice_decided;
      bad.check(lattice, want, "lattice", v, 20);
    }
    if (const int dd = detail::orient4d_double_double(q[0], q[1], q[2], q[3], q[4], h[0], h[1],
                                                      h[2], h[3], h[4])) {
      ++dd_decided;
      bad.check(dd, want, "double-double", v, 20);
    }
    if (detail::orient4d_in_range(q, h)) {
      bad.check(detail::orient4d_expansion(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3],
                                           h[4]),
                want, "expansion", v, 20);
      if (detail::differences_exact(q, h))
        bad.check(detail::orient4d_expansion_diff(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2],
                                                  h[3], h[4]),
                  want, "expansion on differences", v, 20);
    }
    if (i % 16 == 0)
      bad.check(detail::orient4d_gmp(q[0], q[1], q[2], q[3], q[4], h[0], h[1], h[2], h[3], h[4]),
                want, "gmp", v, 20);
  }
  EXPECT_EQ(bad.count(), 0);
  const PredicateCounters& k = thread_counters();
  EXPECT_EQ(k.orient4d_calls, uint64_t(n));
  EXPECT_GT(k.orient4d_exact, uint64_t(n / 10));
  EXPECT_GT(dd_decided, n / 20);
  EXPECT_GT(lattice_decided, n / 20);
  report_fraction("orient4d near-degenerate", k.orient4d_exact, k.orient4d_calls);
}

}  // namespace
}  // namespace anitet::predicates::testing

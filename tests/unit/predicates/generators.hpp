// Random near-degenerate inputs for the predicate tests: exact degenerate configurations on
// integer lattices, the same after a rounding change of frame (scale 1e-4 / 1e4 / 0.1,
// translation ~1e6), degenerate-by-construction points rounded to double, a few ulps of
// perturbation, and some generic points.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace anitet::predicates::testing {

// Fewer cases under the sanitizers (several times slower); the Release run does >= 10^6.
#if defined(__SANITIZE_ADDRESS__)
constexpr int kCaseDivisor = 8;
#else
constexpr int kCaseDivisor = 1;
#endif

using P3 = std::array<double, 3>;

class Rng {
 public:
  explicit Rng(uint64_t seed) : g_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g_); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g_); }
  bool coin() { return integer(0, 1) == 1; }
  std::mt19937_64& engine() { return g_; }

 private:
  std::mt19937_64 g_;
};

// p -> p * scale + shift, rounded: how real data gets translated and scaled.
struct Frame {
  double scale = 1;
  P3 shift{0, 0, 0};
  P3 apply(const P3& p) const {
    return {p[0] * scale + shift[0], p[1] * scale + shift[1], p[2] * scale + shift[2]};
  }
};

inline Frame random_frame(Rng& rng) {
  static const double kScales[] = {1, 1e-4, 1e4, 0.1, 0.5, 0x1p-30, 3};
  Frame f;
  f.scale = kScales[rng.integer(0, 6)];
  switch (rng.integer(0, 3)) {
    case 0: break;
    case 1: f.shift = {1e6, 1e6, 1e6}; break;
    case 2:
      f.shift = {rng.uniform(-2e6, 2e6), rng.uniform(-2e6, 2e6), rng.uniform(-2e6, 2e6)};
      break;
    default: f.shift = {rng.uniform(-10, 10), rng.uniform(-10, 10), rng.uniform(-10, 10)}; break;
  }
  return f;
}

// Move v by 1..3 ulps up or down.
inline double nudge(double v, Rng& rng) {
  const int steps = rng.integer(1, 3);
  const double to = rng.coin() ? INFINITY : -INFINITY;
  for (int i = 0; i < steps; ++i) v = std::nextafter(v, to);
  return v;
}

inline P3 random_point(Rng& rng, double lo, double hi) {
  return {rng.uniform(lo, hi), rng.uniform(lo, hi), rng.uniform(lo, hi)};
}
inline P3 lattice_point(Rng& rng, int lo, int hi) {
  return {double(rng.integer(lo, hi)), double(rng.integer(lo, hi)), double(rng.integer(lo, hi))};
}
inline P3 combo(const P3& a, const P3& b, const P3& c, double s, double t) {
  P3 r;
  for (int k = 0; k < 3; ++k) r[k] = a[k] + s * (b[k] - a[k]) + t * (c[k] - a[k]);
  return r;
}

// Integer points on the sphere x^2 + y^2 + z^2 = r2.
inline std::vector<P3> integer_sphere(int r2) {
  std::vector<P3> out;
  const int r = int(std::sqrt(double(r2))) + 1;
  for (int x = -r; x <= r; ++x)
    for (int y = -r; y <= r; ++y)
      for (int z = -r; z <= r; ++z)
        if (x * x + y * y + z * z == r2) out.push_back({double(x), double(y), double(z)});
  return out;
}

// A point on the plane z = x + y with short mantissas at scattered exponents: points like this
// are exactly coplanar (so also exactly "cospherical" in the lifted sense: insphere = 0), yet
// their differences are not exact in double.
inline P3 scattered_plane_point(Rng& rng) {
  for (;;) {
    const double x = std::ldexp(double(rng.integer(-(1 << 20), 1 << 20)), rng.integer(-40, 0));
    const double y = std::ldexp(double(rng.integer(-(1 << 20), 1 << 20)), rng.integer(-40, 0));
    const double z = x + y;
    if (z - x == y && z - y == x) return {x, y, z};  // the sum is exact
  }
}

// Five near-cospherical points (kinds: rounded sphere, exact lattice sphere, lattice + ulps,
// coplanar a,b,c,d, generic), then a random frame.
inline std::array<P3, 5> cospherical_case(Rng& rng) {
  static const std::vector<P3> kSpheres[] = {integer_sphere(25), integer_sphere(50),
                                             integer_sphere(81), integer_sphere(101)};
  std::array<P3, 5> p;
  const int kind = rng.integer(0, 9);
  if (kind <= 2) {  // on a sphere, rounded
    const P3 c = random_point(rng, -1, 1);
    const double r = rng.uniform(0.1, 10);
    for (auto& q : p) {
      const double th = rng.uniform(0, 6.283185307179586), z = rng.uniform(-1, 1);
      const double s = std::sqrt(1 - z * z);
      q = {c[0] + r * s * std::cos(th), c[1] + r * s * std::sin(th), c[2] + r * z};
    }
  } else if (kind <= 6) {  // exactly cospherical lattice points, maybe a few ulps off
    const auto& sphere = kSpheres[rng.integer(0, 3)];
    const P3 c = lattice_point(rng, -5, 5);
    for (auto& q : p) {
      const P3& s = sphere[size_t(rng.integer(0, int(sphere.size()) - 1))];
      q = {s[0] + c[0], s[1] + c[1], s[2] + c[2]};
    }
    if (kind == 6) {
      auto& q = p[size_t(rng.integer(0, 4))];
      q[size_t(rng.integer(0, 2))] = nudge(q[size_t(rng.integer(0, 2))], rng);
    }
  } else if (kind == 7 && rng.coin()) {  // all five exactly coplanar, inexact differences
    for (auto& q : p) q = scattered_plane_point(rng);
    return p;
  } else if (kind <= 7) {  // a, b, c, d coplanar lattice points
    const P3 a = lattice_point(rng, -5, 5), b = lattice_point(rng, -5, 5);
    const P3 c = lattice_point(rng, -5, 5);
    p = {a, b, c, combo(a, b, c, rng.integer(-2, 2), rng.integer(-2, 2)),
         lattice_point(rng, -5, 5)};
  } else {
    for (auto& q : p) q = random_point(rng, -1, 1);
  }
  const Frame f = random_frame(rng);
  for (auto& q : p) q = f.apply(q);
  if (kind == 5) p[4][0] = nudge(p[4][0], rng);  // perturbed after the frame
  return p;
}

// Four near-coplanar points, same kinds.
inline std::array<P3, 4> coplanar_case(Rng& rng) {
  std::array<P3, 4> p;
  const int kind = rng.integer(0, 9);
  if (kind <= 2) {
    const P3 a = random_point(rng, -1, 1), b = random_point(rng, -1, 1);
    const P3 c = random_point(rng, -1, 1);
    p = {a, b, c, combo(a, b, c, rng.uniform(-2, 2), rng.uniform(-2, 2))};
  } else if (kind <= 6) {
    const P3 a = lattice_point(rng, -8, 8), b = lattice_point(rng, -8, 8);
    const P3 c = lattice_point(rng, -8, 8);
    p = {a, b, c, combo(a, b, c, rng.integer(-3, 3), rng.integer(-3, 3))};
    if (kind == 6) p[3][2] = nudge(p[3][2], rng);
  } else if (kind == 7 && rng.coin()) {  // exactly coplanar, inexact differences
    for (auto& q : p) q = scattered_plane_point(rng);
    return p;
  } else if (kind == 7) {  // a, b, c collinear
    const P3 a = lattice_point(rng, -8, 8), b = lattice_point(rng, -8, 8);
    p = {a, b, combo(a, b, b, rng.integer(-3, 3), 0), lattice_point(rng, -8, 8)};
  } else {
    for (auto& q : p) q = random_point(rng, -1, 1);
  }
  const Frame f = random_frame(rng);
  for (auto& q : p) q = f.apply(q);
  if (kind == 5) p[0][1] = nudge(p[0][1], rng);
  return p;
}

}  // namespace anitet::predicates::testing

// Metric measures of the UGAWG benchmark (Ibanez et al., "First benchmark of the Unstructured
// Grid Adaptation Working Group", IMR 2017; /work/shared/data/ugawg/SOURCES.md): what adaptation
// (src/adapt) aims at and what the quality report (src/quality) measures when a mesh carries a
// metric:
//   - edge length: l = (la - lb) / ln(la / lb) (la, lb: the length in the metric at either end;
//     the exact length when the size varies linearly along the edge), (la + lb) / 2 when they
//     are within 1e-3;
//   - tet quality: the mean ratio (V_M / V_eq)^(2/3) / mean(l_M^2) in the metric M of the corner
//     with the largest det M (the finest), 1 for the regular tet of the metric, <= 0 when flat or
//     inverted.
// Metrics are 6 doubles xx xy yy xz yz zz.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace anitet {

// The range of metric edge lengths meshes aim at, [1/sqrt2, sqrt2]: refinement splits above it
// and collapses below it, and the reports count the share of edges in it.
constexpr double kUnitRangeMin = 0.7071067811865476, kUnitRangeMax = 1.4142135623730951;
inline bool in_unit_range(double l) { return l >= kUnitRangeMin && l <= kUnitRangeMax; }

inline double quad_form(const double m[6], const double v[3]) {
  return m[0] * v[0] * v[0] + m[2] * v[1] * v[1] + m[5] * v[2] * v[2] +
         2.0 * (m[1] * v[0] * v[1] + m[3] * v[0] * v[2] + m[4] * v[1] * v[2]);
}

inline double metric_det(const double m[6]) {
  // | xx xy xz ; xy yy yz ; xz yz zz |
  return m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
         m[3] * (m[1] * m[4] - m[2] * m[3]);
}

// The cube root of a finite x > 0: an estimate from the bits of x, then two Halley steps (each
// triples the correct digits: ~1e-14 relative), about three times faster than std::cbrt.
inline double cbrt_positive(double x) {
  uint64_t i;
  std::memcpy(&i, &x, sizeof i);
  i = i / 3 + 0x2A9F7893782DA1CEull;
  double y;
  std::memcpy(&y, &i, sizeof y);
  for (int k = 0; k < 2; ++k) {
    const double y3 = y * y * y;
    y *= (y3 + 2.0 * x) / (2.0 * y3 + x);
  }
  return y;
}

// Length from the two end lengths (see the top).
inline double combine_lengths(double la, double lb) {
  const double d = la - lb;
  if (std::fabs(d) <= 1e-3) return 0.5 * (la + lb);
  return d / std::log(la / lb);
}

inline double ugawg_edge_length(const double* pa, const double* pb, const double ma[6], const double mb[6]) {
  const double v[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
  return combine_lengths(std::sqrt(quad_form(ma, v)), std::sqrt(quad_form(mb, v)));
}

// Mean ratio of (a b c d) in the metric m of determinant det_m (see the top).
inline double ugawg_mean_ratio(const double* a, const double* b, const double* c, const double* d, const double m[6],
                         double det_m) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  const double vol6 = ab[0] * (ac[1] * ad[2] - ac[2] * ad[1]) - ab[1] * (ac[0] * ad[2] - ac[2] * ad[0]) +
                      ab[2] * (ac[0] * ad[1] - ac[1] * ad[0]);
  if (!(vol6 > 0.0) || !(det_m > 0.0)) return vol6 > 0.0 ? 0.0 : -1.0;
  const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double bd[3] = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
  const double cd[3] = {d[0] - c[0], d[1] - c[1], d[2] - c[2]};
  const double l2 = quad_form(m, ab) + quad_form(m, ac) + quad_form(m, ad) + quad_form(m, bc) + quad_form(m, bd) +
                    quad_form(m, cd);
  // V_eq = 1 / (6 sqrt 2): (V sqrt(det) / V_eq)^(2/3) = (vol6 sqrt(2 det))^(2/3).
  const double x = vol6 * std::sqrt(2.0 * det_m);
  return 6.0 * cbrt_positive(x * x) / l2;
}

}  // namespace anitet

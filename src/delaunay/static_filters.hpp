// Static floating-point filters for the Delaunay kernel's hot loop (internal header).
//
// The predicates module's filters bound the rounding error with the largest coordinate difference
// of each call (semi-static). Over one point set every difference is at most the bounding box's
// largest extent D, so one bound computed up front covers every call: the fast path is then the
// bare determinant and one comparison. When it cannot decide, the caller falls back to the
// module's predicates (semi-static filter, exact arithmetic, SoS).
//
// The determinants are predicates/filters.hpp's own (orient3d_det, insphere_det), so the bounds
// reuse its derivation (first-order error, monotone in the column maxima X, Y, Z and the largest
// lift L): orient3d error <= 46 eps XYZ, insphere error
// <= 376 eps L XYZ, with eps = 2^-53. With X, Y, Z <= D and L <= 3 D^2, and a relative margin for
// the rounding of the bound itself, they become the constants below. They are valid while D lies
// in [2^-150, 2^150]: then no intermediate overflows, and underflow errors (at most ~2^-1070 per
// operation) are negligible next to the bound; outside that range the filters are disabled.
#pragma once

#include <cmath>

#include "predicates/predicates.hpp"

namespace anitet::delaunay_detail {

constexpr int kUnknown = 2;

struct StaticFilters {
  // Infinite: disabled (every call falls through to the predicates module).
  double orient3d_bound = HUGE_VAL;
  double insphere_bound = HUGE_VAL;

  // For points whose coordinates differ by at most `extent` along each axis.
  static StaticFilters for_extent(double extent) {
    StaticFilters f;
    if (!(extent >= 0x1p-150 && extent <= 0x1p150)) return f;
    const double eps = 0x1p-53, margin = 1.0 + 0x1p-30;
    const double d3 = extent * extent * extent;
    f.orient3d_bound = 46.0 * eps * margin * d3;
    f.insphere_bound = 376.0 * eps * margin * 3.0 * d3 * extent * extent;
    return f;
  }
};

// Sign of orient3d(a, b, c, d) (predicates' convention) or kUnknown.
inline int orient3d_static(const double* a, const double* b, const double* c, const double* d,
                           double bound) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double det = predicates::detail::orient3d_det(ux, uy, uz, vx, vy, vz, wx, wy, wz);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return kUnknown;
}

// Sign of insphere(a, b, c, d, e) (predicates' convention: > 0 when e is inside the sphere of
// the positive tet abcd) or kUnknown.
inline int insphere_static(const double* a, const double* b, const double* c, const double* d,
                           const double* e, double bound) {
  const double ax = a[0] - e[0], ay = a[1] - e[1], az = a[2] - e[2];
  const double bx = b[0] - e[0], by = b[1] - e[1], bz = b[2] - e[2];
  const double cx = c[0] - e[0], cy = c[1] - e[1], cz = c[2] - e[2];
  const double dx = d[0] - e[0], dy = d[1] - e[1], dz = d[2] - e[2];
  double lmax;  // unused: the static bound covers every call
  const double det = predicates::detail::insphere_det(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz, lmax);
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return kUnknown;
}

}  // namespace anitet::delaunay_detail

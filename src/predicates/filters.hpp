// The floating-point filters of the predicates, inline so that the Delaunay kernel's hot loops
// pay no call. Included at the end of predicates.hpp; do not include it directly.
//
// Each filter evaluates its determinant in double precision on the coordinate differences,
// and returns the sign when |det| exceeds a bound proven to dominate the rounding error;
// otherwise it calls the out-of-line exact evaluation (predicates.cpp).
//
// Error bounds (semi-static, in the style of Meyer & Pion's FPG). eps = 2^-53 is the unit
// roundoff. With X, Y, Z the largest |difference| in each coordinate column (computed values),
// every monomial of the determinant is bounded by the product of its column maxima. Two error
// sources add up:
//   (ii) rounding of the differences themselves, d~ = d(1+δ), |δ| <= eps: a degree-k monomial
//        moves by at most ((1+eps)^k - 1) ~ k*eps of its size;
//   (i)  rounding in evaluating the formula from the rounded differences. Rules, first order:
//        fl(p*q): err(p)|q| + |p|err(q) + eps|pq|;  fl(p±q): err(p) + err(q) + eps(|p|+|q|).
// orient2d  det = ux*vy - uy*vx.  (i) products eps*XY each, subtraction eps*2XY: 4 eps XY;
//           (ii) 2 monomials of degree 2: 4 eps XY.  Total 8 eps XY.
// incircle  det = (La*m_bc + Lb*m_ca) + Lc*m_ab, rows p-d, L = |p-d|^2 (3 eps L each), m = 2x2
//           minors (4 eps XY, size 2XY), Lmax = max L. (i) each L*m: 3 eps L*2XY + L*4 eps XY +
//           eps 2LXY = 12 eps; three of them 36, the two additions eps(4 + 6).  Total (i) 46 eps
//           Lmax XY. (ii) 12 monomials of degree 4, sum <= 6 Lmax XY: 24 eps.  Total 70 eps Lmax XY.
// orient3d  det = zu*m_vw - zv*m_uw + zw*m_uv, m = xy 2x2 minors.  (i) minor: 4 eps XY,
//           |minor| <= 2XY; each z*minor: 4 eps XYZ + eps 2XYZ = 6 eps XYZ, size 2XYZ; the two
//           additions: eps 4XYZ + eps 6XYZ. Total (i) 3*6 + 10 = 28 eps XYZ.
//           (ii) 6 monomials of degree 3: 18 eps XYZ.  Total 46 eps XYZ.
// insphere  det = (La*D_bcd - Lb*D_acd) + (Lc*D_abd - Ld*D_abc), rows p-e, L = |p-e|^2,
//           D = orient3d-like 3x3 minors as above (28 eps XYZ, size 6XYZ), Lmax = max L.
//           (i) each lift: 3 eps L. Each L*D: 3 eps L*6XYZ + L*28 eps XYZ + eps 6 L XYZ = 52 eps;
//           four of them 208, pairwise sum eps(12 + 12 + 24) = 48.  Total (i) 256 eps Lmax XYZ.
//           (ii) 72 monomials c_i^2*x_j*y_k*z_l of degree 5, sum <= 24 Lmax XYZ: 120 eps.
//           Total 376 eps Lmax XYZ.
// orient4d  det = (hb*D_acd - ha*D_bcd) + (hd*D_abc - hc*D_abd), h = height differences,
//           H = max |h|. (i) each h*D: H*28 eps XYZ + eps 6HXYZ = 34 eps; four: 136; sums 48.
//           (ii) 24 monomials of degree 4: 96 eps.  Total 280 eps HXYZ.
// The constants below add a relative margin of 2^-40, which covers the second-order terms, the
// rounding of the bound's own product, and any error from gradual underflow: the filter only
// accepts when each column maximum lies in a range where every such underflow error is below
// 2^-80 * (product of maxima), and no intermediate can overflow. Outside that range, or when the
// bound cannot separate det from 0, the exact path decides. The bounds stay valid when the
// compiler contracts a*b+c into an FMA (one rounding fewer per contraction). NaN makes both
// comparisons false, so non-finite inputs always reach the exact path.
#pragma once

#include <algorithm>
#include <cmath>

#if defined(__FAST_MATH__)
#error "anitet predicates need IEEE-754 arithmetic: do not compile with -ffast-math"
#endif
#if defined(__FLT_EVAL_METHOD__) && __FLT_EVAL_METHOD__ != 0
#error "anitet predicates need double evaluation in double precision (SSE2, not x87)"
#endif

namespace anitet::predicates {
namespace detail {

// Counters: initial-exec TLS so that an increment is one instruction even from a shared library.
[[gnu::tls_model("initial-exec")]] inline thread_local PredicateCounters tls_counters;

constexpr double kEps = 0x1p-53;
constexpr double filter_constant(int eps_multiple) { return eps_multiple * kEps * (1.0 + 0x1p-40); }
constexpr double kOrient2dBound = filter_constant(8);
constexpr double kIncircleBound = filter_constant(70);
constexpr double kOrient3dBound = filter_constant(46);
constexpr double kInsphereBound = filter_constant(376);
constexpr double kOrient4dBound = filter_constant(280);

// Column-maximum ranges in which each filter is valid (see above).
constexpr double kOrient2dMin = 0x1p-450, kOrient2dMax = 0x1p450;
constexpr double kOrient3dMin = 0x1p-300, kOrient3dMax = 0x1p300;
constexpr double kInsphereMin = 0x1p-190, kInsphereMax = 0x1p190;
constexpr double kHeightMin = 0x1p-380, kHeightMax = 0x1p380;

inline double max3(double a, double b, double c) { return std::max(std::max(a, b), c); }
inline double max4(double a, double b, double c, double d) {
  return std::max(std::max(a, b), std::max(c, d));
}
inline double absmax3(double a, double b, double c) {
  return max3(std::fabs(a), std::fabs(b), std::fabs(c));
}
inline double absmax4(double a, double b, double c, double d) {
  return max4(std::fabs(a), std::fabs(b), std::fabs(c), std::fabs(d));
}
inline bool in_range(double lo, double hi, double a, double b, double c) {
  return lo <= std::min(std::min(a, b), c) && max3(a, b, c) <= hi;
}

// The floating-point determinants the filter bounds are derived for, in one evaluation order.
// The Delaunay kernel's static filters (delaunay/static_filters.hpp) call the same functions, so
// the bounds hold for them too.
inline double orient3d_det(double ux, double uy, double uz, double vx, double vy, double vz,
                           double wx, double wy, double wz) {
  const double m_vw = vx * wy - wx * vy;
  const double m_uw = ux * wy - wx * uy;
  const double m_uv = ux * vy - vx * uy;
  return (uz * m_vw - vz * m_uw) + wz * m_uv;
}
// a..d relative to the query point e; lmax gets the largest lift |a - e|^2 ... |d - e|^2.
inline double insphere_det(double ax, double ay, double az, double bx, double by, double bz,
                           double cx, double cy, double cz, double dx, double dy, double dz,
                           double& lmax) {
  const double m_ab = ax * by - bx * ay, m_ac = ax * cy - cx * ay, m_ad = ax * dy - dx * ay;
  const double m_bc = bx * cy - cx * by, m_bd = bx * dy - dx * by, m_cd = cx * dy - dx * cy;
  const double d_bcd = (bz * m_cd - cz * m_bd) + dz * m_bc;
  const double d_acd = (az * m_cd - cz * m_ad) + dz * m_ac;
  const double d_abd = (az * m_bd - bz * m_ad) + dz * m_ab;
  const double d_abc = (az * m_bc - bz * m_ac) + cz * m_ab;
  const double la = (ax * ax + ay * ay) + az * az;
  const double lb = (bx * bx + by * by) + bz * bz;
  const double lc = (cx * cx + cy * cy) + cz * cz;
  const double ld = (dx * dx + dy * dy) + dz * dz;
  lmax = max4(la, lb, lc, ld);
  return (la * d_bcd - lb * d_acd) + (lc * d_abd - ld * d_abc);
}

// Out of line: exact evaluation (counted as an exact call) and the SoS tie break.
int orient2d_exact(const double* a, const double* b, const double* c);
int incircle_exact(const double* a, const double* b, const double* c, const double* d);
int orient3d_exact(const double* a, const double* b, const double* c, const double* d);
int insphere_exact(const double* a, const double* b, const double* c, const double* d,
                   const double* e);
int orient4d_exact(const double* a, const double* b, const double* c, const double* d,
                   const double* e, double ha, double hb, double hc, double hd, double he);
int insphere_sos_tie(const double* a, const double* b, const double* c, const double* d,
                     const double* e, uint32_t ia, uint32_t ib, uint32_t ic, uint32_t id,
                     uint32_t ie);

}  // namespace detail

inline int orient2d(const double* a, const double* b, const double* c) {
  ++detail::tls_counters.orient2d_calls;
  const double ux = b[0] - a[0], uy = b[1] - a[1];
  const double vx = c[0] - a[0], vy = c[1] - a[1];
  const double det = ux * vy - uy * vx;
  const double mx = std::max(std::fabs(ux), std::fabs(vx));
  const double my = std::max(std::fabs(uy), std::fabs(vy));
  if (detail::kOrient2dMin <= std::min(mx, my) && std::max(mx, my) <= detail::kOrient2dMax) {
    const double bound = detail::kOrient2dBound * mx * my;
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return detail::orient2d_exact(a, b, c);
}

// The lifts stay within insphere's range (degree 4 here, 5 there): the same column range.
inline int incircle(const double* a, const double* b, const double* c, const double* d) {
  ++detail::tls_counters.incircle_calls;
  const double ax = a[0] - d[0], ay = a[1] - d[1];
  const double bx = b[0] - d[0], by = b[1] - d[1];
  const double cx = c[0] - d[0], cy = c[1] - d[1];
  const double la = ax * ax + ay * ay, lb = bx * bx + by * by, lc = cx * cx + cy * cy;
  const double det = (la * (bx * cy - cx * by) + lb * (cx * ay - ax * cy)) + lc * (ax * by - bx * ay);
  const double mx = detail::absmax3(ax, bx, cx);
  const double my = detail::absmax3(ay, by, cy);
  const double lmax = detail::max3(la, lb, lc);
  if (detail::kInsphereMin <= std::min(mx, my) && std::max(mx, my) <= detail::kInsphereMax) {
    const double bound = detail::kIncircleBound * mx * my * lmax;
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return detail::incircle_exact(a, b, c, d);
}

namespace detail {
// The orient3d filter with its error bound scaled by `margin` (>= 1): the sign when the double
// determinant clears the bound, 0 when it does not or the coordinates are out of its range.
inline int orient3d_filter(const double* a, const double* b, const double* c, const double* d, double margin) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double det = orient3d_det(ux, uy, uz, vx, vy, vz, wx, wy, wz);
  const double mx = absmax3(ux, vx, wx);
  const double my = absmax3(uy, vy, wy);
  const double mz = absmax3(uz, vz, wz);
  if (!in_range(kOrient3dMin, kOrient3dMax, mx, my, mz)) return 0;
  const double bound = margin * kOrient3dBound * mx * my * mz;
  return det > bound ? 1 : det < -bound ? -1 : 0;
}
}  // namespace detail

inline int orient3d(const double* a, const double* b, const double* c, const double* d) {
  ++detail::tls_counters.orient3d_calls;
  const int s = detail::orient3d_filter(a, b, c, d, 1.0);
  return s != 0 ? s : detail::orient3d_exact(a, b, c, d);
}

inline int orient3d_certified(const double* a, const double* b, const double* c, const double* d) {
  return detail::orient3d_filter(a, b, c, d, 4.0);
}

inline int insphere(const double* a, const double* b, const double* c, const double* d,
                    const double* e) {
  ++detail::tls_counters.insphere_calls;
  const double ax = a[0] - e[0], ay = a[1] - e[1], az = a[2] - e[2];
  const double bx = b[0] - e[0], by = b[1] - e[1], bz = b[2] - e[2];
  const double cx = c[0] - e[0], cy = c[1] - e[1], cz = c[2] - e[2];
  const double dx = d[0] - e[0], dy = d[1] - e[1], dz = d[2] - e[2];
  double lmax;
  const double det = detail::insphere_det(ax, ay, az, bx, by, bz, cx, cy, cz, dx, dy, dz, lmax);
  const double mx = detail::absmax4(ax, bx, cx, dx);
  const double my = detail::absmax4(ay, by, cy, dy);
  const double mz = detail::absmax4(az, bz, cz, dz);
  if (detail::in_range(detail::kInsphereMin, detail::kInsphereMax, mx, my, mz)) {
    const double bound = detail::kInsphereBound * mx * my * mz * lmax;
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return detail::insphere_exact(a, b, c, d, e);
}

inline int orient4d(const double* a, const double* b, const double* c, const double* d,
                    const double* e, double ha, double hb, double hc, double hd, double he) {
  ++detail::tls_counters.orient4d_calls;
  const double ax = a[0] - e[0], ay = a[1] - e[1], az = a[2] - e[2], ah = ha - he;
  const double bx = b[0] - e[0], by = b[1] - e[1], bz = b[2] - e[2], bh = hb - he;
  const double cx = c[0] - e[0], cy = c[1] - e[1], cz = c[2] - e[2], ch = hc - he;
  const double dx = d[0] - e[0], dy = d[1] - e[1], dz = d[2] - e[2], dh = hd - he;
  const double m_ab = ax * by - bx * ay, m_ac = ax * cy - cx * ay, m_ad = ax * dy - dx * ay;
  const double m_bc = bx * cy - cx * by, m_bd = bx * dy - dx * by, m_cd = cx * dy - dx * cy;
  const double d_bcd = (bz * m_cd - cz * m_bd) + dz * m_bc;
  const double d_acd = (az * m_cd - cz * m_ad) + dz * m_ac;
  const double d_abd = (az * m_bd - bz * m_ad) + dz * m_ab;
  const double d_abc = (az * m_bc - bz * m_ac) + cz * m_ab;
  const double det = (bh * d_acd - ah * d_bcd) + (dh * d_abc - ch * d_abd);
  const double mx = detail::absmax4(ax, bx, cx, dx);
  const double my = detail::absmax4(ay, by, cy, dy);
  const double mz = detail::absmax4(az, bz, cz, dz);
  const double mh = detail::absmax4(ah, bh, ch, dh);
  if (detail::in_range(detail::kInsphereMin, detail::kInsphereMax, mx, my, mz) &&
      detail::kHeightMin <= mh && mh <= detail::kHeightMax) {
    const double bound = detail::kOrient4dBound * mx * my * mz * mh;
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return detail::orient4d_exact(a, b, c, d, e, ha, hb, hc, hd, he);
}

inline int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                        const double* e, uint32_t ia, uint32_t ib, uint32_t ic, uint32_t id,
                        uint32_t ie) {
  const int s = insphere(a, b, c, d, e);
  if (s != 0) return s;
  return detail::insphere_sos_tie(a, b, c, d, e, ia, ib, ic, id, ie);
}

}  // namespace anitet::predicates

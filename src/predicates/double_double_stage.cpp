// Second filter stage in double-double arithmetic, between the fast filter and the exact
// expansions. Near-degenerate inputs whose determinant is tiny but not zero (points rounded onto
// a sphere or a tilted plane: every curved or oblique CAD surface) fail the fast filter, whose
// error is ~eps times the monomials; this stage's error is ~eps^2 times them, so it decides
// nearly all of them in ~100 ns instead of microseconds. Only (near-)exact degeneracies go on
// to the exact expansions.
//
// The differences are exact double-doubles (two_diff), so only the operations add error; with
// the rules of double_double.hpp and column maxima X, Y, Z (and Lmax, H as in filters.hpp):
//   xy minor = x_i y_j - x_j y_i:      2*8.1 + 3.1*2      = 22.4 u^2 XY,   |minor| <= 2XY
//   3x3 D = z m - z m + z m:           3*(22.4 + 16.2) + 3.1*(4 + 6) = 146.8 u^2 XYZ, |D| <= 6XYZ
//   lift L = x^2 + y^2 + z^2:          8.1 L (the squares) + 3.1*2 L = 14.3 u^2 L
//   L*D:                               14.3*6 + 146.8 + 8.1*6        = 281.2 u^2 L XYZ
//   (T0 - T1) + (T2 - T3), |T| <= 6LXYZ: 4*281.2 + 3.1*(12 + 12 + 24) = 1273.6 u^2 Lmax XYZ
//   orient4d, h*D with exact h:        146.8 + 48.6 = 195.4; 4*195.4 + 148.8 = 930.4 u^2 HXYZ
// Constants below carry a 1.1 factor for the second-order terms, the bound's own rounding and
// underflow; the ranges keep u^2 * (product of maxima) above 2^-950 and all values below 2^960.
#include <algorithm>
#include <cmath>

#include "predicates/double_double.hpp"
#include "predicates/exact.hpp"

namespace anitet::predicates::detail {
namespace {

constexpr double kU2 = 0x1p-106;
constexpr double kOrient3dDD = 1.1 * 146.8 * kU2;
constexpr double kInsphereDD = 1.1 * 1273.6 * kU2;
constexpr double kOrient4dDD = 1.1 * 930.4 * kU2;

DD minor2(const DD& x0, const DD& y0, const DD& x1, const DD& y1) {
  return dd_sub(dd_mul(x0, y1), dd_mul(x1, y0));
}

DD expand3(const DD& zj, const DD& m_kl, const DD& zk, const DD& m_jl, const DD& zl,
           const DD& m_jk) {
  return dd_add(dd_sub(dd_mul(zj, m_kl), dd_mul(zk, m_jl)), dd_mul(zl, m_jk));
}

double column_max(const DD* v, int n, int stride) {
  double m = 0;
  for (int i = 0; i < n; ++i) m = std::max(m, std::fabs(v[i * stride].hi));
  return m;
}

bool in(double lo, double hi, double v) { return lo <= v && v <= hi; }

int decide(const DD& det, double bound) {
  if (det.hi > bound) return 1;
  if (det.hi < -bound) return -1;
  return 0;
}

// Rows r[i] = p_i - e (i < 4) as exact double-doubles; the four 3x3 xyz minors of the rows
// without row 0, 1, 2, 3 (in that order).
void minors3(const DD (*r)[3], DD out[4]) {
  DD m[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) m[i][j] = minor2(r[i][0], r[i][1], r[j][0], r[j][1]);
  out[0] = expand3(r[1][2], m[2][3], r[2][2], m[1][3], r[3][2], m[1][2]);
  out[1] = expand3(r[0][2], m[2][3], r[2][2], m[0][3], r[3][2], m[0][2]);
  out[2] = expand3(r[0][2], m[1][3], r[1][2], m[0][3], r[3][2], m[0][1]);
  out[3] = expand3(r[0][2], m[1][2], r[1][2], m[0][2], r[2][2], m[0][1]);
}

}  // namespace

int orient3d_double_double(const double* a, const double* b, const double* c, const double* d) {
  DD r[3][3];
  const double* p[3] = {b, c, d};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i][k] = dd_diff(p[i][k], a[k]);
  const double mx = column_max(&r[0][0], 3, 3), my = column_max(&r[0][1], 3, 3);
  const double mz = column_max(&r[0][2], 3, 3);
  constexpr double kLo = 0x1p-280, kHi = 0x1p300;
  if (!(in(kLo, kHi, mx) && in(kLo, kHi, my) && in(kLo, kHi, mz))) return 0;
  const DD m_vw = minor2(r[1][0], r[1][1], r[2][0], r[2][1]);
  const DD m_uw = minor2(r[0][0], r[0][1], r[2][0], r[2][1]);
  const DD m_uv = minor2(r[0][0], r[0][1], r[1][0], r[1][1]);
  return decide(expand3(r[0][2], m_vw, r[1][2], m_uw, r[2][2], m_uv), kOrient3dDD * mx * my * mz);
}

int insphere_double_double(const double* a, const double* b, const double* c, const double* d,
                           const double* e) {
  DD r[4][3];
  const double* p[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) r[i][k] = dd_diff(p[i][k], e[k]);
  const double mx = column_max(&r[0][0], 4, 3), my = column_max(&r[0][1], 4, 3);
  const double mz = column_max(&r[0][2], 4, 3);
  constexpr double kLo = 0x1p-150, kHi = 0x1p190;
  if (!(in(kLo, kHi, mx) && in(kLo, kHi, my) && in(kLo, kHi, mz))) return 0;
  DD m3[4], lift[4];
  minors3(r, m3);
  double lmax = 0;
  for (int i = 0; i < 4; ++i) {
    lift[i] = dd_add(dd_add(dd_mul(r[i][0], r[i][0]), dd_mul(r[i][1], r[i][1])),
                     dd_mul(r[i][2], r[i][2]));
    lmax = std::max(lmax, lift[i].hi);
  }
  // insphere = sign((La*D_bcd - Lb*D_acd) + (Lc*D_abd - Ld*D_abc)).
  const DD det = dd_add(dd_sub(dd_mul(lift[0], m3[0]), dd_mul(lift[1], m3[1])),
                        dd_sub(dd_mul(lift[2], m3[2]), dd_mul(lift[3], m3[3])));
  return decide(det, kInsphereDD * mx * my * mz * lmax);
}

int orient4d_double_double(const double* a, const double* b, const double* c, const double* d,
                           const double* e, double ha, double hb, double hc, double hd,
                           double he) {
  DD r[4][3], h[4];
  const double* p[4] = {a, b, c, d};
  const double hp[4] = {ha, hb, hc, hd};
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) r[i][k] = dd_diff(p[i][k], e[k]);
    h[i] = dd_diff(hp[i], he);
  }
  const double mx = column_max(&r[0][0], 4, 3), my = column_max(&r[0][1], 4, 3);
  const double mz = column_max(&r[0][2], 4, 3), mh = column_max(h, 4, 1);
  constexpr double kLo = 0x1p-150, kHi = 0x1p190;
  if (!(in(kLo, kHi, mx) && in(kLo, kHi, my) && in(kLo, kHi, mz) &&
        in(0x1p-360, 0x1p380, mh)))
    return 0;
  DD m3[4];
  minors3(r, m3);
  // orient4d = sign((hb*D_acd - ha*D_bcd) + (hd*D_abc - hc*D_abd)).
  const DD det = dd_add(dd_sub(dd_mul(h[1], m3[1]), dd_mul(h[0], m3[0])),
                        dd_sub(dd_mul(h[3], m3[3]), dd_mul(h[2], m3[2])));
  return decide(det, kOrient4dDD * mx * my * mz * mh);
}

}  // namespace anitet::predicates::detail

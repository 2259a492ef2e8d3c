// Exact stage for lattice-like inputs (grids, structured CAD points): when every coordinate
// difference is exact and all of them are small integers times one power of two, the very same
// double formula as the filter computes the determinant without any rounding, so its sign is
// exact. Costs ~20 ns where the expansions take hundreds, on exactly the inputs (grids) whose
// determinants are often exactly 0 and must otherwise go all the way to the expansions.
//
// With every difference = n * 2^low, |n| < 2^bits, each intermediate of the formula is an
// integer multiple of 2^(k*low) below (terms) * 2^(k*bits) in those units; it is exact when that
// stays below 2^53 (and 2^(k*low) does not underflow, the values do not overflow):
//   orient3d  k = 3, |det| <= 6 * 2^(3 bits)            -> bits <= 16
//   insphere  k = 5, |det| <= 72 * 2^(5 bits)           -> bits <= 9
//   orient4d  k = 3 + 1, |det| <= 24 * 2^(3 bits + hbits) -> 3 bits + hbits <= 48
#include <climits>
#include <cstdint>
#include <cstring>

#include "predicates/exact.hpp"
#include "predicates/expansion.hpp"

namespace anitet::predicates::detail {
namespace {

// Exponents of the lowest and highest set bits over a set of doubles (zeros ignored).
struct BitSpan {
  int low = INT_MAX, high = INT_MIN;

  void include(double v) {
    if (v == 0) return;
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    const int biased = int((bits >> 52) & 0x7ff);
    uint64_t mant = bits & ((uint64_t(1) << 52) - 1);
    int unit = -1074;  // exponent of the mantissa's last bit
    if (biased != 0) {
      mant |= uint64_t(1) << 52;
      unit = biased - 1075;
    }
    low = low < unit + __builtin_ctzll(mant) ? low : unit + __builtin_ctzll(mant);
    const int top = unit + 63 - __builtin_clzll(mant);
    high = high > top ? high : top;
  }
  int bits() const { return high - low + 1; }
  bool empty() const { return high == INT_MIN; }
};

// d = a - b when exact.
bool exact_diff(double a, double b, double& d) {
  double err;
  two_diff(a, b, d, err);
  return err == 0;
}

// Rows p_i - o (i < n) of exact differences and their bit span; false when one is inexact.
bool exact_rows(const double* const* p, int n, const double* o, double (*r)[3], BitSpan& span) {
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      if (!exact_diff(p[i][k], o[k], r[i][k])) return false;
      span.include(r[i][k]);
    }
  return true;
}

int sign(double v) { return (v > 0) - (v < 0); }

// The four 3x3 xyz minors of rows {1,2,3}, {0,2,3}, {0,1,3}, {0,1,2}.
void minors3(const double (*r)[3], double out[4]) {
  auto m = [&](int i, int j) { return r[i][0] * r[j][1] - r[j][0] * r[i][1]; };
  out[0] = (r[1][2] * m(2, 3) - r[2][2] * m(1, 3)) + r[3][2] * m(1, 2);
  out[1] = (r[0][2] * m(2, 3) - r[2][2] * m(0, 3)) + r[3][2] * m(0, 2);
  out[2] = (r[0][2] * m(1, 3) - r[1][2] * m(0, 3)) + r[3][2] * m(0, 1);
  out[3] = (r[0][2] * m(1, 2) - r[1][2] * m(0, 2)) + r[2][2] * m(0, 1);
}

}  // namespace

bool orient3d_lattice(const double* a, const double* b, const double* c, const double* d,
                      int& result) {
  const double* p[3] = {b, c, d};
  double r[3][3];
  BitSpan span;
  if (!exact_rows(p, 3, a, r, span)) return false;
  if (span.empty()) {
    result = 0;
    return true;
  }
  if (span.bits() > 16 || span.low < -358 || span.high > 330) return false;
  const double m_vw = r[1][0] * r[2][1] - r[2][0] * r[1][1];
  const double m_uw = r[0][0] * r[2][1] - r[2][0] * r[0][1];
  const double m_uv = r[0][0] * r[1][1] - r[1][0] * r[0][1];
  result = sign((r[0][2] * m_vw - r[1][2] * m_uw) + r[2][2] * m_uv);
  return true;
}

bool insphere_lattice(const double* a, const double* b, const double* c, const double* d,
                      const double* e, int& result) {
  const double* p[4] = {a, b, c, d};
  double r[4][3];
  BitSpan span;
  if (!exact_rows(p, 4, e, r, span)) return false;
  if (span.empty()) {
    result = 0;
    return true;
  }
  if (span.bits() > 9 || span.low < -214 || span.high > 190) return false;
  double m3[4], lift[4];
  minors3(r, m3);
  for (int i = 0; i < 4; ++i) lift[i] = r[i][0] * r[i][0] + r[i][1] * r[i][1] + r[i][2] * r[i][2];
  result = sign((lift[0] * m3[0] - lift[1] * m3[1]) + (lift[2] * m3[2] - lift[3] * m3[3]));
  return true;
}

bool orient4d_lattice(const double* a, const double* b, const double* c, const double* d,
                      const double* e, double ha, double hb, double hc, double hd, double he,
                      int& result) {
  const double* p[4] = {a, b, c, d};
  const double hp[4] = {ha, hb, hc, hd};
  double r[4][3], h[4];
  BitSpan span, hspan;
  if (!exact_rows(p, 4, e, r, span)) return false;
  for (int i = 0; i < 4; ++i) {
    if (!exact_diff(hp[i], he, h[i])) return false;
    hspan.include(h[i]);
  }
  if (span.empty() || hspan.empty()) {
    result = 0;
    return true;
  }
  // The coordinate-only minors need their own range too (the heights may be far larger or
  // smaller than the coordinates).
  if (3 * span.bits() + hspan.bits() > 48 || 3 * span.low < -1074 ||
      3 * span.low + hspan.low < -1074 || 3 * span.high > 1000 ||
      3 * span.high + hspan.high > 1000)
    return false;
  double m3[4];
  minors3(r, m3);
  result = sign((h[1] * m3[1] - h[0] * m3[0]) + (h[3] * m3[3] - h[2] * m3[2]));
  return true;
}

}  // namespace anitet::predicates::detail

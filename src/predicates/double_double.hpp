// Double-double arithmetic with a proven absolute error (internal to the predicates module).
// A DD is hi + lo with |lo| <= u|hi| (u = 2^-53), kept so by renormalizing after each operation
// with an exact two_sum. First-order error of each operation, for |a| <= A, |b| <= B and
// already-accumulated errors e(a), e(b) (derivation: every product or sum of low parts is
// O(u) of the result and rounded once more, so each costs u^2 times its operands' magnitude):
//   dd_add:  e(a) + e(b) + 3.1 u^2 (A + B)
//     fl(al + bl) rounds by <= u^2 (A + B); adding the two_sum error (<= u|s|) rounds by
//     <= 2 u^2 (A + B).
//   dd_mul:  e(a) B + A e(b) + 8.1 u^2 A B
//     dropping al*bl: u^2 AB; rounding ah*bl and al*bh: u^2 AB each; their sum: 2 u^2 AB;
//     adding the two_prod error (<= u AB): 3 u^2 AB.
// (the .1 absorbs the (1+u)^k factors). Same exactness conditions as expansion.hpp for two_prod
// (no overflow, operands < 2^995); underflow only adds absolute errors of 2^-1075 per operation,
// which the callers' ranges make negligible against the bound.
#pragma once

#include "predicates/expansion.hpp"

namespace anitet::predicates::detail {

struct DD {
  double hi, lo;
};

inline DD dd_renorm(double hi, double lo) {
  DD r;
  two_sum(hi, lo, r.hi, r.lo);
  return r;
}
// a - b exactly (error 0).
inline DD dd_diff(double a, double b) {
  DD r;
  two_diff(a, b, r.hi, r.lo);
  return r;
}
inline DD dd_add(const DD& a, const DD& b) {
  double s, e;
  two_sum(a.hi, b.hi, s, e);
  return dd_renorm(s, e + (a.lo + b.lo));
}
inline DD dd_sub(const DD& a, const DD& b) { return dd_add(a, DD{-b.hi, -b.lo}); }
inline DD dd_mul(const DD& a, const DD& b) {
  double p, e;
  two_prod(a.hi, b.hi, p, e);
  return dd_renorm(p, e + (a.hi * b.lo + a.lo * b.hi));
}

}  // namespace anitet::predicates::detail

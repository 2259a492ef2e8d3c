// Exact floating-point expansion arithmetic (internal to the predicates module).
//
// An expansion is a sum of doubles e[0] + e[1] + ... + e[n-1], nonoverlapping and sorted by
// increasing magnitude, with no zero component (n == 0 means the value 0). Every operation here is
// an exact transformation: two_sum / two_prod return the rounded result and its exact rounding
// error, the expansion sum merges two expansions and propagates the errors, scaling multiplies
// by one double. Under round-to-nearest-even these preserve the nonoverlapping property
// (Shewchuk 1997, theorems 6, 13, 19), so the sign of an expansion is the sign of its last
// (largest) component.
//
// Exactness needs: no overflow, and every intermediate value lying on a grid of spacing
// >= 2^-1022, so that no error term is subnormal or lost. The callers check a coordinate range
// that guarantees both (see exact_expansion.cpp); outside it they use GMP.
//
// Capacities are compile-time: Exp<N> holds at most N components and every operation
// static_asserts that its output capacity covers the worst case, so no array can overflow.
//
// This file must be compiled without floating-point contraction or fast-math (the CMake target
// sets -ffp-contract=off): two_sum and the Dekker split depend on each operation being rounded.
#pragma once

#if defined(__FAST_MATH__)
#error "anitet predicates need IEEE-754 arithmetic: do not compile with -ffast-math"
#endif

#include <cmath>

namespace anitet::predicates::detail {

// a + b = x + y exactly, x = fl(a + b) (Knuth's branch-free two-sum).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// a - b = x + y exactly.
inline void two_diff(double a, double b, double& x, double& y) { two_sum(a, -b, x, y); }

// a * b = x + y exactly, x = fl(a * b). With hardware FMA the error is one fused operation;
// otherwise Dekker's product: split each factor into two 26-bit halves whose partial products are
// exact, then subtract them from x in decreasing order of size (each subtraction is exact).
inline void two_prod(double a, double b, double& x, double& y) {
  x = a * b;
#if defined(__FMA__) || defined(__FP_FAST_FMA)
  y = std::fma(a, b, -x);
#else
  constexpr double kSplitter = 134217729.0;  // 2^27 + 1
  const double ca = kSplitter * a;
  const double a_hi = ca - (ca - a);
  const double a_lo = a - a_hi;
  const double cb = kSplitter * b;
  const double b_hi = cb - (cb - b);
  const double b_lo = b - b_hi;
  const double err1 = x - a_hi * b_hi;
  const double err2 = err1 - a_lo * b_hi;
  const double err3 = err2 - a_hi * b_lo;
  y = a_lo * b_lo - err3;
#endif
}

template <int N>
struct Exp {
  static constexpr int capacity = N;
  double v[N];
  int n = 0;

  int sign() const { return n == 0 ? 0 : (v[n - 1] > 0 ? 1 : -1); }
};

// One double as an expansion.
inline Exp<1> exp1(double a) {
  Exp<1> r;
  r.n = 0;
  if (a != 0) r.v[r.n++] = a;
  return r;
}

// a - b exactly, as an expansion of at most 2 components.
inline Exp<2> exp_diff(double a, double b) {
  double x, y;
  two_diff(a, b, x, y);
  Exp<2> r;
  r.n = 0;
  if (y != 0) r.v[r.n++] = y;
  if (x != 0) r.v[r.n++] = x;
  return r;
}

// a * b exactly, as an expansion of at most 2 components.
inline Exp<2> exp_prod(double a, double b) {
  double x, y;
  two_prod(a, b, x, y);
  Exp<2> r;
  r.n = 0;
  if (y != 0) r.v[r.n++] = y;
  if (x != 0) r.v[r.n++] = x;
  return r;
}

// Raw kernels on (pointer, length); the Exp<N> wrappers below prove the capacities. An output
// never aliases an input (except in compress_raw, which works in place).

// h = e + s*f, s = +1 or -1: merge the components by increasing magnitude, then accumulate them
// with two_sum, emitting each nonzero rounding error (Shewchuk's fast expansion sum, with
// two_sum throughout and zero elimination). Returns the length of h (<= ne + nf).
inline int sum_raw(const double* e, int ne, const double* f, int nf, double s, double* h) {
  int i = 0, j = 0, k = 0;
  double q;
  if (ne == 0 && nf == 0) return 0;
  if (j == nf || (i < ne && std::fabs(e[i]) < std::fabs(f[j]))) {
    q = e[i++];
  } else {
    q = s * f[j++];
  }
  while (i < ne || j < nf) {
    double g;
    if (j == nf || (i < ne && std::fabs(e[i]) < std::fabs(f[j]))) {
      g = e[i++];
    } else {
      g = s * f[j++];
    }
    double sum, err;
    two_sum(q, g, sum, err);
    if (err != 0) h[k++] = err;
    q = sum;
  }
  if (q != 0) h[k++] = q;
  return k;
}

// h = e * b (Shewchuk's scale expansion, two_sum throughout, zero elimination). Length <= 2 ne.
inline int scale_raw(const double* e, int ne, double b, double* h) {
  if (ne == 0 || b == 0) return 0;
  int k = 0;
  double q, err;
  two_prod(e[0], b, q, err);
  if (err != 0) h[k++] = err;
  for (int i = 1; i < ne; ++i) {
    double p_hi, p_lo, sum;
    two_prod(e[i], b, p_hi, p_lo);
    two_sum(q, p_lo, sum, err);
    if (err != 0) h[k++] = err;
    two_sum(p_hi, sum, q, err);
    if (err != 0) h[k++] = err;
  }
  if (q != 0) h[k++] = q;
  return k;
}

// Compress e in place (Shewchuk's Compress): the same value as a nonoverlapping expansion whose
// largest component approximates the sum within one ulp, usually with far fewer components.
// A top-down sweep gathers the large parts, a bottom-up sweep re-emits the errors.
// Returns the new length (<= m).
inline int compress_raw(double* e, int m) {
  if (m == 0) return 0;
  int bottom = m - 1;
  double q = e[bottom];
  for (int i = m - 2; i >= 0; --i) {
    double sum, err;
    two_sum(q, e[i], sum, err);
    if (err != 0) {
      e[bottom--] = sum;  // bottom > i: that slot was already read
      q = err;
    } else {
      q = sum;
    }
  }
  int top = 0;
  for (int i = bottom + 1; i < m; ++i) {
    double sum, err;
    two_sum(e[i], q, sum, err);
    if (err != 0) e[top++] = err;  // top < i: that slot was already read
    q = sum;
  }
  if (q != 0) e[top++] = q;
  return top;
}

template <int N>
void exp_compress(Exp<N>& e) {
  e.n = compress_raw(e.v, e.n);
}

// h = e + f and h = e - f.
template <int N, int A, int B>
void exp_add(const Exp<A>& e, const Exp<B>& f, Exp<N>& h) {
  static_assert(N >= A + B, "expansion sum capacity");
  h.n = sum_raw(e.v, e.n, f.v, f.n, 1.0, h.v);
}
template <int N, int A, int B>
void exp_sub(const Exp<A>& e, const Exp<B>& f, Exp<N>& h) {
  static_assert(N >= A + B, "expansion sum capacity");
  h.n = sum_raw(e.v, e.n, f.v, f.n, -1.0, h.v);
}

// h = e * b.
template <int N, int A>
void exp_scale(const Exp<A>& e, double b, Exp<N>& h) {
  static_assert(N >= 2 * A, "expansion scale capacity");
  h.n = scale_raw(e.v, e.n, b, h.v);
}

// h = e * f: the longer operand scaled by each component of the shorter one, the partial
// products summed as they come (after j components the sum has at most 2*long*j components).
template <int N, int A, int B>
void exp_mul(const Exp<A>& e, const Exp<B>& f, Exp<N>& h) {
  static_assert(N >= 2 * A * B, "expansion product capacity");
  constexpr int kMaxLong = A > B ? A : B;
  const bool e_longer = e.n >= f.n;
  const double* lng = e_longer ? e.v : f.v;
  const double* shrt = e_longer ? f.v : e.v;
  const int n_long = e_longer ? e.n : f.n;
  const int n_short = e_longer ? f.n : e.n;
  if (n_short == 0) {
    h.n = 0;
    return;
  }
  if (n_short == 1) {
    h.n = scale_raw(lng, n_long, shrt[0], h.v);
    return;
  }
  double term[2 * kMaxLong];
  double other[N];
  // Ping-pong between h.v and other so that the final sum lands in h.v.
  double* cur = (n_short % 2 == 1) ? h.v : other;
  double* nxt = (n_short % 2 == 1) ? other : h.v;
  int n = scale_raw(lng, n_long, shrt[0], cur);
  for (int j = 1; j < n_short; ++j) {
    const int nt = scale_raw(lng, n_long, shrt[j], term);
    n = sum_raw(cur, n, term, nt, 1.0, nxt);
    double* t = cur;
    cur = nxt;
    nxt = t;
  }
  h.n = n;
}

}  // namespace anitet::predicates::detail

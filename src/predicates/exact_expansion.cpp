// Exact predicates in expansion arithmetic (no heap, fixed-size stack arrays).
//
// Valid range. Every input double is an integer multiple of its last bit, so with q the
// smallest last-bit exponent among the inputs, every degree-k product of inputs, and every
// rounding error two_sum/two_prod produce while summing such products, is a multiple of 2^(kq).
// If kq >= -1022 no error term can be subnormal, so all of them are exactly representable.
// A nonzero |v| >= 2^-m has its last bit at >= 2^(-m-52). Overflow needs the largest values,
// (number of terms) * max^k, below 2^1023, and the Dekker split needs its operands < 2^995.
//   orient2d  degree 2:  |v| in [2^-450, 2^450]   (last bit >= 2^-502,  2*-502 = -1004)
//   orient3d  degree 3:  |v| in [2^-280, 2^320]   (last bit >= 2^-332,  3*-332 = -996)
//   insphere  degree 5:  |v| in [2^-150, 2^190]   (last bit >= 2^-202,  5*-202 = -1010;
//                                                    24*3*2^(5*190+2) < 2^965)
//   orient4d  degree 3 in coordinates + 1 in heights: coordinates as insphere, heights in
//             [2^-360, 2^380] (3*-202 + -412 = -1018; 120*2^(3*190+380) < 2^957)
// (zero is always allowed). Outside these ranges the caller uses GMP.
//
// Sizes: differences are 2-component expansions; the Exp<N> capacities below are the proven
// worst cases (static_asserts in expansion.hpp). The general insphere (raw coordinates) needs
// up to 5760 components: it is the only path with a large stack frame (~110 KB). Intermediate
// minors and lifts are compressed before they are multiplied, which keeps the actual lengths
// short (a few components) and the exact path fast.
#include <cmath>

#include "predicates/exact.hpp"
#include "predicates/expansion.hpp"

namespace anitet::predicates::detail {
namespace {

// x0*y1 - x1*y0.
template <int A>
Exp<4 * A * A> minor2(const Exp<A>& x0, const Exp<A>& y0, const Exp<A>& x1, const Exp<A>& y1) {
  Exp<2 * A * A> p, q;
  exp_mul(x0, y1, p);
  exp_mul(x1, y0, q);
  Exp<4 * A * A> r;
  exp_sub(p, q, r);
  return r;
}

// zj*m_kl - zk*m_jl + zl*m_jk: a 3x3 determinant expanded along its last column.
template <int A, int M>
Exp<6 * A * M> expand3(const Exp<A>& zj, const Exp<M>& m_kl, const Exp<A>& zk, const Exp<M>& m_jl,
                       const Exp<A>& zl, const Exp<M>& m_jk) {
  Exp<2 * A * M> t1, t2, t3;
  exp_mul(zj, m_kl, t1);
  exp_mul(zk, m_jl, t2);
  exp_mul(zl, m_jk, t3);
  Exp<4 * A * M> s;
  exp_sub(t1, t2, s);
  Exp<6 * A * M> r;
  exp_add(s, t3, r);
  return r;
}

// (f0*g0 - f1*g1) + (f2*g2 - f3*g3).
template <int F, int G>
Exp<8 * F * G> alternating_sum4(const Exp<F>* f[4], const Exp<G>* g[4]) {
  Exp<2 * F * G> t[4];
  for (int i = 0; i < 4; ++i) exp_mul(*f[i], *g[i], t[i]);
  Exp<4 * F * G> s01, s23;
  exp_sub(t[0], t[1], s01);
  exp_sub(t[2], t[3], s23);
  Exp<8 * F * G> r;
  exp_add(s01, s23, r);
  return r;
}

// x^2 + y^2 + z^2 of single doubles.
Exp<6> lift(double x, double y, double z) {
  const Exp<2> xx = exp_prod(x, x), yy = exp_prod(y, y), zz = exp_prod(z, z);
  Exp<4> s;
  exp_add(xx, yy, s);
  Exp<6> r;
  exp_add(s, zz, r);
  return r;
}

bool all_in_range(const double* v, int n, double lo, double hi) {
  for (int i = 0; i < n; ++i) {
    const double m = std::fabs(v[i]);
    if (!(m == 0 || (lo <= m && m <= hi))) return false;
  }
  return true;
}

// The four 3x3 xyz determinants of rows {b,c,d}, {a,c,d}, {a,b,d}, {a,b,c} of single-double
// rows r[0..3] (each row x, y, z).
void minors3_of_rows(const Exp<1> (*r)[3], Exp<24> out[4]) {
  Exp<4> m[4][4];
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) m[i][j] = minor2(r[i][0], r[i][1], r[j][0], r[j][1]);
  out[0] = expand3(r[1][2], m[2][3], r[2][2], m[1][3], r[3][2], m[1][2]);
  out[1] = expand3(r[0][2], m[2][3], r[2][2], m[0][3], r[3][2], m[0][2]);
  out[2] = expand3(r[0][2], m[1][3], r[1][2], m[0][3], r[3][2], m[0][1]);
  out[3] = expand3(r[0][2], m[1][2], r[1][2], m[0][2], r[2][2], m[0][1]);
  for (int i = 0; i < 4; ++i) exp_compress(out[i]);
}

// The five 4x4 determinants det[x y z 1] of the points p (raw coordinates) without point i.
void minors4_of_points(const double* const p[5], Exp<96> out[5]) {
  Exp<4> m[5][5];  // xy minors x_i y_j - x_j y_i
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) {
      const Exp<1> xi = exp1(p[i][0]), yi = exp1(p[i][1]), xj = exp1(p[j][0]), yj = exp1(p[j][1]);
      m[i][j] = minor2(xi, yi, xj, yj);
    }
  // det[x y 1] of rows j < k < l: m_kl - m_jl + m_jk.
  auto det_xy1 = [&](int j, int k, int l) {
    Exp<8> s;
    exp_sub(m[k][l], m[j][l], s);
    Exp<12> r;
    exp_add(s, m[j][k], r);
    exp_compress(r);
    return r;
  };
  for (int skip = 0; skip < 5; ++skip) {
    int q[4], n = 0;
    for (int i = 0; i < 5; ++i)
      if (i != skip) q[n++] = i;
    // Expansion along the z column: z_q0 T(q1q2q3) - z_q1 T(q0q2q3) + z_q2 T(q0q1q3) - ...
    const Exp<12> t0 = det_xy1(q[1], q[2], q[3]), t1 = det_xy1(q[0], q[2], q[3]);
    const Exp<12> t2 = det_xy1(q[0], q[1], q[3]), t3 = det_xy1(q[0], q[1], q[2]);
    const Exp<1> z0 = exp1(p[q[0]][2]), z1 = exp1(p[q[1]][2]);
    const Exp<1> z2 = exp1(p[q[2]][2]), z3 = exp1(p[q[3]][2]);
    const Exp<1>* f[4] = {&z0, &z1, &z2, &z3};
    const Exp<12>* g[4] = {&t0, &t1, &t2, &t3};
    out[skip] = alternating_sum4(f, g);
    exp_compress(out[skip]);
  }
}

}  // namespace

int orient2d_expansion(const double* a, const double* b, const double* c) {
  const Exp<2> ux = exp_diff(b[0], a[0]), uy = exp_diff(b[1], a[1]);
  const Exp<2> vx = exp_diff(c[0], a[0]), vy = exp_diff(c[1], a[1]);
  return minor2(ux, uy, vx, vy).sign();
}

int orient3d_expansion(const double* a, const double* b, const double* c, const double* d) {
  Exp<2> u[3], v[3], w[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = exp_diff(b[k], a[k]);
    v[k] = exp_diff(c[k], a[k]);
    w[k] = exp_diff(d[k], a[k]);
  }
  Exp<16> m_vw = minor2(v[0], v[1], w[0], w[1]);
  Exp<16> m_uw = minor2(u[0], u[1], w[0], w[1]);
  Exp<16> m_uv = minor2(u[0], u[1], v[0], v[1]);
  exp_compress(m_vw);
  exp_compress(m_uw);
  exp_compress(m_uv);
  return expand3(u[2], m_vw, v[2], m_uw, w[2], m_uv).sign();
}

int insphere_expansion_diff(const double* a, const double* b, const double* c, const double* d,
                            const double* e) {
  const double* p[4] = {a, b, c, d};
  Exp<1> r[4][3];
  Exp<6> l[4];
  for (int i = 0; i < 4; ++i) {
    double dif[3];
    for (int k = 0; k < 3; ++k) {
      dif[k] = p[i][k] - e[k];  // exact by precondition
      r[i][k] = exp1(dif[k]);
    }
    l[i] = lift(dif[0], dif[1], dif[2]);
    exp_compress(l[i]);
  }
  Exp<24> m3[4];
  minors3_of_rows(r, m3);
  // insphere = sign(La*D_bcd - Lb*D_acd + Lc*D_abd - Ld*D_abc).
  const Exp<6>* f[4] = {&l[0], &l[1], &l[2], &l[3]};
  const Exp<24>* g[4] = {&m3[0], &m3[1], &m3[2], &m3[3]};
  return alternating_sum4(f, g).sign();
}

int insphere_expansion(const double* a, const double* b, const double* c, const double* d,
                       const double* e) {
  const double* const p[5] = {a, b, c, d, e};
  Exp<96> m4[5];
  minors4_of_points(p, m4);
  // insphere = -det[x y z |p|^2 1] = sign(sum_i (-1)^i L_i * det4(points but i)).
  constexpr int kMax = 5 * 1152;
  double buf0[kMax], buf1[kMax];
  double* acc = buf0;
  double* next = buf1;
  int n = 0;
  for (int i = 0; i < 5; ++i) {
    Exp<6> li = lift(p[i][0], p[i][1], p[i][2]);
    exp_compress(li);
    Exp<1152> term;
    exp_mul(li, m4[i], term);
    n = sum_raw(acc, n, term.v, term.n, (i % 2 == 0) ? 1.0 : -1.0, next);
    double* t = acc;
    acc = next;
    next = t;
  }
  return n == 0 ? 0 : (acc[n - 1] > 0 ? 1 : -1);
}

int orient4d_expansion_diff(const double* a, const double* b, const double* c, const double* d,
                            const double* e, double ha, double hb, double hc, double hd,
                            double he) {
  const double* p[4] = {a, b, c, d};
  const double h[4] = {ha, hb, hc, hd};
  Exp<1> r[4][3];
  Exp<1> dh[4];
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) r[i][k] = exp1(p[i][k] - e[k]);  // exact by precondition
    dh[i] = exp1(h[i] - he);
  }
  Exp<24> m3[4];
  minors3_of_rows(r, m3);
  // orient4d = sign((hb*D_acd - ha*D_bcd) + (hd*D_abc - hc*D_abd)).
  const Exp<1>* f[4] = {&dh[1], &dh[0], &dh[3], &dh[2]};
  const Exp<24>* g[4] = {&m3[1], &m3[0], &m3[3], &m3[2]};
  return alternating_sum4(f, g).sign();
}

int orient4d_expansion(const double* a, const double* b, const double* c, const double* d,
                       const double* e, double ha, double hb, double hc, double hd, double he) {
  const double* const p[5] = {a, b, c, d, e};
  const double h[5] = {ha, hb, hc, hd, he};
  Exp<96> m4[5];
  minors4_of_points(p, m4);
  // orient4d = sign(det[x y z h 1]) = sign(sum_i (-1)^(i+1) h_i * det4(points but i)).
  Exp<192> t[5];
  for (int i = 0; i < 5; ++i) exp_scale(m4[i], h[i], t[i]);
  Exp<384> s10, s32;
  exp_sub(t[1], t[0], s10);
  exp_sub(t[3], t[2], s32);
  Exp<768> s;
  exp_add(s10, s32, s);
  Exp<960> r;
  exp_sub(s, t[4], r);
  return r.sign();
}

bool orient2d_in_range(const double* a, const double* b, const double* c) {
  const double v[6] = {a[0], a[1], b[0], b[1], c[0], c[1]};
  return all_in_range(v, 6, 0x1p-450, 0x1p450);
}

bool orient3d_in_range(const double* a, const double* b, const double* c, const double* d) {
  const double* p[4] = {a, b, c, d};
  for (const double* q : p)
    if (!all_in_range(q, 3, 0x1p-280, 0x1p320)) return false;
  return true;
}

bool insphere_in_range(const double* const p[5]) {
  for (int i = 0; i < 5; ++i)
    if (!all_in_range(p[i], 3, 0x1p-150, 0x1p190)) return false;
  return true;
}

bool orient4d_in_range(const double* const p[5], const double h[5]) {
  return insphere_in_range(p) && all_in_range(h, 5, 0x1p-360, 0x1p380);
}

bool differences_exact(const double* const p[5], const double* h) {
  double x, y;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      two_diff(p[i][k], p[4][k], x, y);
      if (y != 0) return false;
    }
    if (h != nullptr) {
      two_diff(h[i], h[4], x, y);
      if (y != 0) return false;
    }
  }
  return true;
}

}  // namespace anitet::predicates::detail

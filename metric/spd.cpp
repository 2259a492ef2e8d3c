#include "spd.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace anitet {
namespace metric {
namespace {

Eigen::Matrix3d to_matrix(const double m[6]) {
  Eigen::Matrix3d a;
  a << m[0], m[1], m[3], m[1], m[2], m[4], m[3], m[4], m[5];
  return a;
}

void from_matrix(const Eigen::Matrix3d& a, double m[6]) {
  // Average the off-diagonal pairs: products of symmetric matrices drift by rounding.
  m[0] = a(0, 0);
  m[1] = 0.5 * (a(0, 1) + a(1, 0));
  m[2] = a(1, 1);
  m[3] = 0.5 * (a(0, 2) + a(2, 0));
  m[4] = 0.5 * (a(1, 2) + a(2, 1));
  m[5] = a(2, 2);
}

// c = a * b for symmetric a, b that commute (powers of one matrix): c is symmetric.
inline void sym_mul(const double a[6], const double b[6], double c[6]) {
  c[0] = a[0] * b[0] + a[1] * b[1] + a[3] * b[3];
  c[1] = a[0] * b[1] + a[1] * b[2] + a[3] * b[4];
  c[2] = a[1] * b[1] + a[2] * b[2] + a[4] * b[4];
  c[3] = a[0] * b[3] + a[1] * b[4] + a[3] * b[5];
  c[4] = a[1] * b[3] + a[2] * b[4] + a[4] * b[5];
  c[5] = a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
}

}  // namespace

void sym_eigen(const double m[6], double val[3], double vec[9]) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(to_matrix(m));
  for (int k = 0; k < 3; ++k) {
    val[k] = es.eigenvalues()(k);
    for (int i = 0; i < 3; ++i) vec[3 * k + i] = es.eigenvectors()(i, k);
  }
}

bool sym_log(const double m[6], double out[6]) {
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(m[i])) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(to_matrix(m));
  const Eigen::Vector3d v = es.eigenvalues();
  if (!(v(0) > 0.0)) return false;
  const Eigen::Matrix3d q = es.eigenvectors();
  const Eigen::Vector3d lv(std::log(v(0)), std::log(v(1)), std::log(v(2)));
  from_matrix(q * lv.asDiagonal() * q.transpose(), out);
  return true;
}

void sym_exp(const double l[6], double out[6]) {
  const double tr = (l[0] + l[2] + l[5]) / 3.0;
  double d[6] = {l[0] - tr, l[1], l[2] - tr, l[3], l[4], l[5] - tr};
  const double norm2 = d[0] * d[0] + d[2] * d[2] + d[5] * d[5] +
                       2.0 * (d[1] * d[1] + d[3] * d[3] + d[4] * d[4]);
  const double e = std::exp(tr);
  if (norm2 < 1e-32) {
    out[0] = out[2] = out[5] = e;
    out[1] = out[3] = out[4] = 0.0;
    return;
  }
  // Scale the trace-free part to Frobenius norm <= 1/8, where a degree-9 Taylor series is exact
  // to ~1e-16, then square back.
  int squarings = 0;
  double norm = std::sqrt(norm2);
  while (norm > 0.125) {
    norm *= 0.5;
    ++squarings;
  }
  const double s = std::ldexp(1.0, -squarings);
  for (double& x : d) x *= s;
  // Degree-9 Taylor polynomial, Paterson-Stockmeyer: with B_j = c_3j I + c_3j+1 d + c_3j+2 d^2,
  // p = B0 + d^3 (B1 + d^3 (B2 + c_9 d^3)): 4 products instead of 9.
  static const double c[10] = {1.0,       1.0,        1.0 / 2,     1.0 / 6,      1.0 / 24,
                               1.0 / 120, 1.0 / 720,  1.0 / 5040,  1.0 / 40320,  1.0 / 362880};
  double d2[6], d3[6], r[6], t[6];
  sym_mul(d, d, d2);
  sym_mul(d2, d, d3);
  auto block = [&](int j, const double* add, double* res) {
    for (int i = 0; i < 6; ++i) res[i] = add[i] + c[3 * j + 1] * d[i] + c[3 * j + 2] * d2[i];
    res[0] += c[3 * j];
    res[2] += c[3 * j];
    res[5] += c[3 * j];
  };
  for (int i = 0; i < 6; ++i) t[i] = c[9] * d3[i];
  block(2, t, r);
  sym_mul(d3, r, t);
  block(1, t, r);
  sym_mul(d3, r, t);
  block(0, t, r);
  for (int k = 0; k < squarings; ++k) {
    double rr[6];
    sym_mul(r, r, rr);
    std::copy(rr, rr + 6, r);
  }
  for (int i = 0; i < 6; ++i) out[i] = r[i] * e;
}

bool cholesky(const double m[6], double l[6]) {
  const double l00 = std::sqrt(m[0]);
  if (!(l00 > 0.0)) return false;
  const double l10 = m[1] / l00, l20 = m[3] / l00;
  const double d11 = m[2] - l10 * l10;
  if (!(d11 > 0.0)) return false;
  const double l11 = std::sqrt(d11);
  const double l21 = (m[4] - l20 * l10) / l11;
  const double d22 = m[5] - l20 * l20 - l21 * l21;
  if (!(d22 > 0.0)) return false;
  l[0] = l00, l[1] = l10, l[2] = l11, l[3] = l20, l[4] = l21, l[5] = std::sqrt(d22);
  return true;
}

bool is_spd(const double m[6]) {
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(m[i])) return false;
  // Cholesky pivots of [[a b d] [b c e] [d e f]].
  const double p0 = m[0];
  if (!(p0 > 0.0)) return false;
  const double l10 = m[1] / p0 * 1.0;
  const double p1 = m[2] - m[1] * l10;
  if (!(p1 > 0.0)) return false;
  const double l20 = m[3] / p0;
  const double l21 = (m[4] - m[3] * l10) / p1;
  const double p2 = m[5] - m[3] * l20 - l21 * l21 * p1;
  return p2 > 0.0;
}

double min_eigenvalue(const double m[6]) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(to_matrix(m), Eigen::EigenvaluesOnly);
  return es.eigenvalues()(0);
}

bool intersect(const double a[6], const double b[6], double out[6]) {
  if (!is_spd(a) || !is_spd(b)) return false;
  const Eigen::Matrix3d ma = to_matrix(a), mb = to_matrix(b);
  const Eigen::LLT<Eigen::Matrix3d> llt(ma);
  const Eigen::Matrix3d l = llt.matrixL();
  // c = L^-1 B L^-T, symmetric; in the basis where A is I, B is c.
  const Eigen::Matrix3d linv_b = l.triangularView<Eigen::Lower>().solve(mb);
  Eigen::Matrix3d c = l.triangularView<Eigen::Lower>().solve(linv_b.transpose());
  c = 0.5 * (c + c.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(c);
  Eigen::Vector3d d = es.eigenvalues();
  for (int k = 0; k < 3; ++k) d(k) = std::max(d(k), 1.0);
  const Eigen::Matrix3d q = es.eigenvectors();
  const Eigen::Matrix3d lq = l * q;
  from_matrix(lq * d.asDiagonal() * lq.transpose(), out);
  return true;
}

bool clamp_sizes(const double m[6], double hmin, double hmax, double out[6]) {
  if (!is_spd(m)) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(to_matrix(m));
  Eigen::Vector3d v = es.eigenvalues();
  const double lo = 1.0 / (hmax * hmax), hi = 1.0 / (hmin * hmin);
  for (int k = 0; k < 3; ++k) v(k) = std::min(std::max(v(k), lo), hi);
  const Eigen::Matrix3d q = es.eigenvectors();
  from_matrix(q * v.asDiagonal() * q.transpose(), out);
  return true;
}

}  // namespace metric
}  // namespace anitet

// Symmetric 3x3 tensors stored as 6 doubles in the order xx xy yy xz yz zz (see core/sizing.hpp),
// and the operations metric fields need on them: log and exp (the log-Euclidean framework of
// Arsigny et al. 2006: interpolate log(M), map back with exp, so results stay SPD), the
// intersection of two metrics, and SPD checks. No OpenVDB and no Eigen in this header.
#pragma once

namespace anitet {
namespace metric {

// Eigen-decomposition of a symmetric tensor: values ascending, vectors as columns (vec[3*k+i] is
// component i of the k-th vector).
void sym_eigen(const double m[6], double val[3], double vec[9]);

// log(M) for an SPD M. Returns false (and leaves out untouched) when M is not SPD.
bool sym_log(const double m[6], double out[6]);
// exp(L) for a symmetric L (always SPD). Scaling and squaring of a Taylor series on the
// trace-free part, so the isotropic case costs one std::exp; relative error ~1e-14.
void sym_exp(const double l[6], double out[6]);

// True when m is symmetric positive definite (all Cholesky pivots > 0).
bool is_spd(const double m[6]);
// M = L L^T with L lower triangular, l = l00 l10 l11 l20 l21 l22 (y = L^T x measures x in M:
// |y| = sqrt(x^T M x)). False, with l untouched, when a pivot is not > 0.
bool cholesky(const double m[6], double l[6]);
// The smallest eigenvalue of a symmetric tensor.
double min_eigenvalue(const double m[6]);

// The intersection of two metrics: the largest ellipsoid {x : x^T M x <= 1} inside both unit
// balls, by simultaneous reduction (Cholesky of a, eigenvectors of a^-1/2 b a^-T/2). When one
// contains the other, the result is that one (up to rounding). Returns false if a or b is not SPD.
bool intersect(const double a[6], const double b[6], double out[6]);

// The metric a * s (s > 0): sizes divided by sqrt(s).
inline void scale(const double a[6], double s, double out[6]) {
  for (int i = 0; i < 6; ++i) out[i] = a[i] * s;
}

// Clamps the sizes (1 / sqrt(eigenvalue)) of m to [hmin, hmax], keeping the eigenvectors.
// Returns false if m is not SPD.
bool clamp_sizes(const double m[6], double hmin, double hmax, double out[6]);

}  // namespace metric
}  // namespace anitet

// Reference predicates for the tests: exact integer determinants (GMP), written independently of
// the library's formulas. Every input double is converted to an integer sharing a power-of-two
// scale with its column group, which multiplies each determinant by a positive power of two and
// so keeps its sign. Determinants by fraction-free Gaussian elimination (Bareiss).
#pragma once

#include <gmpxx.h>

#include <vector>

namespace anitet::predicates::testing {

// Sign of the determinant of a square integer matrix (row-major, n*n entries).
int det_sign(std::vector<mpz_class> m, int n);

// Exact integers x_i * 2^s for all given finite doubles (one common s >= lowest exponent).
std::vector<mpz_class> to_scaled_integers(const std::vector<double>& values);

// The predicates' definitions as determinants of the raw coordinates:
//   orient2d =  sign det[x y 1],  incircle = sign det[x y x^2+y^2 1],  orient3d = -sign det[x y z 1],
//   insphere = -sign det[x y z x^2+y^2+z^2 1],  orient4d = sign det[x y z h 1].
int ref_orient2d(const double* a, const double* b, const double* c);
// incircle = sign det[x y x^2+y^2 1] (2D points).
int ref_incircle(const double* a, const double* b, const double* c, const double* d);
int ref_orient3d(const double* a, const double* b, const double* c, const double* d);
int ref_insphere(const double* a, const double* b, const double* c, const double* d,
                 const double* e);
int ref_orient4d(const double* a, const double* b, const double* c, const double* d,
                 const double* e, double ha, double hb, double hc, double hd, double he);

// insphere with each lift |p_i|^2 raised by delta^k_i, delta = 2^-64 and k_i = 1 + the rank of
// ids[i] in decreasing order (the largest id gets delta^1): a concrete, tiny but finite
// perturbation that must agree with the symbolic one for small integer coordinates.
int ref_insphere_perturbed(const double* const p[5], const unsigned ids[5]);

}  // namespace anitet::predicates::testing

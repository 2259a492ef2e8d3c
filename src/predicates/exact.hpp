// Exact evaluations behind the filters (internal to the predicates module; the tests call them
// directly to check each path on its own). All return the exact sign of the same determinant as
// the public predicate of the same name.
#pragma once

namespace anitet::predicates::detail {

// Lattice stage: true (and the exact sign in result) when every difference is exact and all are
// small integers times one power of two, so that plain double arithmetic is exact.
bool orient3d_lattice(const double* a, const double* b, const double* c, const double* d,
                      int& result);
bool insphere_lattice(const double* a, const double* b, const double* c, const double* d,
                      const double* e, int& result);
bool orient4d_lattice(const double* a, const double* b, const double* c, const double* d,
                      const double* e, double ha, double hb, double hc, double hd, double he,
                      int& result);

// Double-double stage: the exact sign when it can prove it, 0 when undecided (also outside its
// magnitude range). Never wrong, so callers use it before the exact evaluations.
int orient3d_double_double(const double* a, const double* b, const double* c, const double* d);
int insphere_double_double(const double* a, const double* b, const double* c, const double* d,
                           const double* e);
int orient4d_double_double(const double* a, const double* b, const double* c, const double* d,
                           const double* e, double ha, double hb, double hc, double hd,
                           double he);

// Expansion arithmetic. Exact only when every nonzero input lies in the range its *_in_range()
// checks (no overflow, no subnormal error term); the callers check first.
int orient2d_expansion(const double* a, const double* b, const double* c);
int orient3d_expansion(const double* a, const double* b, const double* c, const double* d);
// On differences p - e: needs every difference to be exact (differences_exact()).
int insphere_expansion_diff(const double* a, const double* b, const double* c, const double* d,
                            const double* e);
// On the raw coordinates (5x5 determinant): any inputs in range.
int insphere_expansion(const double* a, const double* b, const double* c, const double* d,
                       const double* e);
int orient4d_expansion_diff(const double* a, const double* b, const double* c, const double* d,
                            const double* e, double ha, double hb, double hc, double hd,
                            double he);
int orient4d_expansion(const double* a, const double* b, const double* c, const double* d,
                       const double* e, double ha, double hb, double hc, double hd, double he);

// Whether every input lies in the range where the expansions above are exact
// (see exact_expansion.cpp).
bool orient2d_in_range(const double* a, const double* b, const double* c);
bool orient3d_in_range(const double* a, const double* b, const double* c, const double* d);
bool insphere_in_range(const double* const p[5]);
bool orient4d_in_range(const double* const p[5], const double h[5]);
// True when every p[i][k] - p[4][k] (i < 4) and h[i] - h[4] (if h) is exact in double.
bool differences_exact(const double* const p[5], const double* h);

// GMP rationals: exact for all finite inputs (the caller rejects non-finite ones).
int orient2d_gmp(const double* a, const double* b, const double* c);
int orient3d_gmp(const double* a, const double* b, const double* c, const double* d);
int insphere_gmp(const double* a, const double* b, const double* c, const double* d,
                 const double* e);
int orient4d_gmp(const double* a, const double* b, const double* c, const double* d,
                 const double* e, double ha, double hb, double hc, double hd, double he);

}  // namespace anitet::predicates::detail

// Exact geometric predicates: a floating-point filter with a proven error bound first, an exact
// fallback when the filter cannot decide. Every function returns the exact sign (-1, 0, +1) of
// its determinant for the double inputs as given.
//
// Sign conventions (chosen so that positive means "positively oriented tet" everywhere):
//   orient2d(a,b,c)     > 0  when a, b, c turn counter-clockwise.
//   incircle(a,b,c,d)   > 0  when d lies strictly inside the circle through a, b, c, given
//                            orient2d(a,b,c) > 0 (2D points: only [0] and [1] are read); 0 when
//                            cocircular. Precisely: sign det[x y x^2+y^2 1] of rows a, b, c, d.
//   orient3d(a,b,c,d)   > 0  when (b-a) x (c-a) . (d-a) > 0 (d on the side the right-hand normal
//                            of triangle abc points to). Note: the opposite sign of Shewchuk's.
//   insphere(a,b,c,d,e) > 0  when e lies strictly inside the sphere through a,b,c,d, given
//                            orient3d(a,b,c,d) > 0; 0 when cospherical.
//   orient4d(a..e, ha..he): sign of the lifted 5x5 determinant where each point is lifted to
//                            height h (insphere is orient4d with h = |p|^2, up to sign); used for
//                            weighted/regular tests and symbolic perturbation.
//                            Precisely: sign det[ax ay az ha 1; ...; ex ey ez he 1], which equals
//                            the 4D orientation det(b-a, c-a, d-a, e-a) of the lifted points, and
//                            orient4d(..., |a|^2, ..., |e|^2) == -insphere(a, b, c, d, e). For a
//                            power (regular) test lift with h = |p|^2 - weight: e is in conflict
//                            with the positive tet abcd iff orient4d < 0.
//   insphere_sos(...)         like insphere, but never 0 for five distinct points: ties are broken
//                            by Simulation of Simplicity on the given global point ids, so that
//                            the Delaunay kernel always makes a consistent choice.
//                            Precisely: the sign of insphere's determinant when each lift |p|^2 is
//                            raised by an infinitesimal eps^(rank), the point with the largest id
//                            raised by far the most (eps_max >> eps_next >> ...). The determinant
//                            is linear in the lifts, so when insphere == 0 the sign is that of the
//                            first nonzero cofactor in decreasing id order: removing point i
//                            (i = 0..4 for a..e) gives (-1)^(i+1) * orient3d(the other four, in
//                            order); e.g. e raised: -orient3d(a,b,c,d) (e moves outside).
//                            It is an alternating function of (a,...,e) like insphere, so
//                            insphere_sos(a,b,c,d,e) == insphere_sos(a,c,b,e,d) (the neighbour
//                            across abc sees the same answer). It returns 0 only when all five
//                            points are coplanar (every cofactor vanishes); when a,b,c,d alone are
//                            coplanar it still returns the sign of the perturbed determinant,
//                            which no longer means "inside". Ids must be distinct.
// Non-finite inputs (NaN, infinity) make every predicate return 0. Any finite doubles are exact.
//
// Evaluation: an inline filter with a proven semi-static error bound (filters.hpp; about 7 ns
// for orient3d, 14 ns for insphere on the shared test machine, where a bare double determinant
// takes 4 ns); when it cannot decide, out of line (predicates.cpp): a
// double-double stage with a proven bound (decides nearly all near-degenerate inputs that are
// not exactly degenerate), then exact expansion arithmetic without heap allocation, or GMP for
// coordinates beyond about 2^-150 .. 2^190 in magnitude. The "_exact" counters count the calls
// the inline filter passed on. Do not build with -ffast-math (the headers refuse it).
#pragma once

#include <cstdint>

namespace anitet::predicates {

inline int orient2d(const double* a, const double* b, const double* c);
inline int incircle(const double* a, const double* b, const double* c, const double* d);
inline int orient3d(const double* a, const double* b, const double* c, const double* d);
inline int insphere(const double* a, const double* b, const double* c, const double* d,
                    const double* e);
inline int orient4d(const double* a, const double* b, const double* c, const double* d,
                    const double* e, double ha, double hb, double hc, double hd, double he);
inline int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                        const double* e, uint32_t ia, uint32_t ib, uint32_t ic, uint32_t id,
                        uint32_t ie);

// The sign of orient3d that a plain double evaluation gets right whatever its operand order:
// +1 or -1 when the determinant computed in doubles clears four times the filter's error bound,
// 0 otherwise (the tet is flat to rounding: valid for the exact predicates, yet a solver or a
// checker computing its volume in doubles may find it zero or negative). Never exact arithmetic.
inline int orient3d_certified(const double* a, const double* b, const double* c, const double* d);

// How often each level was reached, counted per thread (no shared writes on the hot path).
struct PredicateCounters {
  uint64_t orient2d_calls = 0, orient2d_exact = 0;
  uint64_t incircle_calls = 0, incircle_exact = 0;
  uint64_t orient3d_calls = 0, orient3d_exact = 0;
  uint64_t insphere_calls = 0, insphere_exact = 0;
  uint64_t orient4d_calls = 0, orient4d_exact = 0;
  uint64_t sos_ties = 0;  // insphere_sos calls that needed the symbolic perturbation
};
// This thread's counters.
PredicateCounters& thread_counters();
void reset_thread_counters();

}  // namespace anitet::predicates

#include "predicates/filters.hpp"  // the inline definitions of the predicates above

// The exact side of the predicates: counted dispatch through cheap exact shortcuts (a shared
// coordinate, lattice-like inputs), a double-double stage (decides most near-degenerate inputs),
// then expansion arithmetic (inside its valid range) or GMP (outside); and the
// Simulation-of-Simplicity tie break of insphere_sos.
#include "predicates/predicates.hpp"

#include <cmath>

#include "predicates/exact.hpp"

namespace anitet::predicates {

PredicateCounters& thread_counters() { return detail::tls_counters; }
void reset_thread_counters() { detail::tls_counters = PredicateCounters{}; }

namespace detail {
namespace {

// Some coordinate is the same for all n points: a zero column in the difference matrix, so
// orient3d, insphere and orient4d are exactly 0 (common: axis-aligned planar faces).
bool shared_coordinate(const double* const* p, int n) {
  for (int k = 0; k < 3; ++k) {
    bool same = true;
    for (int i = 1; i < n && same; ++i) same = p[i][k] == p[0][k];
    if (same) return true;
  }
  return false;
}

bool finite(const double* const* p, int n, int dim) {
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < dim; ++k)
      if (!std::isfinite(p[i][k])) return false;
  return true;
}

}  // namespace

int orient2d_exact(const double* a, const double* b, const double* c) {
  ++tls_counters.orient2d_exact;
  const double* const p[3] = {a, b, c};
  if (!finite(p, 3, 2)) return 0;
  if (orient2d_in_range(a, b, c)) return orient2d_expansion(a, b, c);
  return orient2d_gmp(a, b, c);
}

// det[x y x^2+y^2 1] of a..d is, up to sign, insphere's 5x5 determinant of the same points at
// z = 0 and a fifth point (0, 0, 1): expanding along the z column leaves this 4x4 determinant
// (insphere = -det[x y z L 1] = -det[x y L 1]). Its exact stages then decide.
int incircle_exact(const double* a, const double* b, const double* c, const double* d) {
  ++tls_counters.incircle_exact;
  const double* const p[4] = {a, b, c, d};
  if (!finite(p, 4, 2)) return 0;
  const double a3[3] = {a[0], a[1], 0.0}, b3[3] = {b[0], b[1], 0.0}, c3[3] = {c[0], c[1], 0.0},
               d3[3] = {d[0], d[1], 0.0}, up[3] = {0.0, 0.0, 1.0};
  return -insphere_exact(a3, b3, c3, d3, up);
}

int orient3d_exact(const double* a, const double* b, const double* c, const double* d) {
  ++tls_counters.orient3d_exact;
  const double* const p[4] = {a, b, c, d};
  if (!finite(p, 4, 3) || shared_coordinate(p, 4)) return 0;
  int lattice = 0;
  if (orient3d_lattice(a, b, c, d, lattice)) return lattice;
  if (const int s = orient3d_double_double(a, b, c, d)) return s;
  if (orient3d_in_range(a, b, c, d)) return orient3d_expansion(a, b, c, d);
  return orient3d_gmp(a, b, c, d);
}

int insphere_exact(const double* a, const double* b, const double* c, const double* d,
                   const double* e) {
  ++tls_counters.insphere_exact;
  const double* const p[5] = {a, b, c, d, e};
  if (!finite(p, 5, 3) || shared_coordinate(p, 5)) return 0;
  int lattice = 0;
  if (insphere_lattice(a, b, c, d, e, lattice)) return lattice;
  if (const int s = insphere_double_double(a, b, c, d, e)) return s;
  if (!insphere_in_range(p)) return insphere_gmp(a, b, c, d, e);
  // Exact differences (grids, translated data) allow the much shorter 4x4 expansion.
  if (differences_exact(p, nullptr)) return insphere_expansion_diff(a, b, c, d, e);
  return insphere_expansion(a, b, c, d, e);
}

int orient4d_exact(const double* a, const double* b, const double* c, const double* d,
                   const double* e, double ha, double hb, double hc, double hd, double he) {
  ++tls_counters.orient4d_exact;
  const double* const p[5] = {a, b, c, d, e};
  const double h[5] = {ha, hb, hc, hd, he};
  const double* const hp[1] = {h};
  if (!finite(p, 5, 3) || !finite(hp, 1, 5) || shared_coordinate(p, 5)) return 0;
  if (ha == he && hb == he && hc == he && hd == he) return 0;  // a zero height column
  int lattice = 0;
  if (orient4d_lattice(a, b, c, d, e, ha, hb, hc, hd, he, lattice)) return lattice;
  if (const int s = orient4d_double_double(a, b, c, d, e, ha, hb, hc, hd, he)) return s;
  if (!orient4d_in_range(p, h)) return orient4d_gmp(a, b, c, d, e, ha, hb, hc, hd, he);
  if (differences_exact(p, h)) return orient4d_expansion_diff(a, b, c, d, e, ha, hb, hc, hd, he);
  return orient4d_expansion(a, b, c, d, e, ha, hb, hc, hd, he);
}

// insphere is exactly 0. Perturb the lifts: point i's lift grows by eps_i, where the point with
// the largest id gets the dominant eps. The determinant is linear in the lift column, so its sign
// is that of the first nonzero cofactor in decreasing id order. Removing row i (0..4) of
// -det[x y z L 1] leaves -(-1)^(i+3) det[x y z 1](others) = (-1)^(i+1) orient3d(others), because
// det[x y z 1](p,q,r,s) = -orient3d(p,q,r,s).
int insphere_sos_tie(const double* a, const double* b, const double* c, const double* d,
                     const double* e, uint32_t ia, uint32_t ib, uint32_t ic, uint32_t id,
                     uint32_t ie) {
  ++tls_counters.sos_ties;
  const double* const p[5] = {a, b, c, d, e};
  const uint32_t ids[5] = {ia, ib, ic, id, ie};
  int order[5] = {0, 1, 2, 3, 4};
  for (int i = 1; i < 5; ++i)  // insertion sort by decreasing id
    for (int j = i; j > 0 && ids[order[j]] > ids[order[j - 1]]; --j) {
      const int t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  for (const int i : order) {
    const double* q[4];
    int n = 0;
    for (int j = 0; j < 5; ++j)
      if (j != i) q[n++] = p[j];
    const int s = orient3d(q[0], q[1], q[2], q[3]);
    if (s != 0) return (i % 2 == 0) ? -s : s;
  }
  return 0;  // all five points coplanar
}

}  // namespace detail
}  // namespace anitet::predicates

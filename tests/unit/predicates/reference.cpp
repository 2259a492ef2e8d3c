#include "reference.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

namespace anitet::predicates::testing {
namespace {

// Reused GMP integers: after warm-up the reference allocates nothing per call.
struct Workspace {
  static constexpr int kMax = 32;
  mpz_t m[kMax], prev, t, u;
  Workspace() {
    for (auto& x : m) mpz_init(x);
    mpz_init(prev);
    mpz_init(t);
    mpz_init(u);
  }
  ~Workspace() {
    for (auto& x : m) mpz_clear(x);
    mpz_clear(prev);
    mpz_clear(t);
    mpz_clear(u);
  }
  Workspace(const Workspace&) = delete;
  Workspace& operator=(const Workspace&) = delete;
};

Workspace& workspace() {
  thread_local Workspace w;
  return w;
}

// Bareiss elimination in place on the n*n matrix w.m (row-major).
int bareiss_sign(Workspace& w, int n) {
  mpz_t* m = w.m;
  int sign = 1;
  mpz_set_ui(w.prev, 1);
  for (int k = 0; k < n - 1; ++k) {
    if (mpz_sgn(m[k * n + k]) == 0) {
      int r = k + 1;
      while (r < n && mpz_sgn(m[r * n + k]) == 0) ++r;
      if (r == n) return 0;
      for (int j = 0; j < n; ++j) mpz_swap(m[k * n + j], m[r * n + j]);
      sign = -sign;
    }
    for (int i = k + 1; i < n; ++i) {
      for (int j = k + 1; j < n; ++j) {
        mpz_mul(w.t, m[i * n + j], m[k * n + k]);
        mpz_mul(w.u, m[i * n + k], m[k * n + j]);
        mpz_sub(w.t, w.t, w.u);
        mpz_divexact(m[i * n + j], w.t, w.prev);
      }
      mpz_set_ui(m[i * n + k], 0);
    }
    mpz_set(w.prev, m[k * n + k]);
  }
  return sign * mpz_sgn(m[(n - 1) * n + (n - 1)]);
}

// v = mant * 2^expo with an integer mantissa; the lowest exponent among nonzero values.
int lowest_exponent(const double* v, int n) {
  int lowest = INT_MAX;
  for (int i = 0; i < n; ++i) {
    if (v[i] == 0) continue;
    int e = 0;
    std::frexp(v[i], &e);
    lowest = std::min(lowest, e - 53);
  }
  return lowest;
}

// out = v * 2^-lowest, exactly.
void set_scaled(mpz_t out, double v, int lowest) {
  if (v == 0) {
    mpz_set_ui(out, 0);
    return;
  }
  int e = 0;
  const double f = std::frexp(v, &e);
  mpz_set_d(out, std::ldexp(f, 53));
  mpz_mul_2exp(out, out, static_cast<mp_bitcnt_t>(e - 53 - lowest));
}

// Fill the rows [coordinates..., extra..., 1] of an n-column matrix: dim scaled coordinates per
// point (one shared scale), then the caller fills the remaining columns.
void fill_coordinates(Workspace& w, const double* const* p, int npts, int dim, int ncols) {
  double v[5 * 3];
  for (int i = 0; i < npts; ++i)
    for (int k = 0; k < dim; ++k) v[i * dim + k] = p[i][k];
  const int lowest = lowest_exponent(v, npts * dim);
  for (int i = 0; i < npts; ++i) {
    for (int k = 0; k < dim; ++k) set_scaled(w.m[i * ncols + k], v[i * dim + k], lowest);
    mpz_set_ui(w.m[i * ncols + ncols - 1], 1);
  }
}

// Column `col` = x^2 + y^2 + z^2 of the already scaled coordinates.
void fill_lift(Workspace& w, int npts, int ncols, int col) {
  for (int i = 0; i < npts; ++i) {
    mpz_t& l = w.m[i * ncols + col];
    mpz_mul(l, w.m[i * ncols], w.m[i * ncols]);
    for (int k = 1; k < 3; ++k) {
      mpz_mul(w.t, w.m[i * ncols + k], w.m[i * ncols + k]);
      mpz_add(l, l, w.t);
    }
  }
}

}  // namespace

int det_sign(std::vector<mpz_class> m, int n) {
  Workspace& w = workspace();
  for (int i = 0; i < n * n; ++i) mpz_set(w.m[i], m[size_t(i)].get_mpz_t());
  return bareiss_sign(w, n);
}

std::vector<mpz_class> to_scaled_integers(const std::vector<double>& values) {
  const int lowest = lowest_exponent(values.data(), int(values.size()));
  std::vector<mpz_class> out(values.size());
  for (size_t i = 0; i < values.size(); ++i) set_scaled(out[i].get_mpz_t(), values[i], lowest);
  return out;
}

int ref_orient2d(const double* a, const double* b, const double* c) {
  Workspace& w = workspace();
  const double* p[3] = {a, b, c};
  fill_coordinates(w, p, 3, 2, 3);
  return bareiss_sign(w, 3);
}

int ref_incircle(const double* a, const double* b, const double* c, const double* d) {
  Workspace& w = workspace();
  const double* p[4] = {a, b, c, d};
  fill_coordinates(w, p, 4, 2, 4);
  for (int i = 0; i < 4; ++i) {
    mpz_t& l = w.m[i * 4 + 2];
    mpz_mul(l, w.m[i * 4], w.m[i * 4]);
    mpz_mul(w.t, w.m[i * 4 + 1], w.m[i * 4 + 1]);
    mpz_add(l, l, w.t);
  }
  return bareiss_sign(w, 4);
}

int ref_orient3d(const double* a, const double* b, const double* c, const double* d) {
  Workspace& w = workspace();
  const double* p[4] = {a, b, c, d};
  fill_coordinates(w, p, 4, 3, 4);
  return -bareiss_sign(w, 4);
}

int ref_insphere(const double* a, const double* b, const double* c, const double* d,
                 const double* e) {
  Workspace& w = workspace();
  const double* p[5] = {a, b, c, d, e};
  fill_coordinates(w, p, 5, 3, 5);
  fill_lift(w, 5, 5, 3);
  return -bareiss_sign(w, 5);
}

int ref_orient4d(const double* a, const double* b, const double* c, const double* d,
                 const double* e, double ha, double hb, double hc, double hd, double he) {
  Workspace& w = workspace();
  const double* p[5] = {a, b, c, d, e};
  fill_coordinates(w, p, 5, 3, 5);
  const double h[5] = {ha, hb, hc, hd, he};
  const int lowest = lowest_exponent(h, 5);  // the height column has its own scale
  for (int i = 0; i < 5; ++i) set_scaled(w.m[i * 5 + 3], h[i], lowest);
  return bareiss_sign(w, 5);
}

int ref_insphere_perturbed(const double* const p[5], const unsigned ids[5]) {
  Workspace& w = workspace();
  fill_coordinates(w, p, 5, 3, 5);
  fill_lift(w, 5, 5, 3);
  // Lift column times 2^320 plus 2^(320 - 64 k): the integer form of |p|^2 + (2^-64)^k
  // (scaling one whole column by 2^320 keeps the sign).
  for (int i = 0; i < 5; ++i) {
    int k = 1;
    for (int j = 0; j < 5; ++j)
      if (ids[j] > ids[i]) ++k;
    mpz_t& l = w.m[i * 5 + 3];
    mpz_mul_2exp(l, l, 320);
    mpz_set_ui(w.t, 1);
    mpz_mul_2exp(w.t, w.t, static_cast<mp_bitcnt_t>(320 - 64 * k));
    mpz_add(l, l, w.t);
  }
  return -bareiss_sign(w, 5);
}

}  // namespace anitet::predicates::testing

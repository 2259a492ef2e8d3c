// Exact predicates in GMP rationals: the fallback for finite inputs outside the ranges where
// expansion arithmetic is exact (tiny or huge magnitudes). A double converts to mpq exactly.
// Slow (heap allocations), but only reached by extreme inputs.
#include <gmpxx.h>

#include "predicates/exact.hpp"

namespace anitet::predicates::detail {
namespace {

int sign_of(const mpq_class& q) { return sgn(q); }

struct Row3 {
  mpq_class x, y, z;
};

Row3 diff3(const double* p, const double* o) {
  return Row3{mpq_class(p[0]) - mpq_class(o[0]), mpq_class(p[1]) - mpq_class(o[1]),
              mpq_class(p[2]) - mpq_class(o[2])};
}

// det of the 3x3 matrix with rows u, v, w.
mpq_class det3(const Row3& u, const Row3& v, const Row3& w) {
  return u.x * (v.y * w.z - v.z * w.y) - u.y * (v.x * w.z - v.z * w.x) +
         u.z * (v.x * w.y - v.y * w.x);
}

// The 4x4 determinant with rows (r_i, f_i), expanded along the last column:
// sum_i (-1)^(i+1) f_i * det3(rows but i).
mpq_class det4_last_column(const Row3 r[4], const mpq_class f[4]) {
  return -f[0] * det3(r[1], r[2], r[3]) + f[1] * det3(r[0], r[2], r[3]) -
         f[2] * det3(r[0], r[1], r[3]) + f[3] * det3(r[0], r[1], r[2]);
}

}  // namespace

int orient2d_gmp(const double* a, const double* b, const double* c) {
  const mpq_class ux = mpq_class(b[0]) - mpq_class(a[0]), uy = mpq_class(b[1]) - mpq_class(a[1]);
  const mpq_class vx = mpq_class(c[0]) - mpq_class(a[0]), vy = mpq_class(c[1]) - mpq_class(a[1]);
  return sign_of(ux * vy - uy * vx);
}

int orient3d_gmp(const double* a, const double* b, const double* c, const double* d) {
  return sign_of(det3(diff3(b, a), diff3(c, a), diff3(d, a)));
}

int insphere_gmp(const double* a, const double* b, const double* c, const double* d,
                 const double* e) {
  const Row3 r[4] = {diff3(a, e), diff3(b, e), diff3(c, e), diff3(d, e)};
  mpq_class lift[4];
  for (int i = 0; i < 4; ++i) lift[i] = r[i].x * r[i].x + r[i].y * r[i].y + r[i].z * r[i].z;
  // insphere = -det[p-e, |p-e|^2].
  return -sign_of(det4_last_column(r, lift));
}

int orient4d_gmp(const double* a, const double* b, const double* c, const double* d,
                 const double* e, double ha, double hb, double hc, double hd, double he) {
  const Row3 r[4] = {diff3(a, e), diff3(b, e), diff3(c, e), diff3(d, e)};
  const mpq_class h[4] = {mpq_class(ha) - mpq_class(he), mpq_class(hb) - mpq_class(he),
                          mpq_class(hc) - mpq_class(he), mpq_class(hd) - mpq_class(he)};
  return sign_of(det4_last_column(r, h));
}

}  // namespace anitet::predicates::detail

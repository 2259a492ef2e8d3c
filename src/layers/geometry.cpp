#include "layers/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace anitet::layers {

namespace {

double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

void cross(const double* a, const double* b, double* c) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

double normalize(double* v) {
  const double len = std::sqrt(dot(v, v));
  if (len > 0.0)
    for (int k = 0; k < 3; ++k) v[k] /= len;
  return len;
}

double min_dot(const std::vector<double>& normals, const double d[3], size_t* worst) {
  double best = 2.0;
  for (size_t i = 0; 3 * i < normals.size(); ++i) {
    const double s = dot(&normals[3 * i], d);
    if (s < best) {
      best = s;
      *worst = i;
    }
  }
  return best;
}

}  // namespace

double unit_normal(const double* a, const double* b, const double* c, double n[3]) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  cross(ab, ac, n);
  return normalize(n);
}

double corner_angle(const double* a, const double* b, const double* c) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double x[3];
  cross(ab, ac, x);
  return std::atan2(std::sqrt(dot(x, x)), dot(ab, ac));
}

double star_margin(const std::vector<double>& normals, const double d[3]) {
  size_t worst = 0;
  return min_dot(normals, d, &worst);
}

namespace {

// The direction maximizing min_i d . n_i over the unit sphere. At the optimum the active normals
// are equidistant from d, and three of them (or fewer) fix it: d = n_i, the bisector of n_i and
// n_j, or the axis (n_j - n_i) x (n_k - n_i). Trying every candidate is exact and cheap for the
// small stars that need it (n <= kMaxExact).
double max_min_direction(const std::vector<double>& normals, double best[3]) {
  const size_t n = normals.size() / 3;
  double best_margin = -2.0;
  // Candidates are checked against the normal that stopped the last one first, and dropped as
  // soon as they cannot beat the best: most fail at once, so this costs about O(n^3).
  size_t last_worst = 0;
  auto consider = [&](double* c) {
    if (normalize(c) == 0.0) return;
    if (dot(&normals[3 * last_worst], c) <= best_margin) return;
    double m = 2.0;
    for (size_t i = 0; i < n; ++i) {
      const double s = dot(&normals[3 * i], c);
      if (s < m) {
        m = s;
        if (m <= best_margin) {
          last_worst = i;
          return;
        }
      }
    }
    best_margin = m;
    std::copy_n(c, 3, best);
  };
  for (size_t i = 0; i < n; ++i) {
    const double* a = &normals[3 * i];
    double c[3] = {a[0], a[1], a[2]};
    consider(c);
    for (size_t j = i + 1; j < n; ++j) {
      const double* b = &normals[3 * j];
      double h[3] = {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
      consider(h);
      const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      for (size_t k = j + 1; k < n; ++k) {
        const double* e = &normals[3 * k];
        const double ae[3] = {e[0] - a[0], e[1] - a[1], e[2] - a[2]};
        double x[3];
        cross(ab, ae, x);
        double y[3] = {-x[0], -x[1], -x[2]};
        consider(x);
        consider(y);
      }
    }
  }
  return best_margin;
}

}  // namespace

double visible_direction(const std::vector<double>& normals, const std::vector<double>& weights,
                         double d[3], bool* improved) {
  *improved = false;
  d[0] = d[1] = d[2] = 0.0;
  for (size_t i = 0; i < weights.size(); ++i)
    for (int k = 0; k < 3; ++k) d[k] += weights[i] * normals[3 * i + k];
  if (normalize(d) == 0.0) d[2] = 1.0;
  size_t worst = 0;
  const double margin = min_dot(normals, d, &worst);
  // The mean normal is the natural push direction; keep it unless some triangle is nearly edge-on.
  constexpr double kGoodMargin = 0.2;
  if (margin >= kGoodMargin) return margin;

  double best[3] = {d[0], d[1], d[2]};
  double best_margin = margin;
  constexpr size_t kMaxExact = 24;
  if (normals.size() / 3 <= kMaxExact) {
    best_margin = max_min_direction(normals, best);
  } else {
    // Large star: max-min ascent, stepping towards the worst normal with a shrinking step.
    double cur[3] = {d[0], d[1], d[2]};
    double step = 0.5;
    for (int it = 0; it < 400; ++it) {
      const double* n = &normals[3 * worst];
      for (int k = 0; k < 3; ++k) cur[k] += step * n[k];
      normalize(cur);
      const double m = min_dot(normals, cur, &worst);
      if (m > best_margin) {
        best_margin = m;
        std::copy_n(cur, 3, best);
      }
      step *= 0.985;
    }
  }
  if (best_margin > margin) {
    std::copy_n(best, 3, d);
    *improved = true;
    return best_margin;
  }
  return margin;
}

double ray_triangle(const double o[3], const double d[3], const double* a, const double* b,
                    const double* c) {
  const double inf = std::numeric_limits<double>::infinity();
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double p[3];
  cross(d, e2, p);
  const double det = dot(e1, p);
  if (det == 0.0) return inf;
  const double s[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
  const double u = dot(s, p) / det;
  if (u < 0.0 || u > 1.0) return inf;
  double q[3];
  cross(s, e1, q);
  const double v = dot(d, q) / det;
  if (v < 0.0 || u + v > 1.0) return inf;
  const double t = dot(e2, q) / det;
  return t > 0.0 ? t : inf;
}

void metric_factor(const double m[6], double u[9]) {
  // M = U^T U with U upper triangular (Cholesky of the full symmetric matrix).
  const double a00 = m[0], a01 = m[1], a11 = m[2], a02 = m[3], a12 = m[4], a22 = m[5];
  std::fill_n(u, 9, 0.0);
  const double u00 = a00 > 0.0 ? std::sqrt(a00) : 0.0;
  if (!(u00 > 0.0)) {
    u[0] = u[4] = u[8] = 1.0;
    return;
  }
  const double u01 = a01 / u00, u02 = a02 / u00;
  const double s11 = a11 - u01 * u01;
  if (!(s11 > 0.0)) {
    std::fill_n(u, 9, 0.0);
    u[0] = u[4] = u[8] = 1.0;
    return;
  }
  const double u11 = std::sqrt(s11);
  const double u12 = (a12 - u01 * u02) / u11;
  const double s22 = a22 - u02 * u02 - u12 * u12;
  if (!(s22 > 0.0)) {
    u[0] = u[4] = u[8] = 1.0;
    u[1] = u[2] = u[5] = 0.0;
    return;
  }
  u[0] = u00;
  u[1] = u01;
  u[2] = u02;
  u[4] = u11;
  u[5] = u12;
  u[8] = std::sqrt(s22);
}

void apply_factor(const double u[9], const double x[3], double y[3]) {
  for (int r = 0; r < 3; ++r) y[r] = u[3 * r] * x[0] + u[3 * r + 1] * x[1] + u[3 * r + 2] * x[2];
}

void solve_factor(const double u[9], const double x[3], double y[3]) {
  y[2] = x[2] / u[8];
  y[1] = (x[1] - u[5] * y[2]) / u[4];
  y[0] = (x[0] - u[1] * y[1] - u[2] * y[2]) / u[0];
}

double radius_ratio(const double* a, const double* b, const double* c, const double* d) {
  // Five square roots: the four face areas and the circumcentre's offset from a,
  // a + (|ab|^2 (ac x ad) + |ac|^2 (ad x ab) + |ad|^2 (ab x ac)) / (2 v6).
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  const double bc[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double bd[3] = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
  double n_cd[3], n_db[3], n_bc[3], n_a[3];
  cross(ac, ad, n_cd);
  cross(ad, ab, n_db);
  cross(ab, ac, n_bc);
  cross(bc, bd, n_a);
  const double v6 = std::fabs(dot(ab, n_cd));
  if (!(v6 > 0.0)) return 0.0;
  const double area2 = std::sqrt(dot(n_cd, n_cd)) + std::sqrt(dot(n_db, n_db)) + std::sqrt(dot(n_bc, n_bc)) +
                       std::sqrt(dot(n_a, n_a));  // twice the total area
  const double r_in = v6 / area2;                     // 3 V / A
  const double lab = dot(ab, ab), lac = dot(ac, ac), lad = dot(ad, ad);
  double o[3];
  for (int k = 0; k < 3; ++k) o[k] = lab * n_cd[k] + lac * n_db[k] + lad * n_bc[k];
  const double big_r = std::sqrt(dot(o, o)) / (2.0 * v6);
  return big_r > 0.0 ? std::min(1.0, 3.0 * r_in / big_r) : 0.0;
}

double radius_ratio_in(const double u[9], const double* a, const double* b, const double* c,
                       const double* d) {
  double q[4][3];
  apply_factor(u, a, q[0]);
  apply_factor(u, b, q[1]);
  apply_factor(u, c, q[2]);
  apply_factor(u, d, q[3]);
  return radius_ratio(q[0], q[1], q[2], q[3]);
}

}  // namespace anitet::layers

#include "adapt/surface_geometry.hpp"

namespace anitet::adapt::geom {

void pn_triangle(const double* const p[3], const double* const n_in[3], const double bary[3], double out[3],
                 double normal[3]) {
  double n[3][3];
  for (int i = 0; i < 3; ++i) {
    const double s = i > 0 && dot(n_in[i], n_in[0]) < 0 ? -1.0 : 1.0;
    for (int k = 0; k < 3; ++k) n[i][k] = s * n_in[i][k];
  }
  // Edge control points: c[i][j] is the one of edge ij next to vertex i.
  double c[3][3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j) edge_control(p[i], n[i], p[j], c[i][j]);
  double e[3] = {0, 0, 0}, v[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 3; ++i) {
      v[k] += p[i][k] / 3.0;
      for (int j = 0; j < 3; ++j)
        if (i != j) e[k] += c[i][j][k] / 6.0;
    }
  }
  double center[3];
  for (int k = 0; k < 3; ++k) center[k] = e[k] + (e[k] - v[k]) / 2.0;
  const double u = bary[0], w1 = bary[1], w2 = bary[2];
  const double b[3] = {u, w1, w2};
  for (int k = 0; k < 3; ++k) {
    double x = 0.0;
    for (int i = 0; i < 3; ++i) x += b[i] * b[i] * b[i] * p[i][k];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (i != j) x += 3.0 * b[i] * b[i] * b[j] * c[i][j][k];
    x += 6.0 * u * w1 * w2 * center[k];
    out[k] = x;
  }
  // Quadratic normals: the vertices' and one per edge (the mean of the ends' reflected in the
  // plane normal to the edge).
  double mid[3][3];  // mid[k]: edge (k, k+1)
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    double d[3], sum[3];
    sub(p[j], p[i], d);
    for (int k = 0; k < 3; ++k) sum[k] = n[i][k] + n[j][k];
    const double l2 = dot(d, d);
    const double f = l2 > 0 ? 2.0 * dot(d, sum) / l2 : 0.0;
    for (int k = 0; k < 3; ++k) mid[i][k] = sum[k] - f * d[k];
    if (!normalize(mid[i])) mid[i][0] = sum[0], mid[i][1] = sum[1], mid[i][2] = sum[2];
  }
  for (int k = 0; k < 3; ++k)
    normal[k] = u * u * n[0][k] + w1 * w1 * n[1][k] + w2 * w2 * n[2][k] + 2 * u * w1 * mid[0][k] +
                2 * w1 * w2 * mid[1][k] + 2 * w2 * u * mid[2][k];
  if (!normalize(normal)) normal[0] = n[0][0], normal[1] = n[0][1], normal[2] = n[0][2];
}

}  // namespace anitet::adapt::geom

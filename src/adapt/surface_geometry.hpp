// The smooth surface adaptation places its points on: curved PN triangles (Vlachos, Peters,
// Boyd, Mitchell, "Curved PN triangles", I3D 2001) through the surface points and their normals.
// An edge of the surface is the cubic Bezier curve through its ends, tangent there to the surface
// (its inner control points: the one-third points of the chord projected on the tangent planes at
// the ends), so two triangles sharing an edge agree on it; a ridge is the cubic Hermite curve
// through its points with the ridge's tangents there. Normals along an edge or inside a triangle
// are the PN triangles' quadratic normals. On a sphere of radius R with edges of length h, the
// points are within about 1e-3 R (h/R)^4 of the sphere.
#pragma once

#include <cmath>

namespace anitet::adapt::geom {

inline double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline void cross(const double a[3], const double b[3], double out[3]) {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}
inline void sub(const double a[3], const double b[3], double out[3]) {
  out[0] = a[0] - b[0], out[1] = a[1] - b[1], out[2] = a[2] - b[2];
}
inline double norm(const double a[3]) { return std::sqrt(dot(a, a)); }
// Normalizes a in place; false (a unchanged) when it is zero or not finite.
inline bool normalize(double a[3]) {
  const double n = norm(a);
  if (!(n > 0.0) || !std::isfinite(n)) return false;
  a[0] /= n, a[1] /= n, a[2] /= n;
  return true;
}

// Unit normal of triangle abc by the right-hand rule (zero when flat); returns twice its area.
inline double triangle_normal(const double a[3], const double b[3], const double c[3], double n[3]) {
  double ab[3], ac[3];
  sub(b, a, ab);
  sub(c, a, ac);
  cross(ab, ac, n);
  const double len = norm(n);
  if (len > 0.0) n[0] /= len, n[1] /= len, n[2] /= len;
  return len;
}

// The inner control point of a surface edge at a (normal na) towards b.
inline void edge_control(const double a[3], const double na[3], const double b[3], double out[3]) {
  double ab[3];
  sub(b, a, ab);
  const double w = dot(ab, na);
  for (int k = 0; k < 3; ++k) out[k] = a[k] + (ab[k] - w * na[k]) / 3.0;
}

inline void bezier(const double p0[3], const double p1[3], const double p2[3], const double p3[3], double t,
                   double out[3]) {
  const double s = 1.0 - t;
  const double c0 = s * s * s, c1 = 3 * s * s * t, c2 = 3 * s * t * t, c3 = t * t * t;
  for (int k = 0; k < 3; ++k) out[k] = c0 * p0[k] + c1 * p1[k] + c2 * p2[k] + c3 * p3[k];
}

// The point at parameter t of the surface edge ab (normals na, nb, of either sign).
inline void surface_edge_point(const double a[3], const double na[3], const double b[3], const double nb[3],
                               double t, double out[3]) {
  double c1[3], c2[3];
  edge_control(a, na, b, c1);
  edge_control(b, nb, a, c2);
  bezier(a, c1, c2, b, t, out);
}

// The PN quadratic normal at parameter t of edge ab (nb's sign first made to agree with na's).
inline void surface_edge_normal(const double a[3], const double na[3], const double b[3], const double nb_in[3],
                                double t, double out[3]) {
  double nb[3] = {nb_in[0], nb_in[1], nb_in[2]};
  if (dot(na, nb) < 0) nb[0] = -nb[0], nb[1] = -nb[1], nb[2] = -nb[2];
  double ab[3];
  sub(b, a, ab);
  const double l2 = dot(ab, ab);
  double sum[3] = {na[0] + nb[0], na[1] + nb[1], na[2] + nb[2]};
  const double v = l2 > 0 ? 2.0 * dot(ab, sum) / l2 : 0.0;
  double mid[3] = {sum[0] - v * ab[0], sum[1] - v * ab[1], sum[2] - v * ab[2]};
  if (!normalize(mid)) mid[0] = sum[0], mid[1] = sum[1], mid[2] = sum[2];
  const double s = 1.0 - t;
  for (int k = 0; k < 3; ++k) out[k] = s * s * na[k] + 2 * s * t * mid[k] + t * t * nb[k];
  if (!normalize(out)) out[0] = na[0], out[1] = na[1], out[2] = na[2];
}

// The ridge curve ab (unit tangents ta, tb of either sign) at t, and its unit tangent there
// (oriented from a to b).
inline void ridge_point(const double a[3], const double ta_in[3], const double b[3], const double tb_in[3], double t,
                        double out[3], double tangent[3]) {
  double ab[3];
  sub(b, a, ab);
  const double len = norm(ab);
  const double sa = dot(ta_in, ab) < 0 ? -1.0 : 1.0, sb = dot(tb_in, ab) < 0 ? -1.0 : 1.0;
  double c1[3], c2[3];
  for (int k = 0; k < 3; ++k) {
    c1[k] = a[k] + sa * ta_in[k] * len / 3.0;
    c2[k] = b[k] - sb * tb_in[k] * len / 3.0;
  }
  bezier(a, c1, c2, b, t, out);
  const double s = 1.0 - t;
  for (int k = 0; k < 3; ++k)
    tangent[k] = 3 * s * s * (c1[k] - a[k]) + 6 * s * t * (c2[k] - c1[k]) + 3 * t * t * (b[k] - c2[k]);
  if (!normalize(tangent)) tangent[0] = ab[0] / len, tangent[1] = ab[1] / len, tangent[2] = ab[2] / len;
}

// The PN triangle through p[0..2] with normals n[0..2] (signs made to agree with n[0]'s) at
// barycentric (u, v, w): its point and its quadratic normal.
void pn_triangle(const double* const p[3], const double* const n[3], const double bary[3], double out[3],
                 double normal[3]);

}  // namespace anitet::adapt::geom

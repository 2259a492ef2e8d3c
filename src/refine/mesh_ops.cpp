#include "refine/mesh_ops.hpp"

#include <algorithm>
#include <cmath>

#include "predicates/predicates.hpp"

namespace anitet::meshops {

namespace {

inline void sub(const double* p, const double* q, double* r) {
  r[0] = p[0] - q[0];
  r[1] = p[1] - q[1];
  r[2] = p[2] - q[2];
}
inline void cross(const double* u, const double* v, double* r) {
  r[0] = u[1] * v[2] - u[2] * v[1];
  r[1] = u[2] * v[0] - u[0] * v[2];
  r[2] = u[0] * v[1] - u[1] * v[0];
}
inline double dot(const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
inline double norm(const double* u) { return std::sqrt(dot(u, u)); }

}  // namespace

double radius_ratio(const double* a, const double* b, const double* c, const double* d) {
  double ab[3], ac[3], ad[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(d, a, ad);
  double cd[3], db[3], bc[3];
  cross(ac, ad, cd);
  cross(ad, ab, db);
  cross(ab, ac, bc);
  const double v6 = dot(ab, cd);
  if (v6 == 0.0) return 0.0;
  // Face areas x 2: the three at a from the cross products, the fourth from (c-b) x (d-b).
  double bcv[3], bdv[3], f[3];
  sub(c, b, bcv);
  sub(d, b, bdv);
  cross(bcv, bdv, f);
  const double area2 = norm(cd) + norm(db) + norm(bc) + norm(f);
  // Circumcentre relative to a: (|ab|^2 (ac x ad) + |ac|^2 (ad x ab) + |ad|^2 (ab x ac)) / (2 V6).
  const double lab = dot(ab, ab), lac = dot(ac, ac), lad = dot(ad, ad);
  double o[3];
  for (int k = 0; k < 3; ++k) o[k] = lab * cd[k] + lac * db[k] + lad * bc[k];
  const double r_circ = norm(o) / (2.0 * std::fabs(v6));
  // Inradius = 3V / area = (v6 / 2) / (area2 / 2) = v6 / area2.
  const double r_in = v6 / area2;
  return r_circ > 0.0 ? 3.0 * r_in / r_circ : 0.0;
}

double tet_radius_ratio(const TetMesh& mesh, uint32_t t) {
  return radius_ratio(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                      mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3)));
}

double shape_quality(const double* a, const double* b, const double* c, const double* d) {
  double ab[3], ac[3], ad[3], bc[3], bd[3], cd[3];
  sub(b, a, ab);
  sub(c, a, ac);
  sub(d, a, ad);
  sub(c, b, bc);
  sub(d, b, bd);
  sub(d, c, cd);
  // Face normals (x2 area) opposite each vertex.
  double na[3], nb[3], nc[3], nd[3];
  cross(bc, bd, na);
  cross(ac, ad, nb);
  cross(ad, ab, nc);
  cross(ab, ac, nd);
  const double v6 = dot(ab, nb);
  if (v6 == 0.0) return 0.0;
  const double la = norm(na), lb = norm(nb), lc = norm(nc), ld = norm(nd);
  // sin(dihedral at edge ij) = v6 |ij| / (|N_k| |N_l|), k and l the other two vertices.
  const double s = std::min({norm(ab) / (lc * ld), norm(ac) / (lb * ld), norm(ad) / (lb * lc),
                             norm(bc) / (la * ld), norm(bd) / (la * lc), norm(cd) / (la * lb)});
  const double sin_term = v6 * s / 0.9428090415820634;  // sin(acos(1/3)) = sqrt(8/9)
  // Radius ratio from the same pieces.
  const double lab = dot(ab, ab), lac = dot(ac, ac), lad = dot(ad, ad);
  double o[3];
  for (int k = 0; k < 3; ++k) o[k] = lab * nb[k] + lac * nc[k] + lad * nd[k];
  const double r_circ = norm(o) / (2.0 * std::fabs(v6));
  const double rr = r_circ > 0.0 ? 3.0 * (v6 / (la + lb + lc + ld)) / r_circ : 0.0;
  return std::min(rr, sin_term);
}

double tet_shape_quality(const TetMesh& mesh, uint32_t t) {
  return shape_quality(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                       mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3)));
}

double min_quality(const TetMesh& mesh, const std::vector<uint32_t>& tets) {
  double q = 1.0;
  for (uint32_t t : tets) q = std::min(q, tet_shape_quality(mesh, t));
  return q;
}

}  // namespace anitet::meshops

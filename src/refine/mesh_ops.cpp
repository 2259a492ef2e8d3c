#include "refine/mesh_ops.hpp"

#include <algorithm>
#include <cmath>

#include "core/sizing.hpp"
#include "metric/spd.hpp"
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
  const double qa = dot(na, na), qb = dot(nb, nb), qc = dot(nc, nc), qd = dot(nd, nd);
  const double lab = dot(ab, ab), lac = dot(ac, ac), lad = dot(ad, ad);
  // sin(dihedral at edge ij) = v6 |ij| / (|N_k| |N_l|), k and l the other two vertices; the
  // smallest is found on squares (one square root instead of six: this is the optimizer's and
  // refinement's hottest function).
  const double s2 = std::min({lab / (qc * qd), lac / (qb * qd), lad / (qb * qc), dot(bc, bc) / (qa * qd),
                              dot(bd, bd) / (qa * qc), dot(cd, cd) / (qa * qb)});
  const double sin_term = v6 * std::sqrt(s2) / 0.9428090415820634;  // sin(acos(1/3)) = sqrt(8/9)
  // Radius ratio from the same pieces.
  const double la = std::sqrt(qa), lb = std::sqrt(qb), lc = std::sqrt(qc), ld = std::sqrt(qd);
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

MetricMap MetricMap::of(const double m[6]) {
  MetricMap map;
  if (metric_is_isotropic(m)) return map;
  // A non positive pivot (M not SPD) keeps the identity.
  map.identity = !metric::cholesky(m, map.l);
  return map;
}

void MetricMap::apply(const double* x, double* y) const {
  // y = L^T x.
  y[0] = l[0] * x[0] + l[1] * x[1] + l[3] * x[2];
  y[1] = l[2] * x[1] + l[4] * x[2];
  y[2] = l[5] * x[2];
}

void MetricMap::unapply(const double* y, double* x) const {
  x[2] = y[2] / l[5];
  x[1] = (y[1] - l[4] * x[2]) / l[2];
  x[0] = (y[0] - l[1] * x[1] - l[3] * x[2]) / l[0];
}

double metric_shape_quality(const MetricMap& map, const double* a, const double* b, const double* c,
                            const double* d) {
  if (map.identity) return shape_quality(a, b, c, d);
  double q[4][3];
  map.apply(a, q[0]);
  map.apply(b, q[1]);
  map.apply(c, q[2]);
  map.apply(d, q[3]);
  return shape_quality(q[0], q[1], q[2], q[3]);
}

double min_quality(const TetMesh& mesh, const std::vector<uint32_t>& tets, const MetricMap& map) {
  double q = 1.0;
  for (uint32_t t : tets)
    q = std::min(q, metric_shape_quality(map, mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                                         mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3))));
  return q;
}

bool collapse_replacement(const TetMesh& mesh, uint32_t v, uint32_t w, const std::vector<uint32_t>* ball_w,
                          std::vector<uint32_t>& old, std::vector<TetVerts>& fresh) {
  bool adjacent = false;
  for (uint32_t t : old) adjacent |= tet_has_vertex(mesh, t, w);
  if (!adjacent) return false;
  if (ball_w)
    for (uint32_t t : *ball_w)
      if (!tet_has_vertex(mesh, t, v)) old.push_back(t);
  fresh.clear();
  for (uint32_t t : old) {
    TetVerts f;
    bool dies = false;
    for (int i = 0; i < 4; ++i) {
      f[i] = mesh.vertex(t, i);
      if (f[i] == w && tet_has_vertex(mesh, t, v)) dies = true;
    }
    if (dies) continue;
    for (uint32_t& x : f)
      if (x == v) x = w;
    fresh.push_back(f);
  }
  return true;
}

bool collapse_tets(TetMesh& mesh, VertexTets& vt, uint32_t v, uint32_t tv, uint32_t w, bool w_moves,
                   std::vector<uint32_t>& old, std::vector<TetVerts>& fresh, std::vector<uint32_t>& ball_w) {
  vertex_ball(mesh, v, tv, old);
  if (w_moves) vertex_ball(mesh, w, vt.tet_of(mesh, w), ball_w);
  return collapse_replacement(mesh, v, w, w_moves ? &ball_w : nullptr, old, fresh);
}

double metric_max_size(const double m[6]) {
  // Smallest eigenvalue of the symmetric 3x3 matrix in closed form (trigonometric).
  const double q = (m[0] + m[2] + m[5]) / 3.0;
  const double p1 = m[1] * m[1] + m[3] * m[3] + m[4] * m[4];
  const double p2 = (m[0] - q) * (m[0] - q) + (m[2] - q) * (m[2] - q) + (m[5] - q) * (m[5] - q) + 2.0 * p1;
  double lmin = q;
  if (p2 > 0.0) {
    const double p = std::sqrt(p2 / 6.0);
    const double b0 = (m[0] - q) / p, b1 = m[1] / p, b2 = (m[2] - q) / p, b3 = m[3] / p, b4 = m[4] / p,
                 b5 = (m[5] - q) / p;
    const double det = b0 * (b2 * b5 - b4 * b4) - b1 * (b1 * b5 - b4 * b3) + b3 * (b1 * b4 - b2 * b3);
    const double r = std::clamp(det / 2.0, -1.0, 1.0);
    const double phi = std::acos(r) / 3.0;
    lmin = q + 2.0 * p * std::cos(phi + 2.0943951023931957);  // + 2 pi / 3
  }
  // Rounding can leave a tiny or negative value for a very elongated M: bound it below by
  // det / trace^2 (<= the smallest eigenvalue of an SPD matrix).
  const double det = m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
                     m[3] * (m[1] * m[4] - m[2] * m[3]);
  const double tr = m[0] + m[2] + m[5];
  if (tr > 0.0) lmin = std::max(lmin, det / (tr * tr));
  return lmin > 0.0 ? 1.0 / std::sqrt(lmin) : 1.0;
}

}  // namespace anitet::meshops

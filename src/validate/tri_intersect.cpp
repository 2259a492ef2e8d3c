#include "validate/tri_intersect.hpp"

#include <algorithm>
#include <cmath>

#include "predicates/predicates.hpp"

namespace anitet::tri_intersect {

namespace {

using predicates::orient2d;
using predicates::orient3d;

bool same_point(const double* p, const double* q) {
  return p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
}

// A point of a coordinate plane: the projection that drops one axis. Dropping axis k keeps axes
// (k+1, k+2) in that cyclic order, so a projection never mirrors a figure.
struct P2 {
  double v[2];
};

P2 project(const double* p, int axis) { return P2{{p[(axis + 1) % 3], p[(axis + 2) % 3]}}; }

int orient(const P2& a, const P2& b, const P2& c) { return orient2d(a.v, b.v, c.v); }

// An axis whose projection keeps the non-degenerate triangle abc non-degenerate (exactly).
int projection_axis(const double* a, const double* b, const double* c) {
  double n[3];
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    n[k] = std::fabs((b[i] - a[i]) * (c[j] - a[j]) - (b[j] - a[j]) * (c[i] - a[i]));
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int x, int y) { return n[x] > n[y]; });
  for (int k : order) {
    if (orient(project(a, k), project(b, k), project(c, k)) != 0) return k;
  }
  return order[0];  // unreachable for a non-degenerate triangle
}

bool point_in_triangle_2d(const P2& p, const P2& a, const P2& b, const P2& c) {
  const int s = orient(a, b, c);
  return orient(a, b, p) * s >= 0 && orient(b, c, p) * s >= 0 && orient(c, a, p) * s >= 0;
}

// Closed segments pq and ab of one plane.
bool segments_meet_2d(const P2& p, const P2& q, const P2& a, const P2& b) {
  const int o1 = orient(p, q, a), o2 = orient(p, q, b);
  if (o1 * o2 > 0) return false;
  const int o3 = orient(a, b, p), o4 = orient(a, b, q);
  if (o3 * o4 > 0) return false;
  if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return true;
  // Collinear: compare the intervals along an axis on which the line is not constant.
  const int k = (p.v[0] != q.v[0] || a.v[0] != b.v[0]) ? 0 : 1;
  const double lo = std::max(std::min(p.v[k], q.v[k]), std::min(a.v[k], b.v[k]));
  const double hi = std::min(std::max(p.v[k], q.v[k]), std::max(a.v[k], b.v[k]));
  return lo <= hi;
}

bool segment_hits_triangle_2d(const P2& p, const P2& q, const P2& a, const P2& b, const P2& c) {
  return point_in_triangle_2d(p, a, b, c) || point_in_triangle_2d(q, a, b, c) ||
         segments_meet_2d(p, q, a, b) || segments_meet_2d(p, q, b, c) ||
         segments_meet_2d(p, q, c, a);
}

// Segment vq and triangle vbc share the corner v: do they meet anywhere else?
bool edge_from_shared_corner_hits(const double* v, const double* q, const double* b,
                                  const double* c) {
  // Off the triangle's plane, the segment touches it at v only.
  if (orient3d(v, b, c, q) != 0) return false;
  const int axis = projection_axis(v, b, c);
  const P2 v2 = project(v, axis), q2 = project(q, axis);
  const P2 b2 = project(b, axis), c2 = project(c, axis);
  // Near v the triangle is the cone spanned by b - v and c - v: is q - v inside it?
  const int s = orient(v2, b2, c2);
  return orient(v2, b2, q2) * s >= 0 && orient(v2, c2, q2) * s <= 0;
}

// Rotates the corners of t so that the corner at point p comes first.
void rotate_to(const double* const t[3], const double* p, const double* out[3]) {
  int k = 0;
  while (k < 2 && !same_point(t[k], p)) ++k;
  for (int i = 0; i < 3; ++i) out[i] = t[(k + i) % 3];
}

bool all_strictly_one_side(int a, int b, int c) {
  return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0);
}

bool disjoint_triangles_meet(const double* const t1[3], const double* const t2[3]) {
  const int p0 = orient3d(t1[0], t1[1], t1[2], t2[0]);
  const int p1 = orient3d(t1[0], t1[1], t1[2], t2[1]);
  const int p2 = orient3d(t1[0], t1[1], t1[2], t2[2]);
  if (all_strictly_one_side(p0, p1, p2)) return false;
  if (p0 == 0 && p1 == 0 && p2 == 0) {
    const int axis = projection_axis(t1[0], t1[1], t1[2]);
    P2 a[3], b[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = project(t1[i], axis);
      b[i] = project(t2[i], axis);
    }
    for (int i = 0; i < 3; ++i) {
      if (segment_hits_triangle_2d(a[i], a[(i + 1) % 3], b[0], b[1], b[2])) return true;
      if (segment_hits_triangle_2d(b[i], b[(i + 1) % 3], a[0], a[1], a[2])) return true;
    }
    return false;
  }
  const int q0 = orient3d(t2[0], t2[1], t2[2], t1[0]);
  const int q1 = orient3d(t2[0], t2[1], t2[2], t1[1]);
  const int q2 = orient3d(t2[0], t2[1], t2[2], t1[2]);
  if (all_strictly_one_side(q0, q1, q2)) return false;
  // Both triangles straddle (or touch) the other's plane: they meet iff an edge of one meets
  // the other triangle (the ends of the intersection segment lie on their boundaries).
  for (int i = 0; i < 3; ++i) {
    if (segment_hits_triangle(t1[i], t1[(i + 1) % 3], t2[0], t2[1], t2[2])) return true;
    if (segment_hits_triangle(t2[i], t2[(i + 1) % 3], t1[0], t1[1], t1[2])) return true;
  }
  return false;
}

// t1 = (v, b, c), t2 = (v, q, r): do they meet anywhere but v?
bool corner_sharing_triangles_meet(const double* const t1[3], const double* const t2[3]) {
  const double *v = t1[0], *b = t1[1], *c = t1[2], *q = t2[1], *r = t2[2];
  const int oq = orient3d(v, b, c, q), orr = orient3d(v, b, c, r);
  if (oq * orr > 0) return false;  // t2 leaves v into one open half-space of t1's plane
  const int ob = orient3d(v, q, r, b), oc = orient3d(v, q, r, c);
  if (ob * oc > 0) return false;
  // The intersection grows from v along some edge of one triangle, or ends on an opposite edge.
  return segment_hits_triangle(q, r, v, b, c) || segment_hits_triangle(b, c, v, q, r) ||
         edge_from_shared_corner_hits(v, q, b, c) || edge_from_shared_corner_hits(v, r, b, c) ||
         edge_from_shared_corner_hits(v, b, q, r) || edge_from_shared_corner_hits(v, c, q, r);
}

// t1 = (u, v, c) and t2 share the edge uv; r is t2's third corner.
bool edge_sharing_triangles_meet(const double* const t1[3], const double* r) {
  const double *u = t1[0], *v = t1[1], *c = t1[2];
  if (orient3d(u, v, c, r) != 0) return false;  // the planes meet along uv only
  const int axis = projection_axis(u, v, c);
  const P2 u2 = project(u, axis), v2 = project(v, axis);
  // Coplanar: they overlap iff c and r lie on the same side of uv.
  return orient(u2, v2, project(c, axis)) * orient(u2, v2, project(r, axis)) > 0;
}

}  // namespace

bool segment_hits_triangle(const double* p, const double* q, const double* a, const double* b,
                           const double* c) {
  const int op = orient3d(a, b, c, p), oq = orient3d(a, b, c, q);
  if (op * oq > 0) return false;
  if (op == 0 && oq == 0) {
    const int axis = projection_axis(a, b, c);
    return segment_hits_triangle_2d(project(p, axis), project(q, axis), project(a, axis),
                                    project(b, axis), project(c, axis));
  }
  // The segment reaches the plane at one point: it is in the triangle iff the line pq passes
  // on the same side of all three edges (or on one of them).
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  const bool has_pos = s1 > 0 || s2 > 0 || s3 > 0;
  const bool has_neg = s1 < 0 || s2 < 0 || s3 < 0;
  return !(has_pos && has_neg);
}

bool triangles_intersect(const double* const t1[3], const double* const t2[3]) {
  int shared = 0;
  const double* first_shared = nullptr;
  bool t2_shared[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (same_point(t1[i], t2[j])) {
        if (shared == 0) first_shared = t1[i];
        ++shared;
        t2_shared[j] = true;
      }
    }
  }
  if (shared == 0) return disjoint_triangles_meet(t1, t2);
  if (shared >= 3) return false;
  if (shared == 1) {
    const double *a[3], *b[3];
    rotate_to(t1, first_shared, a);
    rotate_to(t2, first_shared, b);
    return corner_sharing_triangles_meet(a, b);
  }
  // Two shared corners: put t1's unshared corner last; take t2's unshared corner.
  const double* r = nullptr;
  for (int j = 0; j < 3; ++j) {
    if (!t2_shared[j]) r = t2[j];
  }
  int free1 = 0;
  while (free1 < 3 && (same_point(t1[free1], t2[0]) || same_point(t1[free1], t2[1]) ||
                       same_point(t1[free1], t2[2]))) {
    ++free1;
  }
  const double* a[3] = {t1[(free1 + 1) % 3], t1[(free1 + 2) % 3], t1[free1]};
  return edge_sharing_triangles_meet(a, r);
}

}  // namespace anitet::tri_intersect

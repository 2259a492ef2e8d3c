// 2D metric tensors (xx xy yy) for the 2D mesher: conversions from the 3D SizingField interface
// (a 2D field is a 3D one evaluated at z = 0), log/exp in closed form (log-Euclidean
// interpolation), and the measures refinement and optimization use: edge lengths (the same rule
// as core/sizing.hpp's metric_edge_length) and triangle quality in a metric.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/sizing.hpp"
#include "mesh2d/triangulation.hpp"

namespace anitet::mesh2d {

inline Metric2 metric_at(const SizingField& field, double x, double y) {
  const double p[3] = {x, y, 0.0};
  double m[6];
  field.metric(p, m);
  return Metric2{m[0], m[1], m[2]};
}

// The 3D tensor of a 2D one (zz: the mean of xx and yy, which no 2D measure reads).
inline void to_metric6(const Metric2& m, double out[6]) {
  out[0] = m.xx, out[1] = m.xy, out[2] = m.yy, out[3] = 0.0, out[4] = 0.0, out[5] = 0.5 * (m.xx + m.yy);
}

inline double det(const Metric2& m) { return m.xx * m.yy - m.xy * m.xy; }
inline bool is_spd(const Metric2& m) {
  return std::isfinite(m.xx) && std::isfinite(m.xy) && std::isfinite(m.yy) && m.xx > 0 && det(m) > 0;
}

// log and exp of a symmetric 2x2 tensor through its eigen-decomposition in closed form:
// eigenvalues mean +- dev, the eigenvector angle from (xx - yy, 2 xy).
inline Metric2 log2x2(const Metric2& m) {
  const double mean = 0.5 * (m.xx + m.yy), half = 0.5 * (m.xx - m.yy);
  const double dev = std::sqrt(half * half + m.xy * m.xy);
  const double l1 = std::log(mean + dev), l2 = std::log(std::max(mean - dev, 1e-300));
  const double lm = 0.5 * (l1 + l2), ld = 0.5 * (l1 - l2);
  if (dev <= 1e-300 * mean) return Metric2{lm, 0.0, lm};
  return Metric2{lm + ld * half / dev, ld * m.xy / dev, lm - ld * half / dev};
}
inline Metric2 exp2x2(const Metric2& l) {
  const double mean = 0.5 * (l.xx + l.yy), half = 0.5 * (l.xx - l.yy);
  const double dev = std::sqrt(half * half + l.xy * l.xy);
  const double em = std::exp(mean);
  const double c = em * std::cosh(dev);
  const double s_over = dev > 1e-12 ? em * std::sinh(dev) / dev : em * (1.0 + dev * dev / 6.0);
  return Metric2{c + s_over * half, s_over * l.xy, c - s_over * half};
}

// The frame in which a metric is Euclidean: to(x) = L^T (x - origin) with M = L L^T (Cholesky),
// so that |to(x)| = |x - origin|_M; from() maps back.
struct MetricFrame {
  double l00 = 1, l10 = 0, l11 = 1;
  double ox = 0, oy = 0;
  MetricFrame(const Metric2& m, const double* origin) : ox(origin[0]), oy(origin[1]) {
    l00 = std::sqrt(m.xx);
    l10 = m.xy / l00;
    l11 = std::sqrt(std::max(m.yy - l10 * l10, 1e-300 * m.yy));
  }
  void to(const double* x, double out[2]) const {
    const double dx = x[0] - ox, dy = x[1] - oy;
    out[0] = l00 * dx + l10 * dy;
    out[1] = l11 * dy;
  }
  void from(const double* y, double out[2]) const {
    const double dy = y[1] / l11;
    out[0] = ox + (y[0] - l10 * dy) / l00;
    out[1] = oy + dy;
  }
};

// The circumcentre of a b c in the metric m (the centre of the ellipse of m through them).
inline void metric_circumcenter(const double* a, const double* b, const double* c, const Metric2& m, double out[2]) {
  const MetricFrame f(m, a);
  double pa[2], pb[2], pc[2], cc[2];
  f.to(a, pa);
  f.to(b, pb);
  f.to(c, pc);
  circumcenter(pa, pb, pc, cc);
  f.from(cc, out);
}

// The metric of size h.
inline Metric2 iso_metric(double h) { return Metric2{1.0 / (h * h), 0.0, 1.0 / (h * h)}; }

// Length of e in m.
inline double norm(const Metric2& m, double ex, double ey) {
  return std::sqrt(std::max(m.xx * ex * ex + 2.0 * m.xy * ex * ey + m.yy * ey * ey, 0.0));
}

// The normalized length of ab with the metrics at its ends (core/sizing.hpp's rule).
inline double edge_length(const Metric2& ma, const double* a, const Metric2& mb, const double* b) {
  double m6a[6], m6b[6];
  to_metric6(ma, m6a);
  to_metric6(mb, m6b);
  const double a3[3] = {a[0], a[1], 0.0}, b3[3] = {b[0], b[1], 0.0};
  return metric_edge_length(m6a, a3, m6b, b3);
}

// The mean of three metrics in log space (a triangle's metric).
inline Metric2 mean_metric(const Metric2& a, const Metric2& b, const Metric2& c) {
  if (a.xy == 0 && b.xy == 0 && c.xy == 0 && a.xx == a.yy && b.xx == b.yy && c.xx == c.yy)
    return Metric2{std::cbrt(a.xx * b.xx * c.xx), 0.0, std::cbrt(a.xx * b.xx * c.xx)};
  const Metric2 la = log2x2(a), lb = log2x2(b), lc = log2x2(c);
  return exp2x2(Metric2{(la.xx + lb.xx + lc.xx) / 3.0, (la.xy + lb.xy + lc.xy) / 3.0, (la.yy + lb.yy + lc.yy) / 3.0});
}

// Signed area of abc.
inline double area(const double* a, const double* b, const double* c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

// The mean ratio 4 sqrt(3) A / (sum of squared edge lengths) in the metric m: 1 for a triangle
// equilateral in m, 0 when flat, negative when inverted.
inline double quality(const Metric2& m, const double* a, const double* b, const double* c) {
  const double ar = area(a, b, c) * std::sqrt(std::max(det(m), 0.0));
  const double l = norm(m, b[0] - a[0], b[1] - a[1]), l2 = norm(m, c[0] - b[0], c[1] - b[1]),
               l3 = norm(m, a[0] - c[0], a[1] - c[1]);
  const double s = l * l + l2 * l2 + l3 * l3;
  return s > 0 ? 4.0 * std::sqrt(3.0) * ar / s : 0.0;
}

// The smallest angle of abc (radians; Euclidean).
inline double min_angle(const double* a, const double* b, const double* c) {
  auto ang = [](const double* o, const double* p, const double* q) {
    const double ux = p[0] - o[0], uy = p[1] - o[1], vx = q[0] - o[0], vy = q[1] - o[1];
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy);
  };
  return std::min({ang(a, b, c), ang(b, c, a), ang(c, a, b)});
}

}  // namespace anitet::mesh2d

namespace anitet::mesh2d {

// The field's metric at each vertex of a triangulation, evaluated once per vertex (vertices
// added later are evaluated by update()).
struct VertexMetrics {
  const SizingField& field;
  bool anisotropic;
  std::vector<Metric2> at;

  VertexMetrics(const SizingField& f, bool aniso) : field(f), anisotropic(aniso) {}
  void update(const Triangulation& m) {
    for (size_t v = at.size(); v < m.num_vertices(); ++v) at.push_back(metric_at(field, m.xy[2 * v], m.xy[2 * v + 1]));
  }
  double length(const Triangulation& m, uint32_t a, uint32_t b) const {
    return edge_length(at[a], m.point(a), at[b], m.point(b));
  }
  // A triangle's quality in the mean of its vertices' metrics (Euclidean shape when isotropic).
  double quality(const Triangulation& m, uint32_t a, uint32_t b, uint32_t c) const {
    return quality_at(m.point(a), m.point(b), m.point(c), a, b, c);
  }
  // The same with the points given (a vertex being moved).
  double quality_at(const double* pa, const double* pb, const double* pc, uint32_t a, uint32_t b, uint32_t c) const {
    if (!anisotropic) return mesh2d::quality(Metric2{}, pa, pb, pc);
    return mesh2d::quality(mean_metric(at[a], at[b], at[c]), pa, pb, pc);
  }
};

}  // namespace anitet::mesh2d

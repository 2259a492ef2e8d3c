// Sizing fields: the one interface through which every meshing stage asks "how long should an
// edge be here, and in which direction". A field answers with a metric tensor M (symmetric
// positive definite); the length of a vector e in it is sqrt(e^T M e) and an edge of length 1 is
// the target ("normalized" or "metric" length). An isotropic size h is the metric I / h^2.
//
// Components are stored as 6 doubles in the order xx xy yy xz yz zz (Medit's .sol order, the same
// as VolumeMesh::vertex_metric):
//     | m[0] m[1] m[3] |
//     | m[1] m[2] m[4] |
//     | m[3] m[4] m[5] |
//
// IsotropicSurfaceSizing is the simple field stage 1 uses when nothing else is given: the size of
// the input's triangles near a point. Metric fields held in OpenVDB grids (metric/) implement the
// same interface later.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/surface_mesh.hpp"

namespace anitet {

class SizingField {
 public:
  virtual ~SizingField() = default;
  // The metric tensor at p (xx xy yy xz yz zz). Must be symmetric positive definite.
  virtual void metric(const double p[3], double m[6]) const = 0;
  // True when every metric() is a multiple of I: callers may then skip per-point tensor work.
  virtual bool isotropic() const { return false; }
};

// ---- Metric helpers ----------------------------------------------------------------------------

// The isotropic metric of size h: I / h^2.
inline void isotropic_metric(double h, double m[6]) {
  const double s = 1.0 / (h * h);
  m[0] = s;
  m[1] = 0.0;
  m[2] = s;
  m[3] = 0.0;
  m[4] = 0.0;
  m[5] = s;
}

// Whether m is a multiple of I up to a relative 1e-6 (fields interpolated in log space, e.g.
// metric/'s grids, return isotropic tensors with rounding noise).
inline bool metric_is_isotropic(const double m[6]) {
  const double tol = 1e-6 * std::fabs(m[0] + m[2] + m[5]);
  return std::fabs(m[1]) <= tol && std::fabs(m[3]) <= tol && std::fabs(m[4]) <= tol &&
         std::fabs(m[0] - m[2]) <= tol && std::fabs(m[2] - m[5]) <= tol;
}

// sqrt(v^T M v): the length of v in the metric m.
inline double metric_norm(const double m[6], const double v[3]) {
  const double q = m[0] * v[0] * v[0] + m[2] * v[1] * v[1] + m[5] * v[2] * v[2] +
                   2.0 * (m[1] * v[0] * v[1] + m[3] * v[0] * v[2] + m[4] * v[1] * v[2]);
  return std::sqrt(std::max(q, 0.0));
}

// Normalized length of the edge ab: the geometric mean of its length in the metrics ma at a and
// mb at b (exact for a size that varies geometrically along the edge, cheap, and symmetric in a
// and b).
inline double metric_edge_length(const double ma[6], const double a[3], const double mb[6], const double b[3]) {
  const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  return std::sqrt(metric_norm(ma, e) * metric_norm(mb, e));
}

// The same with the metrics of `field` at both ends.
inline double metric_edge_length(const SizingField& field, const double a[3], const double b[3]) {
  double ma[6], mb[6];
  field.metric(a, ma);
  field.metric(b, mb);
  return metric_edge_length(ma, a, mb, b);
}

// Normalized length of ab in one given metric (e.g. the metric at an element's centroid).
inline double metric_edge_length(const double m[6], const double a[3], const double b[3]) {
  const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  return metric_norm(m, e);
}

// ---- Isotropic size from the input surface -----------------------------------------------------

// h(p) = the mean length of the edges incident to the surface vertex nearest to p (ties: the
// lowest vertex id), times `scale`. Vertices without a triangle are ignored. Nearest-vertex
// queries use a static k-d tree; the field is immutable after construction and thread-safe.
class IsotropicSurfaceSizing final : public SizingField {
 public:
  explicit IsotropicSurfaceSizing(const SurfaceMesh& surface, double scale = 1.0) {
    const size_t nv = surface.num_vertices();
    std::vector<double> sum(nv, 0.0);
    std::vector<uint32_t> count(nv, 0);
    for (size_t t = 0; t < surface.num_triangles(); ++t) {
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = surface.tri[3 * t + k], b = surface.tri[3 * t + (k + 1) % 3];
        if (a >= nv || b >= nv) continue;
        const double* pa = surface.point(a);
        const double* pb = surface.point(b);
        const double len = std::sqrt((pa[0] - pb[0]) * (pa[0] - pb[0]) +
                                     (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                                     (pa[2] - pb[2]) * (pa[2] - pb[2]));
        // Each edge is seen from both of its triangles: count it once per end per triangle.
        sum[a] += len;
        sum[b] += len;
        ++count[a];
        ++count[b];
      }
    }
    for (uint32_t v = 0; v < nv; ++v) {
      if (count[v] == 0 || !(sum[v] > 0.0)) continue;
      ids_.push_back(v);
      pts_.insert(pts_.end(), surface.point(v), surface.point(v) + 3);
      size_.push_back(scale * sum[v] / count[v]);
    }
    axis_.assign(ids_.size(), 0);
    build(0, ids_.size());
  }

  void metric(const double p[3], double m[6]) const override { isotropic_metric(size(p), m); }
  bool isotropic() const override { return true; }

  // The size at p (1 when the surface has no edge at all).
  double size(const double p[3]) const {
    if (ids_.empty()) return 1.0;
    size_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    nearest(0, ids_.size(), p, best, best_d2);
    return size_[best];
  }

 private:
  // Implicit balanced k-d tree over slots [lo, hi): the median slot splits along axis_[mid].
  void build(size_t lo, size_t hi) {
    if (hi - lo <= 1) return;
    double bmin[3], bmax[3];
    for (int k = 0; k < 3; ++k) {
      bmin[k] = std::numeric_limits<double>::infinity();
      bmax[k] = -bmin[k];
    }
    for (size_t i = lo; i < hi; ++i)
      for (int k = 0; k < 3; ++k) {
        bmin[k] = std::min(bmin[k], pts_[3 * i + k]);
        bmax[k] = std::max(bmax[k], pts_[3 * i + k]);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (bmax[k] - bmin[k] > bmax[axis] - bmin[axis]) axis = k;
    const size_t mid = (lo + hi) / 2;
    // Sort the slot permutation by the axis coordinate, moving points, ids and sizes together.
    std::vector<size_t> perm(hi - lo);
    for (size_t i = 0; i < perm.size(); ++i) perm[i] = lo + i;
    std::nth_element(perm.begin(), perm.begin() + (mid - lo), perm.end(), [&](size_t x, size_t y) {
      const double cx = pts_[3 * x + axis], cy = pts_[3 * y + axis];
      return cx < cy || (cx == cy && ids_[x] < ids_[y]);
    });
    std::vector<double> p(3 * perm.size());
    std::vector<uint32_t> id(perm.size());
    std::vector<double> s(perm.size());
    for (size_t i = 0; i < perm.size(); ++i) {
      std::copy_n(&pts_[3 * perm[i]], 3, &p[3 * i]);
      id[i] = ids_[perm[i]];
      s[i] = size_[perm[i]];
    }
    std::copy(p.begin(), p.end(), pts_.begin() + 3 * lo);
    std::copy(id.begin(), id.end(), ids_.begin() + lo);
    std::copy(s.begin(), s.end(), size_.begin() + lo);
    axis_[mid] = static_cast<uint8_t>(axis);
    build(lo, mid);
    build(mid + 1, hi);
  }

  void nearest(size_t lo, size_t hi, const double* q, size_t& best, double& best_d2) const {
    if (lo >= hi) return;
    const size_t mid = (lo + hi) / 2;
    const double* c = &pts_[3 * mid];
    const double d2 = (c[0] - q[0]) * (c[0] - q[0]) + (c[1] - q[1]) * (c[1] - q[1]) +
                      (c[2] - q[2]) * (c[2] - q[2]);
    if (d2 < best_d2 || (d2 == best_d2 && ids_[mid] < ids_[best])) {
      best_d2 = d2;
      best = mid;
    }
    if (hi - lo == 1) return;
    const double delta = q[axis_[mid]] - c[axis_[mid]];
    const bool left_first = delta <= 0.0;
    if (left_first) nearest(lo, mid, q, best, best_d2);
    else nearest(mid + 1, hi, q, best, best_d2);
    if (delta * delta <= best_d2) {
      if (left_first) nearest(mid + 1, hi, q, best, best_d2);
      else nearest(lo, mid, q, best, best_d2);
    }
  }

  std::vector<double> pts_;     // 3 per slot, in k-d tree order
  std::vector<uint32_t> ids_;   // surface vertex id of each slot
  std::vector<double> size_;    // h of each slot
  std::vector<uint8_t> axis_;   // split axis of the subtree whose median is this slot
};

}  // namespace anitet

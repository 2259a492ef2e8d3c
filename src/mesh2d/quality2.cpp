#include "mesh2d/quality2.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/metric_measures.hpp"
#include "mesh2d/metric2.hpp"

namespace anitet::mesh2d {

Quality2 measure_quality(const TriMesh2& m) {
  Quality2 q;
  q.vertices = m.num_vertices();
  q.triangles = m.num_triangles();
  q.min_angle_deg = q.min_angle_free_deg = 180.0;
  q.min_radius_ratio = 1.0;
  double rr_sum = 0;
  auto angle = [](const double* o, const double* p, const double* r) {
    const double ux = p[0] - o[0], uy = p[1] - o[1], vx = r[0] - o[0], vy = r[1] - o[1];
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
  };
  for (size_t t = 0; t < q.triangles; ++t) {
    const uint32_t* v = &m.tri[3 * t];
    const double* a = &m.xy[2 * size_t(v[0])];
    const double* b = &m.xy[2 * size_t(v[1])];
    const double* c = &m.xy[2 * size_t(v[2])];
    const double angles[3] = {angle(a, b, c), angle(b, c, a), angle(c, a, b)};
    const double lo = std::min({angles[0], angles[1], angles[2]});
    q.min_angle_deg = std::min(q.min_angle_deg, lo);
    q.max_angle_deg = std::max({q.max_angle_deg, angles[0], angles[1], angles[2]});
    if (v[0] >= m.input_points && v[1] >= m.input_points && v[2] >= m.input_points) {
      ++q.free_triangles;
      q.min_angle_free_deg = std::min(q.min_angle_free_deg, lo);
    }
    const double la = std::hypot(b[0] - c[0], b[1] - c[1]), lb = std::hypot(c[0] - a[0], c[1] - a[1]),
                 lc = std::hypot(a[0] - b[0], a[1] - b[1]);
    const double s = 0.5 * (la + lb + lc), ar = std::fabs(area(a, b, c));
    const double rr = la * lb * lc > 0 ? 8.0 * ar * ar / (s * la * lb * lc) : 0.0;
    rr_sum += rr;
    q.min_radius_ratio = std::min(q.min_radius_ratio, rr);
  }
  q.mean_radius_ratio = q.triangles ? rr_sum / double(q.triangles) : 0.0;
  std::vector<uint64_t> edges;
  edges.reserve(3 * q.triangles);
  for (size_t t = 0; t < q.triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.tri[3 * t + size_t(k)], b = m.tri[3 * t + size_t((k + 1) % 3)];
      edges.push_back((uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  q.edges = edges.size();
  q.in_range = 1.0;
  if (m.metric.size() == 3 * q.vertices && q.edges) {
    size_t in = 0;
    q.length_min = 1e300;
    for (const uint64_t key : edges) {
      const uint32_t a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
      const Metric2 ma{m.metric[3 * size_t(a)], m.metric[3 * size_t(a) + 1], m.metric[3 * size_t(a) + 2]};
      const Metric2 mb{m.metric[3 * size_t(b)], m.metric[3 * size_t(b) + 1], m.metric[3 * size_t(b) + 2]};
      const double l = edge_length(ma, &m.xy[2 * size_t(a)], mb, &m.xy[2 * size_t(b)]);
      q.length_min = std::min(q.length_min, l);
      q.length_max = std::max(q.length_max, l);
      if (in_unit_range(l)) ++in;
    }
    q.in_range = double(in) / double(q.edges);
  }
  return q;
}

}  // namespace anitet::mesh2d

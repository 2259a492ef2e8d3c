#include "mesh2d/corners.hpp"

#include <algorithm>
#include <cmath>

namespace anitet::mesh2d {

bool sharp_corner(const Triangulation& m, uint32_t v, std::vector<uint32_t>& ends, double& shortest) {
  ends.clear();
  shortest = 1e300;
  if (m.vtri[v] == kNone) return false;
  std::vector<uint32_t> fan;
  m.star(v, fan);
  for (uint32_t t : fan) {
    const int i = m.index_of(t, v);
    if (m.constrained(t, (i + 2) % 3)) ends.push_back(m.v(t, (i + 1) % 3));
  }
  if (!fan.empty()) {
    const uint32_t t = fan.back();
    const int i = m.index_of(t, v);
    if (m.constrained(t, (i + 1) % 3) && m.across(t, (i + 1) % 3) == kNone) ends.push_back(m.v(t, (i + 2) % 3));
  }
  if (ends.size() < 2) return false;
  const double* o = m.point(v);
  double smallest = M_PI;
  for (size_t k = 0; k < ends.size(); ++k) {
    const double* a = m.point(ends[k]);
    shortest = std::min(shortest, std::hypot(a[0] - o[0], a[1] - o[1]));
    const double* b = m.point(ends[(k + 1) % ends.size()]);
    const double ang = std::atan2((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]),
                                  (a[0] - o[0]) * (b[0] - o[0]) + (a[1] - o[1]) * (b[1] - o[1]));
    if (ang > 0) smallest = std::min(smallest, ang);
  }
  return smallest < M_PI / 3;
}

size_t split_corner(Triangulation& m, VertexMetrics& vm, std::vector<uint8_t>& fixed, uint32_t v, double d) {
  std::vector<uint32_t> ends;
  double shortest;
  sharp_corner(m, v, ends, shortest);
  Kernel kernel(m);
  size_t splits = 0;
  for (uint32_t e : ends) {
    const double* o = m.point(v);
    const double* a = m.point(e);
    const double len = std::hypot(a[0] - o[0], a[1] - o[1]);
    if (len < 1.5 * d) continue;
    uint32_t t;
    int k;
    if (!m.find_edge(v, e, t, k) && !m.find_edge(e, v, t, k)) continue;
    const double q[2] = {o[0] + d / len * (a[0] - o[0]), o[1] + d / len * (a[1] - o[1])};
    Location loc;
    loc.t = t, loc.kind = Location::OnEdge, loc.k = k;
    const Metric2 mq = metric_at(vm.field, q[0], q[1]);
    if (kernel.insert(q, loc, vm.anisotropic ? &mq : nullptr, true) == kNone) continue;
    vm.at.push_back(mq);
    fixed.push_back(1);
    ++splits;
  }
  return splits;
}

size_t split_sharp_corners(Triangulation& m, VertexMetrics& vm, std::vector<uint8_t>& fixed, uint32_t count) {
  std::vector<uint32_t> ends;
  size_t splits = 0;
  auto at = [&](uint32_t v) {
    double shortest;
    if (!sharp_corner(m, v, ends, shortest)) return;
    const double h = 1.0 / std::sqrt(std::max(vm.at[v].xx, vm.at[v].yy));
    const double d = std::exp2(std::floor(std::log2(std::min(0.5 * shortest, h))));
    splits += split_corner(m, vm, fixed, v, d);
  };
  for (uint32_t v = 0; v < count; ++v) at(v);
  for (const auto& copy : m.copies) at(copy.first);  // a pinched input point's other fans
  return splits;
}

size_t split_segment_piece(Triangulation& m, VertexMetrics& vm, std::vector<uint8_t>& fixed, uint32_t t, int k) {
  const uint32_t a = m.edge_a(t, k), b = m.edge_b(t, k);
  std::vector<uint32_t> ends;
  double shortest;
  for (uint32_t corner : {a, b})
    if (fixed[corner] && sharp_corner(m, corner, ends, shortest)) {
      const double len = std::hypot(m.point(b)[0] - m.point(a)[0], m.point(b)[1] - m.point(a)[1]);
      return split_corner(m, vm, fixed, corner, std::exp2(std::round(std::log2(0.5 * len))));
    }
  const double mid[2] = {0.5 * (m.point(a)[0] + m.point(b)[0]), 0.5 * (m.point(a)[1] + m.point(b)[1])};
  Location on;
  on.t = t, on.kind = Location::OnEdge, on.k = k;
  const Metric2 mm = metric_at(vm.field, mid[0], mid[1]);
  Kernel kernel(m);
  if (kernel.insert(mid, on, vm.anisotropic ? &mm : nullptr, true) == kNone) return 0;
  vm.at.push_back(mm);
  fixed.push_back(0);
  return 1;
}

}  // namespace anitet::mesh2d

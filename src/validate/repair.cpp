#include "validate/repair.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace anitet::repair {

size_t merge_duplicate_vertices(SurfaceMesh& s, std::vector<uint32_t>& vertex_map) {
  const size_t nv = s.num_vertices();
  std::vector<uint32_t> order;
  order.reserve(nv);
  for (size_t v = 0; v < nv; ++v) {
    const double* p = s.point(v);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) {
      order.push_back(static_cast<uint32_t>(v));
    }
  }
  const auto less = [&](uint32_t a, uint32_t b) {
    const double *p = s.point(a), *q = s.point(b);
    if (p[0] != q[0]) return p[0] < q[0];
    if (p[1] != q[1]) return p[1] < q[1];
    if (p[2] != q[2]) return p[2] < q[2];
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<uint32_t> keep(nv);
  std::iota(keep.begin(), keep.end(), 0u);
  size_t removed = 0;
  for (size_t i = 1; i < order.size(); ++i) {
    const double *p = s.point(order[i]), *q = s.point(order[i - 1]);
    if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) {
      keep[order[i]] = keep[order[i - 1]];  // sorted by id within a group: the lowest id wins
      ++removed;
    }
  }
  if (removed == 0) return 0;
  vertex_map.assign(nv, 0);
  uint32_t next = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (keep[v] == v) {
      vertex_map[v] = next;
      for (int k = 0; k < 3; ++k) s.xyz[3 * size_t(next) + k] = s.xyz[3 * v + k];
      ++next;
    } else {
      vertex_map[v] = vertex_map[keep[v]];  // keep[v] < v: already numbered
    }
  }
  s.xyz.resize(3 * size_t(next));
  for (auto& v : s.tri) v = vertex_map[v];
  return removed;
}

void flip_triangles(SurfaceMesh& s, const std::vector<uint32_t>& tris) {
  for (uint32_t t : tris) std::swap(s.tri[3 * size_t(t) + 1], s.tri[3 * size_t(t) + 2]);
}

}  // namespace anitet::repair

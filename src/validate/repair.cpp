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

std::vector<ShellReorientation> orient_shells_consistently(SurfaceMesh& s, topology::EdgeTable& edges,
                                                          const topology::Topology& topo) {
  std::vector<ShellReorientation> out;
  if (topo.inconsistent_edges.empty()) return out;
  const size_t nt = s.num_triangles(), num_shells = topo.shell_first_triangle.size();
  // Shells to repair: some edge used twice in one direction, every edge with two triangles.
  std::vector<uint8_t> wanted(num_shells, 0);
  for (uint32_t e : topo.inconsistent_edges) wanted[topo.shell_of[edges.half_tri[edges.edge_begin[e]]]] = 1;
  for (const std::vector<uint32_t>* list : {&topo.boundary_edges, &topo.non_manifold_edges})
    for (uint32_t e : *list) wanted[topo.shell_of[edges.half_tri[edges.edge_begin[e]]]] = 0;
  if (std::find(wanted.begin(), wanted.end(), 1) == wanted.end()) return out;

  // Across each two-triangle edge: the other triangle, and whether the two must be flipped
  // differently (they now run the edge the same way) - a bit of the 3t+c slot of each corner.
  constexpr uint32_t kNoTri = UINT32_MAX;
  std::vector<uint32_t> other(3 * nt, kNoTri), edge_of(3 * nt, 0);
  std::vector<uint8_t> differ(3 * nt, 0);
  for (size_t e = 0; e < edges.num_edges(); ++e) {
    if (edges.edge_size(e) != 2) continue;
    const uint32_t h1 = edges.edge_begin[e], h2 = h1 + 1;
    const size_t c1 = 3 * size_t(edges.half_tri[h1]) + edges.half_corner[h1];
    const size_t c2 = 3 * size_t(edges.half_tri[h2]) + edges.half_corner[h2];
    other[c1] = edges.half_tri[h2];
    other[c2] = edges.half_tri[h1];
    differ[c1] = differ[c2] = edges.forward(s, h1) == edges.forward(s, h2);
    edge_of[c1] = edge_of[c2] = uint32_t(e);
  }
  std::vector<int8_t> flip(nt, -1);  // -1: not reached yet
  std::vector<uint8_t> is_flipped(nt, 0);
  std::vector<uint32_t> stack, members;
  for (size_t sh = 0; sh < num_shells; ++sh) {
    if (!wanted[sh]) continue;
    ShellReorientation r;
    r.shell = uint32_t(sh);
    members.clear();
    stack.assign(1, topo.shell_first_triangle[sh]);
    flip[stack[0]] = 0;
    while (!stack.empty() && r.orientable) {
      const uint32_t t = stack.back();
      stack.pop_back();
      members.push_back(t);
      for (int c = 0; c < 3; ++c) {
        const uint32_t u = other[3 * size_t(t) + c];
        if (u == kNoTri) continue;
        const int8_t want = int8_t(flip[t] ^ differ[3 * size_t(t) + c]);
        if (flip[u] < 0) {
          flip[u] = want;
          stack.push_back(u);
        } else if (flip[u] != want) {
          r.orientable = false;
          r.edge_lo = edges.edge_lo(edge_of[3 * size_t(t) + c]);
          r.edge_hi = edges.edge_hi(edge_of[3 * size_t(t) + c]);
          break;
        }
      }
    }
    if (r.orientable) {
      size_t count = 0;
      for (uint32_t t : members) count += size_t(flip[t]);
      const int8_t which = count * 2 <= members.size() ? 1 : 0;  // flip the fewer
      std::vector<uint32_t> flipped;
      for (uint32_t t : members)
        if (flip[t] == which) flipped.push_back(t);
      std::sort(flipped.begin(), flipped.end());
      flip_triangles(s, flipped);
      r.flipped = flipped.size();
      for (uint32_t t : flipped) is_flipped[t] = 1;
    }
    out.push_back(r);
  }
  // (a, b, c) became (a, c, b): the half-edge that ran from corner k runs from corner 2 - k.
  for (size_t h = 0; h < edges.half_tri.size(); ++h)
    if (is_flipped[edges.half_tri[h]]) edges.half_corner[h] = uint8_t(2 - edges.half_corner[h]);
  return out;
}

}  // namespace anitet::repair

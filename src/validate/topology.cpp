#include "validate/topology.hpp"

#include <algorithm>
#include <numeric>

namespace anitet::topology {

namespace {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0u); }
  uint32_t find(uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];  // path halving
      x = parent_[x];
    }
    return x;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) parent_[b] = a;  // the smaller id becomes the root: deterministic
    else parent_[a] = b;
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace

EdgeTable build_edge_table(const SurfaceMesh& s, const std::vector<uint8_t>& usable) {
  struct Half {
    uint64_t key;
    uint32_t tri;
    uint8_t corner;
  };
  std::vector<Half> halves;
  halves.reserve(3 * s.num_triangles());
  for (size_t t = 0; t < s.num_triangles(); ++t) {
    if (!usable[t]) continue;
    for (uint8_t c = 0; c < 3; ++c) {
      const uint32_t a = s.tri[3 * t + c], b = s.tri[3 * t + (c + 1) % 3];
      const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      halves.push_back(Half{key, static_cast<uint32_t>(t), c});
    }
  }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return x.key != y.key ? x.key < y.key : (x.tri != y.tri ? x.tri < y.tri : x.corner < y.corner);
  });
  EdgeTable table;
  table.half_key.resize(halves.size());
  table.half_tri.resize(halves.size());
  table.half_corner.resize(halves.size());
  for (size_t h = 0; h < halves.size(); ++h) {
    table.half_key[h] = halves[h].key;
    table.half_tri[h] = halves[h].tri;
    table.half_corner[h] = halves[h].corner;
    if (h == 0 || halves[h].key != halves[h - 1].key) {
      table.edge_begin.push_back(static_cast<uint32_t>(h));
    }
  }
  table.edge_begin.push_back(static_cast<uint32_t>(halves.size()));
  return table;
}

Topology analyse(const SurfaceMesh& s, const std::vector<uint8_t>& usable, const EdgeTable& edges) {
  Topology topo;
  const size_t nt = s.num_triangles();
  UnionFind shells(nt);
  UnionFind corners(3 * nt);  // corner 3t+c: triangle t at its vertex tri[3t+c]
  std::vector<uint8_t> bad_edge_tri(nt, 0);

  for (size_t e = 0; e < edges.num_edges(); ++e) {
    const uint32_t begin = edges.edge_begin[e], end = edges.edge_begin[e + 1];
    const size_t n = end - begin;
    // The edge is used twice in one direction (on a non-manifold edge too: with three or more
    // triangles this always happens, and SOURCES.md's counts use the same rule).
    size_t forward = 0;
    for (uint32_t h = begin; h < end; ++h) forward += edges.forward(s, h) ? 1 : 0;
    const bool inconsistent = forward >= 2 || n - forward >= 2;
    if (n == 1) topo.boundary_edges.push_back(static_cast<uint32_t>(e));
    if (n > 2) topo.non_manifold_edges.push_back(static_cast<uint32_t>(e));
    if (inconsistent) topo.inconsistent_edges.push_back(static_cast<uint32_t>(e));
    const bool bad = n != 2 || inconsistent;
    // Corners of the edge's triangles at its two ends, for the fan check.
    uint32_t lo0 = 0, hi0 = 0;
    for (uint32_t h = begin; h < end; ++h) {
      const uint32_t t = edges.half_tri[h], c = edges.half_corner[h];
      const uint32_t start = 3 * t + c, stop = 3 * t + (c + 1) % 3;
      const bool fwd = edges.forward(s, h);
      const uint32_t lo = fwd ? start : stop, hi = fwd ? stop : start;
      if (h == begin) {
        lo0 = lo;
        hi0 = hi;
      } else {
        corners.unite(lo0, lo);
        corners.unite(hi0, hi);
        shells.unite(edges.half_tri[begin], t);
      }
      if (bad) bad_edge_tri[t] = 1;
    }
  }

  // A vertex is manifold when all its corners fall in one fan (one union-find class).
  std::vector<uint32_t> fan_of_vertex(s.num_vertices(), UINT32_MAX);
  std::vector<uint8_t> vertex_flagged(s.num_vertices(), 0);
  for (size_t t = 0; t < nt; ++t) {
    if (!usable[t]) continue;
    for (uint32_t c = 0; c < 3; ++c) {
      const uint32_t v = s.tri[3 * t + c];
      const uint32_t root = corners.find(static_cast<uint32_t>(3 * t + c));
      if (fan_of_vertex[v] == UINT32_MAX) {
        fan_of_vertex[v] = root;
      } else if (fan_of_vertex[v] != root && !vertex_flagged[v]) {
        vertex_flagged[v] = 1;
      }
    }
  }
  for (size_t v = 0; v < s.num_vertices(); ++v) {
    if (vertex_flagged[v]) topo.non_manifold_vertices.push_back(static_cast<uint32_t>(v));
  }

  // Shells, numbered in order of their smallest triangle id (the union-find root).
  topo.shell_of.assign(nt, -1);
  std::vector<int32_t> shell_of_root(nt, -1);
  for (size_t t = 0; t < nt; ++t) {
    if (!usable[t]) continue;
    const uint32_t root = shells.find(static_cast<uint32_t>(t));
    if (shell_of_root[root] < 0) {
      shell_of_root[root] = static_cast<int32_t>(topo.shell_first_triangle.size());
      topo.shell_first_triangle.push_back(static_cast<uint32_t>(t));
      topo.shell_size.push_back(0);
      topo.shell_closed.push_back(1);
    }
    const int32_t sh = shell_of_root[root];
    topo.shell_of[t] = sh;
    ++topo.shell_size[sh];
    if (bad_edge_tri[t]) topo.shell_closed[sh] = 0;
  }
  return topo;
}

}  // namespace anitet::topology

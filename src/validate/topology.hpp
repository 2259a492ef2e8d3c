// Combinatorial checks of a triangle soup: edges and their triangles, vertex fans, shells.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.hpp"

namespace anitet::topology {

// The half-edges of the usable triangles (three distinct vertex ids), grouped by undirected
// edge. Half-edge h runs from tri[3*t + c] to tri[3*t + (c+1)%3] with t = half_tri[h],
// c = half_corner[h]; edge e owns half-edges [edge_begin[e], edge_begin[e+1]), sorted by
// triangle id. Edges are sorted by (smaller vertex id, larger vertex id).
struct EdgeTable {
  std::vector<uint64_t> half_key;  // (lo << 32) | hi of each half-edge
  std::vector<uint32_t> half_tri;
  std::vector<uint8_t> half_corner;
  std::vector<uint32_t> edge_begin;

  size_t num_edges() const { return edge_begin.empty() ? 0 : edge_begin.size() - 1; }
  size_t edge_size(size_t e) const { return edge_begin[e + 1] - edge_begin[e]; }
  uint32_t edge_lo(size_t e) const { return uint32_t(half_key[edge_begin[e]] >> 32); }
  uint32_t edge_hi(size_t e) const { return uint32_t(half_key[edge_begin[e]] & 0xffffffffu); }
  // True when half-edge h runs from the smaller vertex id to the larger one.
  bool forward(const SurfaceMesh& s, size_t h) const {
    return s.tri[3 * size_t(half_tri[h]) + half_corner[h]] == uint32_t(half_key[h] >> 32);
  }
};

// usable[t]: triangle t has three distinct vertex ids (all ids are known to be in range).
EdgeTable build_edge_table(const SurfaceMesh& s, const std::vector<uint8_t>& usable);

struct Topology {
  std::vector<uint32_t> boundary_edges;       // edges with one triangle
  std::vector<uint32_t> non_manifold_edges;   // edges with more than two triangles
  std::vector<uint32_t> inconsistent_edges;   // used twice in one direction (any triangle count)
  std::vector<uint32_t> non_manifold_vertices;
  // Shells: connected components of usable triangles across edges, numbered by smallest
  // triangle id. shell_of[t] = -1 for unusable triangles.
  std::vector<int32_t> shell_of;
  std::vector<uint32_t> shell_first_triangle;
  std::vector<uint32_t> shell_size;
  std::vector<uint8_t> shell_closed;  // all its edges have two consistently oriented triangles
};

Topology analyse(const SurfaceMesh& s, const std::vector<uint8_t>& usable, const EdgeTable& edges);

}  // namespace anitet::topology

// Axis-aligned bounding-box hierarchy over triangles, for "which triangles are near this box"
// queries (self-intersection checks, boundary checks, front collision tests in stage 1).
// Built once over a fixed set of triangles; queries are const and thread-safe.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

struct Box3 {
  double lo[3];
  double hi[3];
};

// The box of n >= 1 points (xyz: 3 doubles per point).
inline Box3 bounding_box(const double* xyz, size_t n) {
  Box3 b = {{xyz[0], xyz[1], xyz[2]}, {xyz[0], xyz[1], xyz[2]}};
  for (size_t i = 1; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = std::min(b.lo[d], xyz[3 * i + size_t(d)]);
      b.hi[d] = std::max(b.hi[d], xyz[3 * i + size_t(d)]);
    }
  return b;
}

// Whether two closed boxes overlap (touching counts).
inline bool boxes_overlap(const Box3& a, const Box3& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] &&  //
         a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&  //
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// The cube of half-side r around p.
inline Box3 box_around(const double* p, double r) {
  return {{p[0] - r, p[1] - r, p[2] - r}, {p[0] + r, p[1] + r, p[2] + r}};
}

class TriangleBVH {
 public:
  TriangleBVH() = default;
  // xyz: 3 doubles per vertex; tri: 3 indices per triangle. Keeps no pointer to the inputs.
  void build(const double* xyz, const uint32_t* tri, size_t num_triangles);

  // Calls visit(triangle_index) for every triangle whose box overlaps [lo, hi] (closed boxes:
  // touching counts). visit returns false to stop early.
  template <class Visit>
  void query(const Box3& box, Visit&& visit) const;

  // Every pair (i < j) of triangles whose boxes overlap, for self-intersection tests; visit(i, j)
  // returns false to stop early.
  template <class Visit>
  void overlapping_pairs(Visit&& visit) const;

  size_t num_triangles() const { return tri_box_.size(); }
  const Box3& triangle_box(size_t t) const { return tri_box_[t]; }

 private:
  struct Node {
    Box3 box;
    uint32_t first;  // leaf: first index into order_; inner: left child (right = first + 1)
    uint32_t count;  // leaf: number of triangles; inner: 0
  };
  std::vector<Node> nodes_;
  std::vector<uint32_t> order_;  // triangle ids, leaves point into it
  std::vector<Box3> tri_box_;
  // (template bodies are defined in bvh_impl.hpp, included below)
  template <class Visit>
  bool pairs_within(uint32_t n, Visit& visit) const;
  template <class Visit>
  bool pairs_between(uint32_t a, uint32_t b, Visit& visit) const;
};

}  // namespace anitet

#include "core/bvh_impl.hpp"

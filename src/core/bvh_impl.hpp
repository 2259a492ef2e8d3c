// Template bodies of TriangleBVH (included at the end of bvh.hpp; do not include directly).
#pragma once

#include <utility>

namespace anitet {

namespace bvh_detail {

inline double half_perimeter(const Box3& b) {
  return (b.hi[0] - b.lo[0]) + (b.hi[1] - b.lo[1]) + (b.hi[2] - b.lo[2]);
}

}  // namespace bvh_detail

template <class Visit>
void TriangleBVH::query(const Box3& box, Visit&& visit) const {
  if (nodes_.empty()) return;
  // Depth is bounded by the build (median splits): 64 levels cover any 32-bit triangle count.
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (!boxes_overlap(node.box, box)) continue;
    if (node.count > 0) {
      for (uint32_t k = node.first; k < node.first + node.count; ++k) {
        const uint32_t t = order_[k];
        if (boxes_overlap(tri_box_[t], box) && !visit(t)) return;
      }
    } else {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
    }
  }
}

template <class Visit>
void TriangleBVH::overlapping_pairs(Visit&& visit) const {
  if (nodes_.empty()) return;
  pairs_within(0, visit);
}

template <class Visit>
bool TriangleBVH::pairs_within(uint32_t n, Visit& visit) const {
  const Node& node = nodes_[n];
  if (node.count > 0) {
    for (uint32_t a = node.first; a < node.first + node.count; ++a) {
      for (uint32_t b = a + 1; b < node.first + node.count; ++b) {
        const uint32_t i = order_[a], j = order_[b];
        if (!boxes_overlap(tri_box_[i], tri_box_[j])) continue;
        if (!(i < j ? visit(i, j) : visit(j, i))) return false;
      }
    }
    return true;
  }
  return pairs_within(node.first, visit) && pairs_within(node.first + 1, visit) &&
         pairs_between(node.first, node.first + 1, visit);
}

template <class Visit>
bool TriangleBVH::pairs_between(uint32_t a, uint32_t b, Visit& visit) const {
  const Node& na = nodes_[a];
  const Node& nb = nodes_[b];
  if (!boxes_overlap(na.box, nb.box)) return true;
  if (na.count > 0 && nb.count > 0) {
    for (uint32_t x = na.first; x < na.first + na.count; ++x) {
      const uint32_t i = order_[x];
      const Box3& bi = tri_box_[i];
      if (!boxes_overlap(bi, nb.box)) continue;
      for (uint32_t y = nb.first; y < nb.first + nb.count; ++y) {
        const uint32_t j = order_[y];
        if (!boxes_overlap(bi, tri_box_[j])) continue;
        if (!(i < j ? visit(i, j) : visit(j, i))) return false;
      }
    }
    return true;
  }
  // Descend into the inner node (the larger box when both are inner).
  const bool split_a = nb.count > 0 || (na.count == 0 && bvh_detail::half_perimeter(na.box) >=
                                                             bvh_detail::half_perimeter(nb.box));
  if (split_a) {
    return pairs_between(na.first, b, visit) && pairs_between(na.first + 1, b, visit);
  }
  return pairs_between(a, nb.first, visit) && pairs_between(a, nb.first + 1, visit);
}

}  // namespace anitet

// A dynamic spatial index over boxes (the advancing front's triangles): a loose octree whose
// nodes live in a hash map (open addressing: FlatKeyMap), so that inserting and erasing are O(depth) and only occupied parts of
// space cost memory. Handles any mix of large and tiny boxes (CAD surfaces), unlike a uniform grid.
//
// An item whose box has extent e and centre c is stored in the deepest cell of size s >= e that
// contains c; the cell's loose box (the cell grown by s/2 on every side) then contains the item's
// box. A query descends only into nodes whose subtree holds items and whose loose box overlaps it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"  // Box3
#include "core/flat_key_map.hpp"

namespace anitet::layers {

class LooseOctree {
 public:
  static constexpr int kMaxDepth = 19;  // 19 bits per coordinate: key = level | x | y | z

  // Empties the index; the root cell is the cube that contains `bounds` (with a margin).
  void reset(const Box3& bounds);

  // Item ids are small integers chosen by the caller (dense: storage grows to the largest id).
  void insert(uint32_t id, const Box3& box);
  void erase(uint32_t id);
  size_t size() const { return num_items_; }

  // Calls visit(id) for every item whose loose cell overlaps `box` (a superset of the items
  // whose boxes overlap it: callers test their own boxes). visit returns false to stop.
  template <class Visit>
  void query(const Box3& box, Visit&& visit) const;

 private:
  struct Node {
    std::vector<uint32_t> items;
    uint32_t count = 0;     // items in this node's subtree
    uint8_t children = 0;   // bit c: child c exists in the map
  };
  static uint64_t make_key(int level, uint64_t x, uint64_t y, uint64_t z) {
    return (uint64_t(level) << 57) | (x << 38) | (y << 19) | z;
  }

  // The node of key k is nodes_[node_of_.find(k)]; nodes are never removed before reset().
  Node& node_at(uint64_t key) {
    const auto next = static_cast<uint32_t>(nodes_.size());
    const uint32_t i = node_of_.find_or_insert(key, next);
    if (i == next) nodes_.emplace_back();
    return nodes_[i];
  }
  FlatKeyMap node_of_;
  std::vector<Node> nodes_;
  std::vector<uint64_t> item_key_;  // per item id: its node, or kNoKey
  double origin_[3] = {0, 0, 0};
  double size_ = 1.0;  // root cell edge
  size_t num_items_ = 0;
  static constexpr uint64_t kNoKey = ~uint64_t(0);
};

template <class Visit>
void LooseOctree::query(const Box3& box, Visit&& visit) const {
  struct Frame {
    int level;
    uint64_t x, y, z;
  };
  Frame stack[8 * (kMaxDepth + 2)];
  int top = 0;
  stack[top++] = Frame{0, 0, 0, 0};
  while (top > 0) {
    const Frame f = stack[--top];
    const uint32_t index = node_of_.find(make_key(f.level, f.x, f.y, f.z));
    if (index == FlatKeyMap::kAbsent || nodes_[index].count == 0) continue;
    const double s = size_ / double(uint64_t(1) << f.level);
    const uint64_t c[3] = {f.x, f.y, f.z};
    bool overlap = true;
    for (int k = 0; k < 3 && overlap; ++k) {
      const double lo = origin_[k] + (double(c[k]) - 0.5) * s;
      const double hi = origin_[k] + (double(c[k]) + 1.5) * s;
      overlap = box.lo[k] <= hi && lo <= box.hi[k];
    }
    if (!overlap) continue;
    const Node& node = nodes_[index];
    for (uint32_t id : node.items)
      if (!visit(id)) return;
    if (f.level == kMaxDepth) continue;
    for (int ch = 0; ch < 8; ++ch) {
      if (!(node.children & (1u << ch))) continue;
      stack[top++] = Frame{f.level + 1, 2 * f.x + (ch & 1), 2 * f.y + ((ch >> 1) & 1),
                           2 * f.z + ((ch >> 2) & 1)};
    }
  }
}

}  // namespace anitet::layers

// A dynamic spatial index over boxes (the advancing front's triangles): a loose octree whose
// nodes hold the indices of their children and parent, so that inserting and erasing are
// O(depth), a query walks the tree without hashing, and only occupied parts of space cost memory.
// Handles any mix of large and tiny boxes (CAD surfaces), unlike a uniform grid.
//
// An item whose box has extent e and centre c is stored in the deepest cell of size s >= e that
// contains c; the cell's loose box (the cell grown by s/2 on every side) then contains the item's
// box. A query descends only into nodes whose subtree holds items and whose loose box overlaps it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"  // Box3

namespace anitet::layers {

class LooseOctree {
 public:
  static constexpr int kMaxDepth = 19;  // cell coordinates fit in 19 bits per axis

  // Empties the index; the root cell is the cube that contains `bounds` (with a margin).
  void reset(const Box3& bounds);

  // Item ids are small integers chosen by the caller (dense: storage grows to the largest id).
  void insert(uint32_t id, const Box3& box);
  void erase(uint32_t id);
  size_t size() const { return num_items_; }

  // Calls visit(id) for every item whose box overlaps `box` (closed boxes: touching counts).
  // visit returns false to stop.
  template <class Visit>
  void query(const Box3& box, Visit&& visit) const;

 private:
  static constexpr uint32_t kNoNode = 0xffffffffu;
  struct Node {
    uint32_t child[8] = {kNoNode, kNoNode, kNoNode, kNoNode,
                         kNoNode, kNoNode, kNoNode, kNoNode};
    uint32_t parent = kNoNode;
    uint32_t count = 0;  // items in this node's subtree
    std::vector<uint32_t> items;
    // Their boxes, beside them: a query tests them here, where reading each from the caller's array
    // by id was a cache miss per candidate.
    std::vector<Box3> boxes;
  };

  // Nodes are never removed before reset(); nodes_[0] is the root.
  std::vector<Node> nodes_;
  std::vector<uint32_t> item_node_;  // per item id: its node, or kNoNode
  double origin_[3] = {0, 0, 0};
  double size_ = 1.0;  // root cell edge
  size_t num_items_ = 0;
};

template <class Visit>
void LooseOctree::query(const Box3& box, Visit&& visit) const {
  struct Frame {
    uint32_t node;
    int level;
    uint32_t x, y, z;
  };
  // Whether the loose box of cell (x, y, z) at `level` overlaps the query box.
  auto overlaps = [&](int level, uint32_t x, uint32_t y, uint32_t z) {
    const double s = size_ / double(uint64_t(1) << level);
    const uint32_t c[3] = {x, y, z};
    for (int k = 0; k < 3; ++k) {
      const double lo = origin_[k] + (double(c[k]) - 0.5) * s;
      const double hi = origin_[k] + (double(c[k]) + 1.5) * s;
      if (!(box.lo[k] <= hi && lo <= box.hi[k])) return false;
    }
    return true;
  };
  Frame stack[8 * (kMaxDepth + 2)];
  int top = 0;
  if (overlaps(0, 0, 0, 0)) stack[top++] = Frame{0, 0, 0, 0, 0};
  while (top > 0) {
    const Frame f = stack[--top];
    const Node& node = nodes_[f.node];
    if (node.count == 0) continue;
    for (size_t k = 0; k < node.items.size(); ++k)
      if (boxes_overlap(node.boxes[k], box) && !visit(node.items[k])) return;
    // A child is tested before it is stacked: the test needs only its cell, and most children
    // of a small query miss it, so their nodes (cache misses) are never read. The same items
    // in the same order as testing each node when popped.
    for (int ch = 0; ch < 8; ++ch) {
      if (node.child[ch] == kNoNode) continue;
      const uint32_t x = 2 * f.x + (ch & 1), y = 2 * f.y + ((ch >> 1) & 1), z = 2 * f.z + ((ch >> 2) & 1);
      if (overlaps(f.level + 1, x, y, z)) stack[top++] = Frame{node.child[ch], f.level + 1, x, y, z};
    }
  }
}

}  // namespace anitet::layers

#include "layers/loose_octree.hpp"

#include <algorithm>
#include <cmath>

namespace anitet::layers {

void LooseOctree::reset(const Box3& bounds) {
  nodes_.assign(1, Node{});
  item_node_.clear();
  num_items_ = 0;
  double extent = 0.0;
  for (int k = 0; k < 3; ++k) extent = std::max(extent, bounds.hi[k] - bounds.lo[k]);
  if (!(extent > 0.0) || !std::isfinite(extent)) extent = 1.0;
  size_ = 1.0625 * extent;
  for (int k = 0; k < 3; ++k) {
    const double mid = 0.5 * (bounds.lo[k] + bounds.hi[k]);
    origin_[k] = std::isfinite(mid) ? mid - 0.5 * size_ : 0.0;
  }
}

void LooseOctree::insert(uint32_t id, const Box3& box) {
  if (nodes_.empty()) nodes_.assign(1, Node{});
  double extent = 0.0, centre[3];
  for (int k = 0; k < 3; ++k) {
    extent = std::max(extent, box.hi[k] - box.lo[k]);
    centre[k] = 0.5 * (box.lo[k] + box.hi[k]);
  }
  // The deepest level whose cell still holds the box inside its loose bounds.
  int level = 0;
  double s = size_;
  while (level < kMaxDepth && 0.5 * s >= extent) {
    s *= 0.5;
    ++level;
  }
  // Cell of the centre at that level, clamped (boxes outside the root still get a node: the
  // loose bounds then do not contain them, so queries near them may miss them; callers keep
  // every box inside the bounds given to reset).
  const uint64_t n = uint64_t(1) << level;
  uint64_t c[3];
  for (int k = 0; k < 3; ++k) {
    double f = std::floor((centre[k] - origin_[k]) / s);
    if (!(f >= 0.0)) f = 0.0;
    if (f > double(n - 1)) f = double(n - 1);
    c[k] = static_cast<uint64_t>(f);
  }
  // Create or follow the path from the root, counting the item in every node on it.
  uint32_t node = 0;
  ++nodes_[0].count;
  for (int l = 1; l <= level; ++l) {
    const int shift = level - l;
    const int ch = int((c[0] >> shift) & 1) | (int((c[1] >> shift) & 1) << 1) |
                   (int((c[2] >> shift) & 1) << 2);
    uint32_t next = nodes_[node].child[ch];
    if (next == kNoNode) {
      next = static_cast<uint32_t>(nodes_.size());
      nodes_.emplace_back();  // (invalidates references into nodes_)
      nodes_[next].parent = node;
      nodes_[node].child[ch] = next;
    }
    node = next;
    ++nodes_[node].count;
  }
  nodes_[node].items.push_back(id);
  nodes_[node].boxes.push_back(box);
  if (item_node_.size() <= id) item_node_.resize(size_t(id) + 1, kNoNode);
  item_node_[id] = node;
  ++num_items_;
}

void LooseOctree::erase(uint32_t id) {
  if (id >= item_node_.size() || item_node_[id] == kNoNode) return;
  uint32_t node = item_node_[id];
  item_node_[id] = kNoNode;
  --num_items_;
  std::vector<uint32_t>& items = nodes_[node].items;
  std::vector<Box3>& boxes = nodes_[node].boxes;
  auto it = std::find(items.begin(), items.end(), id);
  if (it != items.end()) {
    const size_t k = size_t(it - items.begin());
    *it = items.back();
    items.pop_back();
    boxes[k] = boxes.back();
    boxes.pop_back();
  }
  for (; node != kNoNode; node = nodes_[node].parent) --nodes_[node].count;
}

}  // namespace anitet::layers

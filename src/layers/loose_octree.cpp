#include "layers/loose_octree.hpp"

#include <algorithm>
#include <cmath>

namespace anitet::layers {

void LooseOctree::reset(const Box3& bounds) {
  node_of_.clear();
  nodes_.clear();
  item_key_.clear();
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
  // Create or update the path from the root, counting the item in every ancestor.
  for (int l = 0; l <= level; ++l) {
    const int shift = level - l;
    const uint64_t x = c[0] >> shift, y = c[1] >> shift, z = c[2] >> shift;
    Node& node = node_at(make_key(l, x, y, z));
    ++node.count;
    if (l < level) {
      const int ch = int((c[0] >> (shift - 1)) & 1) | (int((c[1] >> (shift - 1)) & 1) << 1) |
                     (int((c[2] >> (shift - 1)) & 1) << 2);
      node.children = uint8_t(node.children | (1u << ch));
    } else {
      node.items.push_back(id);
    }
  }
  if (item_key_.size() <= id) item_key_.resize(size_t(id) + 1, kNoKey);
  item_key_[id] = make_key(level, c[0], c[1], c[2]);
  ++num_items_;
}

void LooseOctree::erase(uint32_t id) {
  if (id >= item_key_.size() || item_key_[id] == kNoKey) return;
  const uint64_t key = item_key_[id];
  item_key_[id] = kNoKey;
  --num_items_;
  const int level = int(key >> 57);
  const uint64_t mask = (uint64_t(1) << 19) - 1;
  const uint64_t c[3] = {(key >> 38) & mask, (key >> 19) & mask, key & mask};
  for (int l = 0; l <= level; ++l) {
    const int shift = level - l;
    Node& node = node_at(make_key(l, c[0] >> shift, c[1] >> shift, c[2] >> shift));
    --node.count;
    if (l == level) {
      auto it = std::find(node.items.begin(), node.items.end(), id);
      if (it != node.items.end()) {
        *it = node.items.back();
        node.items.pop_back();
      }
    }
  }
}

}  // namespace anitet::layers

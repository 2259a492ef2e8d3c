// A hash map from 64-bit keys to 32-bit values with open addressing and linear probing: one
// array of keys and one of values, no node per entry. The spatial hashes of refinement's spacing
// grid and the layers' loose octree look up millions of cells; a node-based map's pointer chasing
// dominated both. Key ~0 is reserved (the empty slot); the load factor stays at most 1/2.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

class FlatKeyMap {
 public:
  static constexpr uint32_t kAbsent = ~0u;
  static constexpr uint64_t kEmptyKey = ~uint64_t(0);

  // k's value, or kAbsent.
  uint32_t find(uint64_t k) const {
    if (keys_.empty()) return kAbsent;
    for (size_t i = slot(k);; i = (i + 1) & mask_) {
      if (keys_[i] == k) return values_[i];
      if (keys_[i] == kEmptyKey) return kAbsent;
    }
  }
  // k's value slot, inserted holding `init` when k is new. The reference is valid until the next
  // insertion.
  uint32_t& find_or_insert(uint64_t k, uint32_t init) {
    if (2 * (count_ + 1) > keys_.size()) grow();
    for (size_t i = slot(k);; i = (i + 1) & mask_) {
      if (keys_[i] == k) return values_[i];
      if (keys_[i] == kEmptyKey) {
        keys_[i] = k;
        values_[i] = init;
        ++count_;
        return values_[i];
      }
    }
  }
  size_t size() const { return count_; }
  void clear() {
    keys_.clear();
    values_.clear();
    mask_ = count_ = 0;
  }

 private:
  size_t slot(uint64_t k) const { return static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> 32) & mask_; }
  void grow() {
    std::vector<uint64_t> keys(std::max<size_t>(1024, 2 * keys_.size()), kEmptyKey);
    std::vector<uint32_t> values(keys.size(), kAbsent);
    keys.swap(keys_);
    values.swap(values_);
    mask_ = keys_.size() - 1;
    for (size_t j = 0; j < keys.size(); ++j) {
      if (keys[j] == kEmptyKey) continue;
      size_t i = slot(keys[j]);
      while (keys_[i] != kEmptyKey) i = (i + 1) & mask_;
      keys_[i] = keys[j];
      values_[i] = values[j];
    }
  }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t mask_ = 0, count_ = 0;
};

}  // namespace anitet

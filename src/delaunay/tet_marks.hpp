// Per-insertion marks on tets ("in the cavity", "tested, not in conflict") kept in a small
// open-addressing table instead of in the mesh: a mark costs no access to the mesh's flag array
// (a cache miss per neighbour on large meshes), and a new insertion clears all marks at once by
// bumping a generation counter (internal header).
#pragma once

#include <cstdint>
#include <vector>

namespace anitet::delaunay_detail {

class TetMarks {
 public:
  static constexpr uint32_t kNone = 0, kIn = 1, kOut = 2;

  TetMarks() { resize(1024); }

  // Forgets every mark.
  void clear() {
    count_ = 0;
    if (++generation_ == kGenerations) {
      std::fill(slots_.begin(), slots_.end(), 0);
      generation_ = 1;
    }
  }

  uint32_t get(uint32_t t) const {
    for (size_t h = hash(t);; h = (h + 1) & mask_) {
      const uint64_t e = slots_[h];
      if ((e >> 34) != generation_) return kNone;
      if (static_cast<uint32_t>(e) == t) return static_cast<uint32_t>(e >> 32) & 3u;
    }
  }

  void set(uint32_t t, uint32_t mark) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    for (size_t h = hash(t);; h = (h + 1) & mask_) {
      const uint64_t e = slots_[h];
      const bool empty = (e >> 34) != generation_;
      if (empty || static_cast<uint32_t>(e) == t) {
        slots_[h] = (generation_ << 34) | (uint64_t(mark) << 32) | t;
        count_ += empty;
        return;
      }
    }
  }

 private:
  static constexpr uint64_t kGenerations = uint64_t(1) << 30;

  size_t hash(uint32_t t) const { return (uint32_t(t * 0x9E3779B1u) >> shift_) & mask_; }

  void resize(size_t capacity) {
    slots_.assign(capacity, 0);
    mask_ = capacity - 1;
    shift_ = 32;
    for (size_t c = capacity; c > 1; c >>= 1) --shift_;
  }

  void grow() {
    std::vector<uint64_t> old;
    old.swap(slots_);
    const uint64_t generation = generation_;
    resize(2 * old.size());
    generation_ = 1;
    count_ = 0;
    for (uint64_t e : old)
      if ((e >> 34) == generation) set(static_cast<uint32_t>(e), static_cast<uint32_t>(e >> 32) & 3u);
  }

  std::vector<uint64_t> slots_;
  size_t mask_ = 0;
  int shift_ = 32;
  size_t count_ = 0;
  uint64_t generation_ = 1;
};

}  // namespace anitet::delaunay_detail

// The cavity kernel's view of a TetMesh's tet arrays (internal header): vertices, half-face
// adjacency, flags and regions, the bulk build's per-insertion marks ("in cavity", "tested") in
// tet_flags bits 14 and 13, slot recycling through the free list, and prefetch hints.
//
// (A compact 32-byte-per-tet layout was tried for the bulk build: its insertion loop ran ~10%
// faster, but converting it to a TetMesh at the end cost as much, and it raised peak memory.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"

namespace anitet::delaunay_detail {


constexpr uint32_t kMarkIn = 1;   // in the current cavity
constexpr uint32_t kMarkOut = 2;  // tested, not in conflict

// The slots one task of the parallel bulk build may fill: its own free list and a range of slots
// appended for it before the task starts (the arrays are never resized while tasks run).
struct SlotPool {
  std::vector<uint32_t> free;
  uint32_t next = 0, end = 0;
};

class TetStorage {
 public:
  explicit TetStorage(TetMesh& mesh, SlotPool* pool = nullptr) : mesh_(&mesh), pool_(pool) { refresh(); }

  size_t num_slots() const { return mesh_->num_tet_slots(); }
  uint32_t* verts(uint32_t t) { return tv_ + 4 * size_t(t); }
  const uint32_t* verts(uint32_t t) const { return tv_ + 4 * size_t(t); }
  uint32_t adj(uint32_t t, int i) const { return ta_[4 * size_t(t) + i]; }
  void set_adj(uint32_t half_face, uint32_t value) { ta_[half_face] = value; }
  uint16_t flags(uint32_t t) const { return tf_[t]; }
  int32_t region(uint32_t t) const { return tr_[t]; }
  // A slot becomes a live tet with these flags and region (marks cleared).
  void init_tet(uint32_t t, uint16_t flags, int32_t region) {
    tf_[t] = flags;
    tr_[t] = region;
  }
  // Same, keeping the slot's region.
  void clear_flags(uint32_t t) { tf_[t] = 0; }

  // Marks live in tet_flags bits 14 (in) and 13 (out).
  uint32_t mark(uint32_t t) const { return (tf_[t] >> 13) & 3u; }
  void set_mark(uint32_t t, uint32_t m) { tf_[t] = static_cast<uint16_t>((tf_[t] & ~kMarkBits) | (m << 13)); }
  void clear_mark(uint32_t t) { tf_[t] &= static_cast<uint16_t>(~kMarkBits); }

  bool deleted(uint32_t t) const { return (tf_[t] & tflag::kDeleted) != 0; }
  void release(uint32_t t) {
    tf_[t] = tflag::kDeleted;
    free_list().push_back(t);
  }
  bool reuse_free(uint32_t& t) {
    std::vector<uint32_t>& free = free_list();
    if (free.empty()) return false;
    t = free.back();
    free.pop_back();
    return true;
  }
  // Whether `count` more slots than the cavity frees are available (always, without a pool).
  bool can_take(size_t count) const {
    return !pool_ || count <= pool_->free.size() + size_t(pool_->end - pool_->next);
  }
  // Appends `count` unset slots (with a pool: takes them from its range, can_take() said yes);
  // returns the first.
  uint32_t append(size_t count) {
    if (pool_) {
      const uint32_t first = pool_->next;
      pool_->next += static_cast<uint32_t>(count);
      return first;
    }
    const size_t first = num_slots();
    mesh_->tet_v.resize(4 * (first + count));
    mesh_->tet_adj.resize(4 * (first + count));
    mesh_->tet_flags.resize(first + count);
    mesh_->tet_region.resize(first + count);
    refresh();
    return static_cast<uint32_t>(first);
  }

  void prefetch_tet(uint32_t t) const {
    __builtin_prefetch(tv_ + 4 * size_t(t));
    __builtin_prefetch(tf_ + t);
  }
  void prefetch_adj(uint32_t t) const { __builtin_prefetch(ta_ + 4 * size_t(t)); }

 private:
  static constexpr uint16_t kMarkBits = 3u << 13;
  std::vector<uint32_t>& free_list() { return pool_ ? pool_->free : mesh_->free_tets; }
  void refresh() {
    tv_ = mesh_->tet_v.data();
    ta_ = mesh_->tet_adj.data();
    tf_ = mesh_->tet_flags.data();
    tr_ = mesh_->tet_region.data();
  }

  TetMesh* mesh_;
  SlotPool* pool_;
  uint32_t* tv_ = nullptr;
  uint32_t* ta_ = nullptr;
  uint16_t* tf_ = nullptr;
  int32_t* tr_ = nullptr;
};

}  // namespace anitet::delaunay_detail

#include "io/vertex_merger.hpp"

#include <cstring>

namespace anitet {

namespace {

inline uint64_t key_bits(double v) {
  if (v == 0.0) return 0;  // -0.0 and +0.0 are the same point
  uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

inline uint64_t mix(uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

}  // namespace

ExactVertexMerger::ExactVertexMerger(std::vector<double>& xyz, size_t expected_points) : xyz_(xyz) {
  size_t capacity = 64;
  while (capacity < 2 * expected_points) capacity *= 2;
  table_.assign(capacity, 0);
  mask_ = capacity - 1;
}

size_t ExactVertexMerger::slot_of(const uint64_t key[3]) const {
  uint64_t h = mix(key[0] ^ mix(key[1] ^ mix(key[2])));
  return static_cast<size_t>(h) & mask_;
}

uint32_t ExactVertexMerger::insert(double x, double y, double z) {
  const uint64_t key[3] = {key_bits(x), key_bits(y), key_bits(z)};
  size_t slot = slot_of(key);
  for (;;) {
    uint32_t entry = table_[slot];
    if (entry == 0) break;
    const double* p = &xyz_[3 * (entry - 1)];
    if (key_bits(p[0]) == key[0] && key_bits(p[1]) == key[1] && key_bits(p[2]) == key[2]) {
      return entry - 1;
    }
    slot = (slot + 1) & mask_;
  }
  uint32_t index = static_cast<uint32_t>(xyz_.size() / 3);
  xyz_.push_back(x);
  xyz_.push_back(y);
  xyz_.push_back(z);
  table_[slot] = index + 1;
  if (++count_ * 2 > table_.size()) grow();
  return index;
}

void ExactVertexMerger::grow() {
  std::vector<uint32_t> old;
  old.swap(table_);
  table_.assign(old.size() * 2, 0);
  mask_ = table_.size() - 1;
  for (uint32_t entry : old) {
    if (entry == 0) continue;
    const double* p = &xyz_[3 * (entry - 1)];
    const uint64_t key[3] = {key_bits(p[0]), key_bits(p[1]), key_bits(p[2])};
    size_t slot = slot_of(key);
    while (table_[slot] != 0) slot = (slot + 1) & mask_;
    table_[slot] = entry;
  }
}

}  // namespace anitet

// Merges points with exactly equal coordinates (STL stores every triangle corner separately).
// Equality is bitwise after mapping -0.0 to +0.0, so no two distinct points are ever merged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

class ExactVertexMerger {
 public:
  // Appends new points to `xyz` (3 per point); `expected_points` sizes the table.
  ExactVertexMerger(std::vector<double>& xyz, size_t expected_points);

  // The index of the point (x, y, z), added to `xyz` if not seen before.
  uint32_t insert(double x, double y, double z);

 private:
  void grow();
  size_t slot_of(const uint64_t key[3]) const;

  std::vector<double>& xyz_;
  std::vector<uint32_t> table_;  // vertex index + 1, 0 = empty; open addressing, linear probing
  size_t mask_ = 0;
  size_t count_ = 0;
};

}  // namespace anitet

// Insertion order for the incremental Delaunay kernel: a biased randomized insertion order (BRIO,
// Amenta, Choi & Rote 2003) whose rounds are each sorted along a Hilbert curve, so consecutive
// points are close in space (short walks, warm caches) while the rounds keep the randomization
// that bounds the expected amount of work. Deterministic: same input and seed, same order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet::delaunay_detail {

// Position along the 3D Hilbert curve of the cell (x, y, z) of a 2^bits grid (bits in 1..21).
// Consecutive positions are face-adjacent cells.
uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits);

// A splitmix64 stream: a portable, deterministic source of random bits.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform-enough integer in [0, bound), bound < 2^32.
  uint32_t below(uint32_t bound) { return static_cast<uint32_t>(((next() >> 32) * bound) >> 32); }

 private:
  uint64_t state_;
};

struct BrioOptions {
  uint64_t seed = 0x5eed;
  // Rounds from the last: the last holds (1 - ratio) of the points, the one before (1 - ratio)
  // of the rest, and so on, down to a first round of at most min_round points.
  double ratio = 0.25;
  size_t min_round = 1024;
};

// The insertion order of the n points xyz[3i..3i+2]: a permutation of 0..n-1. round_begin, when
// given, receives the position in it where each round starts (first round first).
std::vector<uint32_t> brio_order(const double* xyz, size_t n, const BrioOptions& options,
                                 std::vector<size_t>* round_begin = nullptr);

// Sorts order[0..count) by the Hilbert position of their points inside the box lo..hi.
void hilbert_sort(const double* xyz, uint32_t* order, size_t count, const double lo[3],
                  const double hi[3]);

}  // namespace anitet::delaunay_detail

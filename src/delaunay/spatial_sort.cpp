#include "delaunay/spatial_sort.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace anitet::delaunay_detail {

namespace {

// Spreads the low 21 bits of x so that bit i lands on bit 3i.
uint64_t spread_by_3(uint64_t x) {
  x &= 0x1fffff;
  x = (x | (x << 32)) & 0x001f00000000ffffull;
  x = (x | (x << 16)) & 0x001f0000ff0000ffull;
  x = (x | (x << 8)) & 0x100f00f00f00f00full;
  x = (x | (x << 4)) & 0x10c30c30c30c30c3ull;
  x = (x | (x << 2)) & 0x1249249249249249ull;
  return x;
}

struct KeyedIndex {
  uint64_t key;
  uint32_t index;
};

// LSD radix sort on the low key_bits bits of the keys, 11 bits per pass; stable.
void radix_sort(std::vector<KeyedIndex>& items, std::vector<KeyedIndex>& scratch, int key_bits) {
  constexpr int kDigitBits = 11;
  constexpr size_t kBuckets = size_t(1) << kDigitBits;
  scratch.resize(items.size());
  std::vector<size_t> count(kBuckets);
  for (int shift = 0; shift < key_bits; shift += kDigitBits) {
    std::fill(count.begin(), count.end(), 0);
    for (const KeyedIndex& it : items) ++count[(it.key >> shift) & (kBuckets - 1)];
    // A pass whose digit is the same for every item leaves the order unchanged.
    if (std::count(count.begin(), count.end(), items.size()) == 1) continue;
    size_t sum = 0;
    for (size_t& c : count) {
      const size_t here = c;
      c = sum;
      sum += here;
    }
    for (const KeyedIndex& it : items) scratch[count[(it.key >> shift) & (kBuckets - 1)]++] = it;
    items.swap(scratch);
  }
}

int bits_for_count(size_t count) {
  int log2 = 0;
  while ((size_t(1) << log2) < count && log2 < 63) ++log2;
  return std::clamp((log2 + 2) / 3 + 2, 2, 21);
}

}  // namespace

uint64_t hilbert_index(uint32_t x, uint32_t y, uint32_t z, int bits) {
  // Skilling's transform ("Programming the Hilbert curve", 2004): axes to the transposed index,
  // then interleave the three words most significant bit first.
  uint32_t X[3] = {x, y, z};
  const uint32_t top = 1u << (bits - 1);
  for (uint32_t q = top; q > 1; q >>= 1) {
    const uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (X[i] & q) {
        X[0] ^= p;
      } else {
        const uint32_t t = (X[0] ^ X[i]) & p;
        X[0] ^= t;
        X[i] ^= t;
      }
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  uint32_t t = 0;
  for (uint32_t q = top; q > 1; q >>= 1)
    if (X[2] & q) t ^= q - 1;
  for (uint32_t& w : X) w ^= t;
  return (spread_by_3(X[0]) << 2) | (spread_by_3(X[1]) << 1) | spread_by_3(X[2]);
}

namespace {

void bounding_box(const double* xyz, size_t n, double lo[3], double hi[3]) {
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = xyz[d];
  for (size_t i = 1; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], xyz[3 * i + d]);
      hi[d] = std::max(hi[d], xyz[3 * i + d]);
    }
}

// Hilbert positions of points (indices[k] or k) in the box lo..hi, on a 2^bits grid.
void hilbert_keys(const double* xyz, const uint32_t* indices, size_t count, const double lo[3],
                  const double hi[3], int bits, std::vector<KeyedIndex>& items) {
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double cells = double(uint32_t(1) << bits);
  const double scale = extent > 0 ? cells / extent : 0.0;
  const auto max_cell = static_cast<uint32_t>(cells) - 1;
  items.resize(count);
  // On every core for large sets (the keys do not depend on how the range is cut).
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 1 << 15), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t k = range.begin(); k < range.end(); ++k) {
      const uint32_t index = indices ? indices[k] : static_cast<uint32_t>(k);
      const double* p = xyz + 3 * size_t(index);
      uint32_t c[3];
      for (int d = 0; d < 3; ++d) {
        const double f = (p[d] - lo[d]) * scale;
        c[d] = f <= 0 ? 0u : std::min(max_cell, static_cast<uint32_t>(f));
      }
      items[k] = {hilbert_index(c[0], c[1], c[2], bits), index};
    }
  });
}

}  // namespace

void hilbert_sort(const double* xyz, uint32_t* order, size_t count, const double lo[3],
                  const double hi[3]) {
  if (count < 2) return;
  const int bits = bits_for_count(count);
  std::vector<KeyedIndex> items, scratch;
  hilbert_keys(xyz, order, count, lo, hi, bits, items);
  radix_sort(items, scratch, 3 * bits);
  for (size_t k = 0; k < count; ++k) order[k] = items[k].index;
}

std::vector<uint32_t> brio_order(const double* xyz, size_t n, const BrioOptions& options,
                                 std::vector<size_t>* round_begin_out) {
  std::vector<uint32_t> order(n);
  if (n == 0) return order;
  double lo[3], hi[3];
  bounding_box(xyz, n, lo, hi);

  // One Hilbert sort of all the points; a stable partition by round then leaves every round
  // sorted along the curve.
  const int bits = bits_for_count(n);
  std::vector<KeyedIndex> items, scratch;
  hilbert_keys(xyz, nullptr, n, lo, hi, bits, items);
  radix_sort(items, scratch, 3 * bits);

  // Round sizes from the last one backwards: the last holds (1 - ratio) of the points, and so on
  // down to a first round of at most min_round points.
  const double ratio = std::clamp(options.ratio, 0.0, 0.95);
  std::vector<size_t> round_begin;  // from the last round to the first
  for (size_t end = n; end > 0;) {
    size_t begin = static_cast<size_t>(double(end) * ratio);
    if (end <= std::max<size_t>(options.min_round, 1)) begin = 0;
    round_begin.push_back(begin);
    end = begin;
  }
  std::reverse(round_begin.begin(), round_begin.end());  // first round first
  const size_t rounds = round_begin.size();

  // Deal the round slots out at random: slot k of a random permutation of 0..n-1 goes to the
  // round containing position k. Fisher-Yates with our own generator (std::shuffle differs
  // between standard libraries).
  std::vector<uint32_t> round_of(n);
  {
    std::vector<uint32_t> perm(n);
    for (size_t i = 0; i < n; ++i) perm[i] = static_cast<uint32_t>(i);
    SplitMix64 rng(options.seed);
    for (size_t i = n - 1; i > 0; --i) std::swap(perm[i], perm[rng.below(static_cast<uint32_t>(i + 1))]);
    size_t r = 0;
    for (size_t k = 0; k < n; ++k) {
      while (r + 1 < rounds && k >= round_begin[r + 1]) ++r;
      round_of[perm[k]] = static_cast<uint32_t>(r);
    }
  }
  std::vector<size_t> next(round_begin.begin(), round_begin.end());
  for (const KeyedIndex& it : items) order[next[round_of[it.index]]++] = it.index;
  // Every other round runs the curve backwards, so that each round starts near where the
  // previous one ended (short walks between rounds).
  for (size_t r = 0; r < rounds; ++r) {
    if ((rounds - 1 - r) % 2 == 0) continue;
    const size_t end = r + 1 < rounds ? round_begin[r + 1] : n;
    std::reverse(order.begin() + static_cast<ptrdiff_t>(round_begin[r]),
                 order.begin() + static_cast<ptrdiff_t>(end));
  }
  if (round_begin_out) *round_begin_out = round_begin;
  return order;
}

}  // namespace anitet::delaunay_detail

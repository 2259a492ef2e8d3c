#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <cstdint>
#include <random>
#include <vector>

#include "core/buckets.hpp"

namespace anitet {
namespace {

// Sources with 0-3 items each, random keys: parallel_bucket_by_key gives bucket_by_key's buckets
// (same starts, same values in the same order) on one thread and on two, with enough sources
// for several ranges, and with few (one range) or none.
TEST(Buckets, ParallelBucketsAreTheSequentialOnes) {
  for (size_t sources : {size_t(0), size_t(100), size_t(200000)}) {
    const size_t keys = 5000;
    std::mt19937 rng(uint32_t(sources + 1));
    std::vector<uint32_t> item_count(sources), item_key, item_first(sources + 1, 0);
    for (size_t s = 0; s < sources; ++s) {
      item_count[s] = rng() % 4;
      item_first[s + 1] = item_first[s] + item_count[s];
      for (uint32_t k = 0; k < item_count[s]; ++k) item_key.push_back(rng() % keys);
    }
    // Value: the item's index, so that the order inside each bucket shows.
    auto emit_range = [&](size_t first, size_t last, auto&& emit) {
      for (size_t s = first; s < last; ++s)
        for (uint32_t i = item_first[s]; i < item_first[s + 1]; ++i) emit(item_key[i], i);
    };
    std::vector<uint32_t> start, values, fill;
    bucket_by_key(keys, [&](auto&& emit) { emit_range(0, sources, emit); }, start, values, fill);
    for (int threads : {1, 2}) {
      tbb::global_control arena(tbb::global_control::max_allowed_parallelism, size_t(threads));
      std::vector<uint32_t> pstart, pvalues, counts;
      parallel_bucket_by_key(keys, sources, emit_range, pstart, pvalues, counts);
      EXPECT_EQ(pstart, start) << sources << " sources, " << threads << " threads";
      EXPECT_EQ(pvalues, values) << sources << " sources, " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace anitet

#include "core/flat_key_map.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <unordered_map>

namespace anitet {
namespace {

TEST(FlatKeyMap, AgreesWithUnorderedMapThroughGrowth) {
  FlatKeyMap map;
  std::unordered_map<uint64_t, uint32_t> ref;
  EXPECT_EQ(map.find(42), FlatKeyMap::kAbsent);  // empty, before any allocation
  uint64_t x = 0x1234567;
  for (uint32_t i = 0; i < 50000; ++i) {
    // Keys clustered like cell keys (many share high bits), some repeated.
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    const uint64_t k = (uint64_t(i % 7) << 57) | ((x >> 20) & 0xffff);
    uint32_t& v = map.find_or_insert(k, i);
    auto [it, fresh] = ref.try_emplace(k, i);
    EXPECT_EQ(v, it->second);
    if (!fresh && i % 3 == 0) v = it->second = i;  // overwrite through the returned slot
  }
  EXPECT_EQ(map.size(), ref.size());
  for (const auto& [k, v] : ref) EXPECT_EQ(map.find(k), v);
  EXPECT_EQ(map.find(uint64_t(7) << 57), FlatKeyMap::kAbsent);
  map.clear();
  EXPECT_EQ(map.size(), 0u);
  EXPECT_EQ(map.find(ref.begin()->first), FlatKeyMap::kAbsent);
}

}  // namespace
}  // namespace anitet

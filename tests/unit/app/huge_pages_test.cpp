// app/huge_pages.cpp: large blocks from the arena never overlap, are huge-page aligned, are
// reused for later requests of any smaller size, and the resident memory stays within the live
// blocks' peak. (Under the sanitizers the file replaces nothing: these tests are skipped.)
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define ANITET_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ANITET_TEST_SANITIZED 1
#endif

namespace {

constexpr size_t kMiB = size_t(1) << 20;
constexpr size_t kHugePage = 2 * kMiB;

bool replaced() {
#if defined(__linux__) && !defined(ANITET_TEST_SANITIZED)
  return true;
#else
  return false;
#endif
}

// Resident memory of this process, from /proc/self/statm.
size_t resident_bytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long size = 0, resident = 0;
  const int got = std::fscanf(f, "%lu %lu", &size, &resident);
  std::fclose(f);
  return got == 2 ? size_t(resident) * size_t(sysconf(_SC_PAGE_SIZE)) : 0;
}

struct Block {
  char* p;
  size_t size;
  uint64_t tag;
};

// Writes the tag every 64 KiB (and in the last bytes), so that each page of the block is touched.
void stamp(const Block& b) {
  for (size_t at = 0; at + 8 <= b.size; at += 64 * 1024) std::memcpy(b.p + at, &b.tag, 8);
  std::memcpy(b.p + b.size - 8, &b.tag, 8);
}
bool intact(const Block& b) {
  uint64_t x;
  for (size_t at = 0; at + 8 <= b.size; at += 64 * 1024) {
    std::memcpy(&x, b.p + at, 8);
    if (x != b.tag) return false;
  }
  std::memcpy(&x, b.p + b.size - 8, 8);
  return x == b.tag;
}

Block make(size_t size, uint64_t tag) {
  Block b{new char[size], size, tag};
  stamp(b);
  return b;
}

// First in the file: the arena's peak is the process's (ctest runs each test alone anyway).
TEST(HugePages, ResidentMemoryStaysWithinTheLivePeak) {
  if (!replaced()) GTEST_SKIP() << "operator new not replaced here";
  const size_t before = resident_bytes();
  ASSERT_GT(before, size_t(0));
  // A live peak of 128 MiB, then many rounds of blocks of new sizes with at most 96 MiB live:
  // without handing free blocks back, the freed ones would pile up.
  std::vector<Block> live;
  for (int k = 0; k < 8; ++k) live.push_back(make(16 * kMiB, uint64_t(k)));
  for (Block& b : live) delete[] b.p;
  live.clear();
  size_t most = 0;
  std::mt19937_64 rng(3);
  for (int round = 0; round < 60; ++round) {
    size_t total = 0;
    while (total < 96 * kMiB) {
      const size_t size = std::min(96 * kMiB - total, kHugePage * (1 + rng() % 20));
      if (size < kHugePage) break;
      live.push_back(make(size, uint64_t(round)));
      total += size;
    }
    most = std::max(most, resident_bytes());
    for (Block& b : live) {
      EXPECT_TRUE(intact(b));
      delete[] b.p;
    }
    live.clear();
  }
  // 128 MiB of peak, and some slack for the test's own small allocations.
  EXPECT_LE(most, before + 128 * kMiB + 16 * kMiB);
}

// A large block touched only in part (a reserved array) does not count towards the peak as a
// whole: the free blocks are not kept resident beside it up to its size, so that when it is
// touched in full later the process holds that block, not that block and the free ones too.
TEST(HugePages, AnUntouchedReservationDoesNotKeepFreeBlocksResident) {
  if (!replaced()) GTEST_SKIP() << "operator new not replaced here";
  const size_t before = resident_bytes();
  ASSERT_GT(before, size_t(0));
  Block reserved{new char[256 * kMiB], 256 * kMiB, 7};
  std::memset(reserved.p, 1, 32 * kMiB);  // 32 MiB of it in use
  std::vector<Block> live;
  for (int k = 0; k < 8; ++k) live.push_back(make(16 * kMiB, uint64_t(k)));  // 160 MiB in use at most
  for (Block& b : live) delete[] b.p;
  stamp(reserved);  // now all of it: 256 MiB in use
  const size_t most = resident_bytes();
  EXPECT_TRUE(intact(reserved));
  delete[] reserved.p;
  // 256 MiB of peak (the 128 MiB freed before are not kept beside it), and some slack.
  EXPECT_LE(most, before + 256 * kMiB + 16 * kMiB);
}

TEST(HugePages, BlocksAreAlignedAndNeverOverlapAcrossThreads) {
  if (!replaced()) GTEST_SKIP() << "operator new not replaced here";
  bool ok[2] = {true, true};
  auto work = [&ok](int id) {
    std::mt19937_64 rng(uint64_t(id) + 7);
    std::vector<Block> live;
    uint64_t tag = uint64_t(id) << 40;
    for (int step = 0; step < 400; ++step) {
      if (live.size() < 8 && (live.empty() || rng() % 3 != 0)) {
        const size_t size = kHugePage + rng() % (24 * kMiB);  // not a whole number of pages
        Block b = make(size, ++tag);
        if (reinterpret_cast<uintptr_t>(b.p) % kHugePage != 0) ok[id] = false;
        live.push_back(b);
      } else {
        const size_t k = rng() % live.size();
        if (!intact(live[k])) ok[id] = false;
        delete[] live[k].p;
        live.erase(live.begin() + long(k));
      }
      for (const Block& b : live)
        if (!intact(b)) ok[id] = false;
    }
    for (const Block& b : live) {
      if (!intact(b)) ok[id] = false;
      delete[] b.p;
    }
  };
  std::thread other(work, 1);
  work(0);
  other.join();
  EXPECT_TRUE(ok[0]);
  EXPECT_TRUE(ok[1]);
}

// Reuse shows as memory that does not grow: the freed block's pages (or another free block's)
// serve the smaller requests instead of fresh ones.
TEST(HugePages, FreedBlockServesSmallerRequests) {
  if (!replaced()) GTEST_SKIP() << "operator new not replaced here";
  Block big = make(64 * kMiB, 1);
  delete[] big.p;
  const size_t before = resident_bytes();
  Block small = make(20 * kMiB, 2), second = make(30 * kMiB, 3);
  const size_t after = resident_bytes();
  EXPECT_LE(after, before + 4 * kMiB);
  EXPECT_TRUE(intact(small));
  delete[] small.p;
  delete[] second.p;
}

}  // namespace

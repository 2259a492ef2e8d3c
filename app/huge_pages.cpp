// The command-line tool's allocations of 2 MiB and more go on transparent huge pages (when the
// kernel offers them on request, "madvise" mode, as on Debian's default and on this project's
// machines). The mesher's flat arrays are hundreds of MB on large meshes, and each 4 KiB page
// costs a fault when first touched; on the paravirtualized machines here those faults were a
// fifth of armadillo's run (22.9 and 27.0 s against 18.9 and 19.3 s with this file, run
// alternately; glibc's glibc.malloc.hugetlb=1 tunable gave 18.2 and 23.9 s; the same meshes).
// Peak memory grows a little (armadillo 585 -> 646 MB): whole huge pages.
//
// Freed blocks of 2 MiB and more are kept for reuse (a request of up to 1.5 times smaller takes
// one): first touches of fresh huge pages cost about 0.4 ms per MiB here (the kernel zeroes
// them), and each refinement pass and the report free and allocate again arrays of the same
// sizes (armadillo: 975 huge-page faults per run, 695 with the cache, 0.3-0.8 s less). The cache
// holds at most 256 MiB, and never so much that cached and live blocks together exceed the
// largest total the live ones have reached: the peak memory stays what it was.
//
// Only the executable replaces the global operator new: the library (and so the C ABI and the
// Python binding) leaves allocation to its host. Not under the sanitizers, whose own operator new
// checks new/delete pairing.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define ANITET_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define ANITET_SANITIZED 1
#endif

#if defined(__linux__) && !defined(ANITET_SANITIZED)

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t(1) << 21;
constexpr std::size_t kCacheCap = std::size_t(256) << 20;

struct Block {
  void* p;
  std::size_t size;
};

// The blocks of 2 MiB and more, live and cached, in fixed tables (no allocation under the lock:
// operator new must not call itself). A block the live table has no room for is not cached.
class HugeBlocks {
 public:
  // A cached block of at least `size` bytes and at most 1.5 times as many (the smallest), or null.
  void* reuse(std::size_t size) {
    std::lock_guard<std::mutex> hold(lock_);
    std::size_t best = cached_n_;
    for (std::size_t i = 0; i < cached_n_; ++i)
      if (cached_[i].size >= size && cached_[i].size <= size + size / 2 &&
          (best == cached_n_ || cached_[i].size < cached_[best].size))
        best = i;
    if (best == cached_n_ || live_n_ == kLive) return nullptr;
    const Block b = cached_[best];
    std::copy(cached_ + best + 1, cached_ + cached_n_, cached_ + best);
    --cached_n_;
    cached_bytes_ -= b.size;
    add_live(b);
    return b.p;
  }
  // A fresh block of `size` bytes: the cache first gives back what would raise the peak.
  void* fresh(std::size_t size) {
    std::unique_lock<std::mutex> hold(lock_);
    const std::size_t live_after = live_bytes_ + size;
    const std::size_t peak = std::max(peak_live_, live_after);
    evict_while([&] { return live_after + cached_bytes_ > peak; });
    hold.unlock();
    void* p = std::aligned_alloc(kHugePage, size);
    if (p == nullptr) return nullptr;
    madvise(p, size, MADV_HUGEPAGE);  // advice only: a refusal leaves ordinary pages
    hold.lock();
    if (live_n_ < kLive) add_live({p, size});
    return p;
  }
  // Whether p was a live block here (then it is cached or freed).
  bool release(void* p) {
    std::lock_guard<std::mutex> hold(lock_);
    for (std::size_t i = live_n_; i-- > 0;) {
      if (live_[i].p != p) continue;
      const Block b = live_[i];
      live_[i] = live_[--live_n_];
      live_bytes_ -= b.size;
      if (cached_n_ == kCached) evict_while([&] { return cached_n_ == kCached; });
      cached_[cached_n_++] = b;
      cached_bytes_ += b.size;
      evict_while([&] { return cached_bytes_ > kCacheCap; });
      return true;
    }
    return false;
  }

 private:
  static constexpr std::size_t kLive = 4096, kCached = 256;
  void add_live(const Block& b) {
    live_[live_n_++] = b;
    live_bytes_ += b.size;
    peak_live_ = std::max(peak_live_, live_bytes_);
  }
  // Frees the oldest cached blocks while `more` says so.
  template <class F>
  void evict_while(F&& more) {
    while (cached_n_ > 0 && more()) {
      std::free(cached_[0].p);
      cached_bytes_ -= cached_[0].size;
      std::copy(cached_ + 1, cached_ + cached_n_, cached_);
      --cached_n_;
    }
  }
  std::mutex lock_;
  Block live_[kLive];
  Block cached_[kCached];
  std::size_t live_n_ = 0, cached_n_ = 0;
  std::size_t live_bytes_ = 0, cached_bytes_ = 0, peak_live_ = 0;
};

// Never destroyed: operator delete may run after static destructors.
HugeBlocks& huge_blocks() {
  static HugeBlocks* blocks = new (std::malloc(sizeof(HugeBlocks))) HugeBlocks();
  return *blocks;
}

void* allocate(std::size_t n) {
  if (n >= kHugePage) {
    const std::size_t rounded = (n + kHugePage - 1) & ~(kHugePage - 1);
    if (void* p = huge_blocks().reuse(rounded)) return p;
    if (void* p = huge_blocks().fresh(rounded)) return p;
  } else if (void* p = std::malloc(n > 0 ? n : 1)) {
    return p;
  }
  throw std::bad_alloc();
}

void release(void* p) noexcept {
  // Only a 2 MiB-aligned pointer can be a huge block (malloc's small blocks rarely are).
  if (p != nullptr && (reinterpret_cast<std::uintptr_t>(p) & (kHugePage - 1)) == 0 && huge_blocks().release(p))
    return;
  std::free(p);
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }

#endif

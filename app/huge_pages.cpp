// The command-line tool's allocations of 2 MiB and more go on transparent huge pages (when the
// kernel offers them on request, "madvise" mode, as on Debian's default and on this project's
// machines). The mesher's flat arrays are hundreds of MB on large meshes, and each 4 KiB page
// costs a fault when first touched; on paravirtualized machines those faults are a large share of
// a run.
//
// They come from one reserved range of address space (an arena), in whole 2 MiB pages, and a
// freed block stays in it, resident, for any later request it can hold (split, or merged with
// its free neighbours): a first touch of a fresh huge page costs about 0.8 ms here (the kernel
// zeroes it), and the refinement's passes, the optimizer and the report free and allocate again
// arrays of ever new sizes, which blocks kept only for requests of about their own size would
// seldom serve. Free blocks are handed back to the kernel (madvise MADV_DONTNEED, the range kept)
// whenever live and free blocks together would exceed the most pages the live blocks have had
// resident, so the arena does not raise the peak memory. That peak counts the pages the kernel
// has (mincore), not the blocks' sizes: the refinement reserves its mesh arrays for more tets than
// it makes, and a peak of sizes let the free blocks stay resident up to that reservation (1648 MB
// where 1472 were ever in use at 10^7 tets, which set the run's peak memory, issue 49). A freed
// block likewise counts as resident only where it was touched. When the range cannot be reserved
// or is full, blocks come from aligned_alloc.
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
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <mutex>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t(1) << 21;

// A run of whole huge pages of the arena, as page indices from its base.
struct Run {
  std::size_t first, pages;
  bool resident;  // touched since the kernel last had it back (counts towards the peak)
};

// The arena: a reserved range (MAP_NORESERVE: no memory until touched), used from the bottom up
// to `top_`; live blocks' sizes in a page-indexed table, free runs in an address-ordered table.
// Fixed tables only: operator new must not call itself under the lock.
class Arena {
 public:
  // A block of `pages` huge pages, or null (no arena, or no room: the caller falls back).
  void* allocate(std::size_t pages) {
    std::lock_guard<std::mutex> hold(lock_);
    if (!reserved() || pages > kMaxBlockPages) return nullptr;
    std::size_t first = 0;
    const std::size_t best = best_fit(pages);
    if (best < free_n_) {
      Run& r = free_[best];
      first = r.first;
      if (r.resident) free_resident_ -= pages;
      r.first += pages;
      r.pages -= pages;
      if (r.pages == 0) erase(best);
    } else if (free_n_ > 0 && free_[free_n_ - 1].first + free_[free_n_ - 1].pages == top_) {
      // The free run at the top grows into fresh pages (a growing array's usual pattern).
      const Run r = free_[free_n_ - 1];
      if (r.first + pages > capacity_) return nullptr;
      if (r.resident) free_resident_ -= r.pages;
      erase(free_n_ - 1);
      first = r.first;
      top_ = first + pages;
    } else {
      if (top_ + pages > capacity_) return nullptr;
      first = top_;
      top_ += pages;
    }
    block_pages_[first] = static_cast<std::uint32_t>(pages);
    live_ += pages;
    give_back_above_peak();
    return base_ + first * kHugePage;
  }
  // Lock-free: the range is set once (a block freed here was allocated after that).
  bool owns(const void* p) const {
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p);
    return at >= begin_.load(std::memory_order_acquire) && at < end_.load(std::memory_order_acquire);
  }
  void release(void* p) {
    std::lock_guard<std::mutex> hold(lock_);
    const std::size_t first = std::size_t(static_cast<char*>(p) - base_) / kHugePage;
    const std::size_t pages = block_pages_[first];
    // The live blocks are at a high before a release: their resident pages raise the peak (not
    // measured when they cannot: their sizes are within it).
    if (live_ > peak_) peak_ = std::max(peak_, resident_live_pages());
    block_pages_[first] = 0;
    live_ -= pages;
    // The block's runs as the kernel has them (a reserved array's untouched tail is not resident).
    for (std::size_t at = first; at < first + pages; at += kWindowPages) {
      const std::size_t w = std::min(kWindowPages, first + pages - at);
      measure(at, w);
      for (std::size_t h = 0; h < w;) {
        std::size_t end = h + 1;
        while (end < w && page_resident_[end] == page_resident_[h]) ++end;
        if (page_resident_[h]) free_resident_ += end - h;  // (before insert, which takes it back when it has no room)
        insert({at + h, end - h, page_resident_[h]});  // (merged with the window before's last run)
        h = end;
      }
    }
    // Now too, not only at the next allocation: the live blocks may yet touch the rest of their
    // sizes (a reserved array growing), which the free pages kept would then add to.
    give_back_above_peak();
  }

 private:
  static constexpr std::size_t kMaxRuns = 4096;
  static constexpr std::size_t kMaxBlockPages = std::size_t(1) << 31;

  // Reserves the range on first use: twice the machine's memory (at most 1 TiB), and the table
  // of block sizes, one entry per page (both untouched until used).
  bool reserved() {
    if (base_ != nullptr || tried_) return base_ != nullptr;
    tried_ = true;
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    std::size_t bytes = pages > 0 && page > 0 ? 2 * std::size_t(pages) * std::size_t(page) : std::size_t(64) << 30;
    bytes = std::min(bytes, std::size_t(1) << 40);
    const std::size_t huge_pages = bytes / kHugePage;
    if (huge_pages == 0) return false;
    void* table = mmap(nullptr, huge_pages * sizeof(std::uint32_t), PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (table == MAP_FAILED) return false;
    // One page more, to start on a huge-page boundary.
    void* range = mmap(nullptr, bytes + kHugePage, PROT_READ | PROT_WRITE,
                       MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (range == MAP_FAILED) {
      munmap(table, huge_pages * sizeof(std::uint32_t));
      return false;
    }
    const std::uintptr_t at = (reinterpret_cast<std::uintptr_t>(range) + kHugePage - 1) & ~(kHugePage - 1);
    madvise(range, bytes + kHugePage, MADV_HUGEPAGE);  // advice only: a refusal leaves ordinary pages
    block_pages_ = static_cast<std::uint32_t*>(table);
    base_ = reinterpret_cast<char*>(at);
    capacity_ = huge_pages;
    end_.store(at + huge_pages * kHugePage, std::memory_order_release);
    begin_.store(at, std::memory_order_release);
    return true;
  }
  // Whether each of the w huge pages from first holds memory (any of its small pages, when the
  // kernel gave small ones), in page_resident_; all of them do when the kernel cannot tell.
  void measure(std::size_t first, std::size_t w) {
    constexpr std::size_t kSmall = kHugePage / 4096;
    const bool known = mincore(base_ + first * kHugePage, w * kHugePage, residency_) == 0;
    for (std::size_t h = 0; h < w; ++h)
      page_resident_[h] = !known || std::any_of(residency_ + h * kSmall, residency_ + (h + 1) * kSmall,
                                                [](unsigned char c) { return (c & 1) != 0; });
  }
  std::size_t resident_pages(std::size_t first, std::size_t pages) {
    std::size_t n = 0;
    for (std::size_t at = first; at < first + pages; at += kWindowPages) {
      const std::size_t w = std::min(kWindowPages, first + pages - at);
      measure(at, w);
      n += std::size_t(std::count(page_resident_, page_resident_ + w, true));
    }
    return n;
  }
  std::size_t resident_live_pages() {
    std::size_t n = 0;
    for (std::size_t first = 0; first < top_;) {
      const std::size_t pages = block_pages_[first];
      if (pages == 0) {
        ++first;
        continue;
      }
      n += resident_pages(first, pages);
      first += pages;
    }
    return n;
  }
  // The free run to take `pages` from: the smallest resident one that holds them, else the
  // smallest one; free_n_ when none does.
  std::size_t best_fit(std::size_t pages) const {
    std::size_t best = free_n_;
    for (std::size_t i = 0; i < free_n_; ++i) {
      const Run& r = free_[i];
      if (r.pages < pages) continue;
      if (best == free_n_ || (r.resident && !free_[best].resident) ||
          (r.resident == free_[best].resident && r.pages < free_[best].pages))
        best = i;
    }
    return best;
  }
  // Adds a free run, merged with free neighbours of the same residency.
  void insert(Run run) {
    std::size_t at = 0;
    while (at < free_n_ && free_[at].first < run.first) ++at;
    if (at < free_n_ && free_[at].resident == run.resident && run.first + run.pages == free_[at].first) {
      run.pages += free_[at].pages;
      erase(at);
    }
    if (at > 0 && free_[at - 1].resident == run.resident && free_[at - 1].first + free_[at - 1].pages == run.first) {
      free_[at - 1].pages += run.pages;
      return;
    }
    if (free_n_ == kMaxRuns) {  // no room to remember it: the kernel has its pages back, the range is lost
      if (run.resident) {
        madvise(base_ + run.first * kHugePage, run.pages * kHugePage, MADV_DONTNEED);
        free_resident_ -= run.pages;
      }
      return;
    }
    std::copy_backward(free_ + at, free_ + free_n_, free_ + free_n_ + 1);
    free_[at] = run;
    ++free_n_;
  }
  void erase(std::size_t i) {
    std::copy(free_ + i + 1, free_ + free_n_, free_ + i);
    --free_n_;
  }
  // While live and resident free pages exceed the live peak, the kernel takes back the top part
  // of the largest resident free run.
  void give_back_above_peak() {
    while (live_ + free_resident_ > peak_) {
      std::size_t largest = free_n_;
      for (std::size_t i = 0; i < free_n_; ++i)
        if (free_[i].resident && (largest == free_n_ || free_[i].pages > free_[largest].pages)) largest = i;
      if (largest == free_n_) return;
      Run& r = free_[largest];
      const std::size_t pages = std::min(r.pages, live_ + free_resident_ - peak_);
      const Run back{r.first + r.pages - pages, pages, false};
      madvise(base_ + back.first * kHugePage, pages * kHugePage, MADV_DONTNEED);
      free_resident_ -= pages;
      r.pages -= pages;
      if (r.pages == 0) erase(largest);
      insert(back);
    }
  }

  std::mutex lock_;
  bool tried_ = false;
  char* base_ = nullptr;
  std::size_t capacity_ = 0, top_ = 0;  // in huge pages
  std::uint32_t* block_pages_ = nullptr;
  std::atomic<std::uintptr_t> begin_{UINTPTR_MAX}, end_{0};  // the range, for owns()
  Run free_[kMaxRuns];
  std::size_t free_n_ = 0;
  // In huge pages: the live blocks' sizes, the most pages they have had resident, and the
  // resident pages of the free runs.
  std::size_t live_ = 0, peak_ = 0, free_resident_ = 0;
  static constexpr std::size_t kWindowPages = 64;  // huge pages per mincore call
  unsigned char residency_[kWindowPages * (kHugePage / 4096)];  // mincore's answer, per small page
  bool page_resident_[kWindowPages];                            // measure()'s, per huge page
};

// Never destroyed: operator delete may run after static destructors.
Arena& arena() {
  static Arena* a = new (std::malloc(sizeof(Arena))) Arena();
  return *a;
}

void* allocate(std::size_t n) {
  if (n >= kHugePage) {
    const std::size_t pages = n / kHugePage + (n % kHugePage != 0);
    if (void* p = arena().allocate(pages)) return p;
    if (void* p = std::aligned_alloc(kHugePage, pages * kHugePage)) {
      madvise(p, pages * kHugePage, MADV_HUGEPAGE);
      return p;
    }
  } else if (void* p = std::malloc(n > 0 ? n : 1)) {
    return p;
  }
  throw std::bad_alloc();
}

void release(void* p) noexcept {
  if (p != nullptr && arena().owns(p)) arena().release(p);
  else std::free(p);
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }

#endif

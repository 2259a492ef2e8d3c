// The command-line tool's allocations of 2 MiB and more go on transparent huge pages (when the
// kernel offers them on request, "madvise" mode, as on Debian's default and on this project's
// machines). The mesher's flat arrays are hundreds of MB on large meshes, and each 4 KiB page
// costs a fault when first touched; on the paravirtualized machines here those faults were a
// fifth of armadillo's run (22.9 and 27.0 s against 18.9 and 19.3 s with this file, run
// alternately; glibc's glibc.malloc.hugetlb=1 tunable gave 18.2 and 23.9 s; the same meshes).
// Peak memory grows a little (armadillo 585 -> 646 MB): whole huge pages.
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

#include <cstddef>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t(1) << 21;

void* allocate(std::size_t n) {
  if (n >= kHugePage) {
    const std::size_t rounded = (n + kHugePage - 1) & ~(kHugePage - 1);
    if (void* p = std::aligned_alloc(kHugePage, rounded)) {
      madvise(p, rounded, MADV_HUGEPAGE);  // advice only: a refusal leaves ordinary pages
      return p;
    }
  } else if (void* p = std::malloc(n > 0 ? n : 1)) {
    return p;
  }
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

#endif

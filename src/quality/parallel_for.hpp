// Internal: run f(begin, end) over [0, n) in chunks, with TBB when asked and worth it.
#pragma once

#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace anitet::quality_detail {

template <class F>
void for_chunks(size_t n, bool parallel, F&& f) {
  constexpr size_t kGrain = 4096;
  if (!parallel || n < 2 * kGrain) {
    if (n > 0) f(size_t(0), n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<size_t>& r) { f(r.begin(), r.end()); });
}

}  // namespace anitet::quality_detail

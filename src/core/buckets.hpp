// Items grouped by a small integer key with a counting sort: linear, and stable (within a
// bucket, the items keep the order they were emitted in). Used wherever the mesh's tets are
// regrouped per vertex: faces and edges by their smallest vertex (quality report, HTML report,
// refinement's edge list, the adjacency), the tets by their first vertex along a curve
// (refinement's renumbering) and the balls of the vertices (the optimizer).
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace anitet {

// emit_all(emit) calls emit(key, value) once per item, key < num_keys, and must make the same
// calls each time: it runs twice (counting, then filling). Afterwards the values of key k are
// values[start[k] .. start[k + 1]). fill is scratch memory (kept by callers that call often).
// Values: a std::vector of any allocator.
template <class Index, class Values, class EmitAll>
void bucket_by_key(size_t num_keys, EmitAll&& emit_all, std::vector<Index>& start, Values& values,
                   std::vector<Index>& fill) {
  using Value = typename Values::value_type;
  start.assign(num_keys + 1, 0);
  emit_all([&](size_t key, const Value&) { ++start[key + 1]; });
  for (size_t k = 0; k < num_keys; ++k) start[k + 1] += start[k];
  values.resize(start[num_keys]);
  fill.assign(start.begin(), start.end() - 1);
  emit_all([&](size_t key, const Value& value) { values[fill[key]++] = value; });
}

// The same buckets, on every core. The items come from num_items sources (tets, usually):
// emit_range(begin, end, emit) calls emit(key, value) for the items of sources begin..end-1, in
// order, the same calls each time. Up to 8 ranges of sources are counted and filled by their own
// tasks, each into its own positions of every bucket, range after range: so a bucket lists its
// items in source order, exactly as bucket_by_key over all sources would, whatever the threads.
// counts is scratch memory: ranges x num_keys.
// Values: a std::vector of any allocator (an UninitVector: sized without being written, then
// filled here on every core).
template <class Index, class Values, class EmitRange>
void parallel_bucket_by_key(size_t num_keys, size_t num_items, EmitRange&& emit_range, std::vector<Index>& start,
                            Values& values, std::vector<Index>& counts) {
  using Value = typename Values::value_type;
  const size_t threads = size_t(std::max(1, tbb::this_task_arena::max_concurrency()));
  // (Small inputs: one range, not worth a task; the counts cost ranges x num_keys.)
  const size_t ranges = std::max<size_t>(1, std::min({size_t(8), threads, num_items / 16384}));
  auto range = [&](size_t r) { return std::make_pair(num_items * r / ranges, num_items * (r + 1) / ranges); };
  counts.assign(ranges * num_keys, 0);
  tbb::parallel_for(size_t(0), ranges, [&](size_t r) {
    Index* count = counts.data() + r * num_keys;  // (no reference: num_keys may be 0)
    const auto [begin, end] = range(r);
    emit_range(begin, end, [count](size_t key, const Value&) { ++count[key]; });
  });
  start.assign(num_keys + 1, 0);
  for (size_t k = 0; k < num_keys; ++k) {
    Index total = 0;
    for (size_t r = 0; r < ranges; ++r) total += counts[r * num_keys + k];
    start[k + 1] = start[k] + total;
  }
  // Each range's first position in each bucket.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, num_keys, 16384), [&](const tbb::blocked_range<size_t>& keys) {
    for (size_t k = keys.begin(); k != keys.end(); ++k) {
      Index at = start[k];
      for (size_t r = 0; r < ranges; ++r) at += std::exchange(counts[r * num_keys + k], at);
    }
  });
  values.resize(start[num_keys]);
  tbb::parallel_for(size_t(0), ranges, [&](size_t r) {
    Index* fill = counts.data() + r * num_keys;
    Value* out = values.data();
    const auto [begin, end] = range(r);
    emit_range(begin, end, [fill, out](size_t key, const Value& value) { out[fill[key]++] = value; });
  });
}

}  // namespace anitet

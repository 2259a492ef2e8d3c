#include "validate/self_intersect.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>

#include "validate/tri_intersect.hpp"

namespace anitet {

namespace {

using Pair = std::pair<uint32_t, uint32_t>;

bool same_vertex_set(const uint32_t* a, const uint32_t* b) {
  uint32_t x[3] = {a[0], a[1], a[2]}, y[3] = {b[0], b[1], b[2]};
  std::sort(x, x + 3);
  std::sort(y, y + 3);
  return x[0] == y[0] && x[1] == y[1] && x[2] == y[2];
}

}  // namespace

std::vector<Pair> find_intersecting_pairs(const SurfaceMesh& s, const TriangleBVH& bvh,
                                          const std::vector<uint8_t>& testable,
                                          int num_threads) {
  const auto test = [&](const Pair& pr) {
    const uint32_t* ti = &s.tri[3 * size_t(pr.first)];
    const uint32_t* tj = &s.tri[3 * size_t(pr.second)];
    if (same_vertex_set(ti, tj)) return false;  // a duplicate, reported as such
    const double* a[3] = {s.point(ti[0]), s.point(ti[1]), s.point(ti[2])};
    const double* b[3] = {s.point(tj[0]), s.point(tj[1]), s.point(tj[2])};
    return tri_intersect::triangles_intersect(a, b);
  };

  // Candidates are the box-overlapping pairs (the box test is the cheap filter before the exact
  // tests), gathered serially in batches of bounded size and tested in parallel.
  constexpr size_t kBatch = size_t(1) << 20;
  std::vector<Pair> batch;
  batch.reserve(std::min(kBatch, 16 * s.num_triangles() + 1));
  tbb::enumerable_thread_specific<std::vector<Pair>> found;
  const auto test_batch = [&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batch.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                        auto& local = found.local();
                        for (size_t k = r.begin(); k != r.end(); ++k) {
                          if (test(batch[k])) local.push_back(batch[k]);
                        }
                      });
    batch.clear();
  };
  const auto run = [&] {
    bvh.overlapping_pairs([&](uint32_t i, uint32_t j) {
      if (testable[i] && testable[j]) batch.emplace_back(i, j);
      if (batch.size() == kBatch) test_batch();
      return true;
    });
    test_batch();
  };
  if (num_threads > 0) {
    tbb::task_arena arena(num_threads);
    arena.execute(run);
  } else {
    run();
  }
  std::vector<Pair> pairs;
  for (const auto& local : found) pairs.insert(pairs.end(), local.begin(), local.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace anitet

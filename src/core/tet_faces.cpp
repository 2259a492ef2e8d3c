#include "core/tet_faces.hpp"

#include <algorithm>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/uninit_vector.hpp"

namespace anitet {

namespace {

void sort3(uint32_t f[3]) {
  if (f[0] > f[1]) std::swap(f[0], f[1]);
  if (f[1] > f[2]) std::swap(f[1], f[2]);
  if (f[0] > f[1]) std::swap(f[0], f[1]);
}

// One chunk of vertices' findings, merged in chunk order afterwards.
struct ChunkFindings {
  std::vector<uint32_t> boundary, uncovered, repeated;
  size_t shared = 0;
};

// The table of one vertex's faces: slots of (face, tets, triangles), a power of two at least twice
// the bucket's size; `used` lists the slots taken, in the order of the faces' first appearance.
struct FaceTable {
  std::vector<uint64_t> key;
  std::vector<uint32_t> count, cover, used;

  size_t prepare(size_t n) {
    size_t slots = 16;
    while (slots < 2 * n) slots *= 2;
    if (key.size() < slots) {
      key.resize(slots);
      count.assign(slots, 0);
      cover.assign(slots, 0);
    }
    used.clear();
    return slots - 1;
  }
  static size_t home(uint64_t f, size_t mask) { return size_t((f * 0x9E3779B97F4A7C15ull) >> 40) & mask; }
};

}  // namespace

FaceCensus census_faces(const uint32_t* tet, size_t num_tets, size_t nv, bool parallel, const uint32_t* tri,
                        size_t num_triangles) {
  FaceCensus out;
  // (middle << 32) | largest of every tet face, bucketed by the smallest.
  std::vector<size_t> start;
  UninitVector<uint64_t> rest;
  {
    std::vector<size_t> fill;
    // One sort of the tet's four vertices gives its four faces sorted (the face opposite v[i] is
    // the sorted four without one copy of v[i]), emitted in the order i = 0..3.
    auto emit_faces = [&](size_t first, size_t last, auto&& emit) {
      for (size_t t = first; t < last; ++t) {
        const uint32_t* v = &tet[4 * t];
        uint32_t s4[4] = {v[0], v[1], v[2], v[3]};
        if (s4[0] > s4[1]) std::swap(s4[0], s4[1]);
        if (s4[2] > s4[3]) std::swap(s4[2], s4[3]);
        if (s4[0] > s4[2]) std::swap(s4[0], s4[2]);
        if (s4[1] > s4[3]) std::swap(s4[1], s4[3]);
        if (s4[1] > s4[2]) std::swap(s4[1], s4[2]);
        for (int i = 0; i < 4; ++i) {
          const int j = s4[0] == v[i] ? 0 : s4[1] == v[i] ? 1 : s4[2] == v[i] ? 2 : 3;
          const uint32_t lo = s4[j == 0 ? 1 : 0], mid = s4[j <= 1 ? 2 : 1], hi = s4[j == 3 ? 2 : 3];
          emit(lo, (uint64_t(mid) << 32) | hi);
        }
      }
    };
    if (parallel) parallel_bucket_by_key(nv, num_tets, emit_faces, start, rest, fill);
    else bucket_by_key(nv, [&](auto&& emit) { emit_faces(0, num_tets, emit); }, start, rest, fill);
  }
  // The triangles' ids, bucketed the same way (in id order within a bucket).
  std::vector<uint32_t> tri_start, tri_ids, tri_fill;
  if (num_triangles > 0) {
    bucket_by_key(
        nv,
        [&](auto&& emit) {
          for (size_t b = 0; b < num_triangles; ++b) {
            uint32_t f[3] = {tri[3 * b], tri[3 * b + 1], tri[3 * b + 2]};
            sort3(f);
            emit(f[0], uint32_t(b));
          }
        },
        tri_start, tri_ids, tri_fill);
    out.tets_of_triangle.assign(num_triangles, 0);
  }

  constexpr size_t kChunk = 16384;
  const size_t chunks = (nv + kChunk - 1) / kChunk;
  std::vector<ChunkFindings> found(chunks);
  auto census = [&](size_t first_chunk, size_t last_chunk) {
    FaceTable table;
    for (size_t c = first_chunk; c < last_chunk; ++c) {
      ChunkFindings& mine = found[c];
      for (size_t v = c * kChunk; v < std::min(nv, (c + 1) * kChunk); ++v) {
        const size_t n = start[v + 1] - start[v];
        const size_t nb = num_triangles > 0 ? tri_start[v + 1] - tri_start[v] : 0;
        if (n == 0 && nb == 0) continue;
        const size_t mask = table.prepare(n);
        for (size_t k = start[v]; k < start[v + 1]; ++k) {
          const uint64_t f = rest[k];
          size_t at = FaceTable::home(f, mask);
          while (table.count[at] != 0 && table.key[at] != f) at = (at + 1) & mask;
          if (table.count[at]++ == 0) {
            table.key[at] = f;
            table.used.push_back(uint32_t(at));
          }
        }
        for (size_t k = nb ? tri_start[v] : 0, end = nb ? tri_start[v + 1] : 0; k < end; ++k) {
          const uint32_t b = tri_ids[k];
          uint32_t g[3] = {tri[3 * size_t(b)], tri[3 * size_t(b) + 1], tri[3 * size_t(b) + 2]};
          sort3(g);
          const uint64_t f = (uint64_t(g[1]) << 32) | g[2];
          size_t at = FaceTable::home(f, mask);
          while (table.count[at] != 0 && table.key[at] != f) at = (at + 1) & mask;
          if (table.count[at] == 0) continue;  // no tet has it: tets_of_triangle stays 0
          out.tets_of_triangle[b] = uint8_t(std::min<uint32_t>(table.count[at], 255));
          if (table.cover[at]++ > 0) mine.repeated.push_back(b);
        }
        for (uint32_t at : table.used) {
          if (table.count[at] == 1) {
            const uint32_t face[3] = {uint32_t(v), uint32_t(table.key[at] >> 32), uint32_t(table.key[at])};
            mine.boundary.insert(mine.boundary.end(), face, face + 3);
            if (num_triangles > 0 && table.cover[at] == 0) mine.uncovered.insert(mine.uncovered.end(), face, face + 3);
          } else if (table.count[at] > 2) {
            ++mine.shared;
          }
          table.count[at] = 0;
          table.cover[at] = 0;
        }
      }
    }
  };
  if (parallel && chunks > 1) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<size_t>& r) { census(r.begin(), r.end()); });
  } else {
    census(0, chunks);
  }
  size_t total = 0;
  for (const ChunkFindings& c : found) total += c.boundary.size();
  out.boundary.reserve(total);
  for (ChunkFindings& c : found) {
    out.boundary.insert(out.boundary.end(), c.boundary.begin(), c.boundary.end());
    out.uncovered.insert(out.uncovered.end(), c.uncovered.begin(), c.uncovered.end());
    out.repeated.insert(out.repeated.end(), c.repeated.begin(), c.repeated.end());
    out.shared_by_more_than_two += c.shared;
  }
  std::sort(out.repeated.begin(), out.repeated.end());
  return out;
}

}  // namespace anitet

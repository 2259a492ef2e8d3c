#include "refine/edges.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/sizing.hpp"

namespace anitet::refine_detail {

void collect_edges(const TetMesh& mesh, const std::vector<double>& metrics, std::vector<Edge>& edges,
                   EdgeScratch& scratch) {
  // Bucketed by the lower end (a counting sort), then deduplicated per bucket: linear in the
  // tets, where one global sort of every tet's six edges dominated refinement.
  const size_t nv = mesh.num_vertices();
  auto for_each_edge = [&mesh](uint32_t first, uint32_t last, auto&& f) {
    for (uint32_t t = first; t < last; ++t) {
      if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
      // Edge k of the tet lies on facet i when neither end is vertex i.
      uint8_t on_facet = 0;
      for (int i = 0; i < 4; ++i) {
        if (!mesh.facet_protected(t, i)) continue;
        for (int k = 0; k < 6; ++k)
          if (kEdgeVertex[k][0] != i && kEdgeVertex[k][1] != i) on_facet |= uint8_t(1u << k);
      }
      for (int k = 0; k < 6; ++k) {
        uint32_t a = mesh.vertex(t, kEdgeVertex[k][0]), b = mesh.vertex(t, kEdgeVertex[k][1]);
        if (a > b) std::swap(a, b);
        f(a, b, t, ((on_facet >> k) & 1u) != 0);
      }
    }
  };
  // The counting sort by the lower end, on every core (parallel_bucket_by_key: each bucket lists
  // its items in tet order, as one loop would). 8 bytes per tet edge (the buckets hold six per
  // tet: their memory traffic is most of the cost).
  const uint32_t nt = static_cast<uint32_t>(mesh.num_tet_slots());
  // (The lists are rebuilt: freed before they grow, they are never held twice. Their last
  // copies were the peak of the 1e7-tet run.)
  if (size_t(6) * nt > scratch.all.capacity()) std::vector<EdgeScratch::Entry>().swap(scratch.all);
  parallel_bucket_by_key(
      nv, nt,
      [&](size_t first, size_t last, auto&& emit) {
        for_each_edge(uint32_t(first), uint32_t(last), [&](uint32_t a, uint32_t b, uint32_t t, bool s) {
          emit(a, EdgeScratch::Entry{b, t | (s ? EdgeScratch::Entry::kSurface : 0u)});
        });
      },
      scratch.start, scratch.all, scratch.fill);
  const std::vector<uint32_t>& start = scratch.start;
  const std::vector<EdgeScratch::Entry>& all = scratch.all;
  // Duplicates are found within each bucket through a per-thread array holding, per upper end b,
  // the position of (a, b) while bucket a is scanned (kNone otherwise: each bucket clears what it
  // set). In chunks of vertices on every core: a first pass counts each chunk's edges, a second
  // writes them at the chunk's offset in `edges` (one copy of the edges at any time: refinement's
  // peak memory). Same edges in the same order as one loop.
  constexpr size_t kChunk = 8192;
  const size_t chunks = (nv + kChunk - 1) / kChunk;
  auto dedup_chunk = [&](size_t c, auto&& keep, auto&& again) {
    std::vector<uint32_t>& where = scratch.where.local();
    if (where.size() < nv) where.resize(nv, TetMesh::kNone);
    uint32_t kept = 0;
    for (size_t v = c * kChunk; v < std::min(nv, (c + 1) * kChunk); ++v) {
      for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
        const EdgeScratch::Entry& e = all[k];
        if (where[e.b] != TetMesh::kNone) {
          again(where[e.b], e);
          continue;
        }
        where[e.b] = kept++;
        keep(static_cast<uint32_t>(v), e);
      }
      for (uint32_t k = start[v]; k < start[v + 1]; ++k) where[all[k].b] = TetMesh::kNone;
    }
    return kept;
  };
  std::vector<size_t> offset(chunks + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c)
      offset[c + 1] = dedup_chunk(c, [](uint32_t, const EdgeScratch::Entry&) {},
                                  [](uint32_t, const EdgeScratch::Entry&) {});
  });
  for (size_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];
  if (offset[chunks] > edges.capacity()) std::vector<Edge>().swap(edges);
  edges.resize(offset[chunks]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c) {
      Edge* out = edges.data() + offset[c];
      dedup_chunk(
          c,
          [&](uint32_t a, const EdgeScratch::Entry& e) {
            const uint32_t b = e.b;
            const double* pa = mesh.point(a);
            const double* pb = mesh.point(b);
            const double d[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
            *out++ = {a, b, e.tet & ~EdgeScratch::Entry::kSurface, (e.tet & EdgeScratch::Entry::kSurface) != 0,
                      std::sqrt(metric_norm(&metrics[6 * size_t(a)], d) * metric_norm(&metrics[6 * size_t(b)], d))};
          },
          [&](uint32_t j, const EdgeScratch::Entry& e) {
            edges[offset[c] + j].on_surface |= (e.tet & EdgeScratch::Entry::kSurface) != 0;
          });
    }
  });
}

size_t live_vertex_count(const TetMesh& mesh) {
  std::vector<uint8_t> used(mesh.num_vertices(), 0);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    for (int i = 0; i < 4; ++i) used[mesh.vertex(t, i)] = 1;
  }
  size_t n = 0;
  for (uint8_t u : used) n += u;
  return n;
}

void length_summary(const std::vector<Edge>& edges, double collapse_length, double split_length, double& mean,
                    double& in_range) {
  size_t counted = 0, inside = 0;
  double sum = 0.0;
  for (const Edge& e : edges) {
    if (e.on_surface) continue;
    ++counted;
    sum += e.length;
    if (e.length >= collapse_length && e.length <= split_length) ++inside;
  }
  mean = counted ? sum / double(counted) : 0.0;
  in_range = counted ? double(inside) / double(counted) : 1.0;
}

}  // namespace anitet::refine_detail

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/bvh.hpp"
#include "delaunay/spatial_sort.hpp"
#include "refine/refine.hpp"

namespace anitet {
namespace {

// array (per_tet entries per tet slot) with the slots order[0], order[1], ... only, each entry
// mapped by `value`; with a sixteenth more room: the optimizer's flips take new slots right after
// this, and growing the arrays then copied all of them to fresh pages.
template <class T, class ForRange, class Value>
void permute_tets(std::vector<T>& array, size_t per_tet, const std::vector<uint32_t>& order, ForRange&& for_range,
                  Value&& value) {
  const size_t nt = order.size();
  std::vector<T> out;
  out.reserve(per_tet * (nt + nt / 16));
  out.resize(per_tet * nt);
  for_range(nt, [&](size_t k) {
    for (size_t i = 0; i < per_tet; ++i) out[per_tet * k + i] = value(array[per_tet * size_t(order[k]) + i]);
  });
  array.swap(out);
}

}  // namespace

void order_for_locality(TetMesh& mesh, uint32_t first_vertex) {
  const size_t nv = mesh.num_vertices();
  const auto slots = static_cast<uint32_t>(mesh.num_tet_slots());
  first_vertex = static_cast<uint32_t>(std::min<size_t>(first_vertex, nv));
  // (The long loops over vertices and tets run on every core, each index writing its own entries,
  // so the result does not depend on the threads. The curve and the new ids stay in order.)
  auto for_range = [](size_t n, auto&& body) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 16384), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) body(i);
    });
  };
  // Every used vertex's rank along a Hilbert curve through the mesh's box.
  std::vector<std::atomic<uint8_t>> used(nv);  // (atomic: tets sharing a vertex mark it at once)
  for_range(slots, [&](size_t t) {
    if (!mesh.is_deleted(uint32_t(t)))
      for (int i = 0; i < 4; ++i)
        if (mesh.vertex(uint32_t(t), i) != TetMesh::kGhost)
          used[mesh.vertex(uint32_t(t), i)].store(1, std::memory_order_relaxed);
  });
  std::vector<uint32_t> curve;
  for (uint32_t v = 0; v < nv; ++v)
    if (used[v]) curve.push_back(v);
  if (curve.empty()) return;
  // (The unused vertices, removed by collapses, lie inside: the box is the used ones'.)
  const Box3 box = bounding_box(mesh.xyz.data(), nv);
  delaunay_detail::hilbert_sort(mesh.xyz.data(), curve.data(), curve.size(), box.lo, box.hi);
  std::vector<uint32_t> rank(nv, TetMesh::kNone);
  for_range(curve.size(), [&](size_t k) { rank[curve[k]] = static_cast<uint32_t>(k); });
  // New ids: the first ones kept, the used others in curve order, then the unused in id order.
  std::vector<uint32_t> new_id(nv);
  for (uint32_t v = 0; v < first_vertex; ++v) new_id[v] = v;
  uint32_t next = first_vertex;
  for (uint32_t v : curve)
    if (v >= first_vertex) new_id[v] = next++;
  for (uint32_t v = first_vertex; v < nv; ++v)
    if (!used[v]) new_id[v] = next++;
  std::vector<double> xyz(mesh.xyz.size());
  std::vector<uint8_t> vflags(nv);
  for_range(nv, [&](size_t v) {  // (new_id is a permutation)
    std::copy_n(mesh.point(uint32_t(v)), 3, &xyz[3 * size_t(new_id[v])]);
    vflags[new_id[v]] = mesh.vflags[v];
  });
  mesh.xyz.swap(xyz);
  mesh.vflags.swap(vflags);
  // Tets grouped by the rank of their first vertex along the curve (slot order within a group).
  std::vector<uint32_t> start, order, fill;
  parallel_bucket_by_key(
      curve.size(), slots,
      [&](size_t first, size_t last, auto&& emit) {
        for (auto t = uint32_t(first); t < last; ++t) {
          if (mesh.is_deleted(t)) continue;
          uint32_t r = TetMesh::kNone;
          for (int i = 0; i < 4; ++i)
            if (mesh.vertex(t, i) != TetMesh::kGhost) r = std::min(r, rank[mesh.vertex(t, i)]);
          emit(r, t);
        }
      },
      start, order, fill);
  std::vector<uint32_t>().swap(start);
  std::vector<uint32_t>().swap(fill);
  std::vector<uint32_t>().swap(rank);
  std::vector<uint32_t> new_tet(slots, TetMesh::kNone);
  for_range(order.size(), [&](size_t k) { new_tet[order[k]] = static_cast<uint32_t>(k); });
  // One array at a time, each old one freed before the next is built: the whole tet arrays old
  // and new at once set the peak memory of large runs (issue 49).
  const uint32_t kNoNeighbour = TetMesh::kNoNeighbour;
  permute_tets(mesh.tet_adj, 4, order, for_range, [&](uint32_t a) {
    return a == kNoNeighbour ? a : 4 * new_tet[a >> 2] + (a & 3);
  });
  std::vector<uint32_t>().swap(new_tet);
  permute_tets(mesh.tet_v, 4, order, for_range,
               [&](uint32_t v) { return v == TetMesh::kGhost ? v : new_id[v]; });
  permute_tets(mesh.tet_flags, 1, order, for_range, [](uint16_t f) { return f; });
  permute_tets(mesh.tet_region, 1, order, for_range, [](int32_t r) { return r; });
  mesh.free_tets.clear();
}

}  // namespace anitet

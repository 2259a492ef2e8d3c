#include "refine/edges.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/sizing.hpp"

namespace anitet::refine_detail {

namespace {

// f(a, b, t, on_surface) for the six edges (a < b) of each live tet t in first .. last - 1, in
// order; on_surface: the edge lies on a protected facet of t.
template <class F>
void for_each_edge(const TetMesh& mesh, uint32_t first, uint32_t last, F&& f) {
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
}

// A tet's edge (a, b) in a's bucket (collect_edges).
struct Entry {
  static constexpr uint32_t kSurface = 1u << 31;  // tet's top bit: the edge is on a protected facet
  uint32_t b;
  uint32_t tet;
};

}  // namespace

void collect_edges(const TetMesh& mesh, const std::vector<double>& metrics, EdgeList& edges,
                   EdgeScratch& scratch) {
  // Bucketed by the lower end (a counting sort), then deduplicated per bucket: linear in the
  // tets, where one global sort of every tet's six edges dominated refinement.
  const size_t nv = mesh.num_vertices();
  // The counting sort by the lower end, on every core (parallel_bucket_by_key: each bucket lists
  // its items in tet order, as one loop would). 8 bytes per tet edge (the buckets hold six per
  // tet: their memory traffic is most of the cost). Freed on return: not held beside the lists
  // between the calls (48 bytes per tet slot; refinement's peak memory, issue 49). (Entries of 4
  // bytes, the tet and its edge, reading the upper end from the tet again: about 1.7 times the
  // edge lists' time on one core.)
  const uint32_t nt = static_cast<uint32_t>(mesh.num_tet_slots());
  UninitVector<Entry> all;
  parallel_bucket_by_key(
      nv, nt,
      [&](size_t first, size_t last, auto&& emit) {
        for_each_edge(mesh, uint32_t(first), uint32_t(last), [&](uint32_t a, uint32_t b, uint32_t t, bool s) {
          emit(a, Entry{b, t | (s ? Entry::kSurface : 0u)});
        });
      },
      scratch.start, all, scratch.fill);
  const std::vector<uint32_t>& start = scratch.start;
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
        const Entry& e = all[k];
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
      offset[c + 1] = dedup_chunk(c, [](uint32_t, const Entry&) {},
                                  [](uint32_t, const Entry&) {});
  });
  for (size_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];
  if (offset[chunks] > edges.capacity()) EdgeList().swap(edges);
  edges.resize(offset[chunks]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c) {
      Edge* out = edges.data() + offset[c];
      dedup_chunk(
          c,
          [&](uint32_t a, const Entry& e) {
            *out++ = {a, e.b, e.tet & ~Entry::kSurface, (e.tet & Entry::kSurface) != 0,
                      false, normalized_length(mesh, metrics, a, e.b)};
          },
          [&](uint32_t j, const Entry& e) {
            edges[offset[c] + j].on_surface |= (e.tet & Entry::kSurface) != 0;
          });
    }
  });
}

EdgeStar edge_star(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t start, const uint8_t* changed) {
  EdgeStar star{start, changed[start] ? start : TetMesh::kNone, false};
  // t's two facets through ab are those opposite its other two vertices.
  auto other_two = [&](uint32_t t, int& i, int& j) {
    i = j = -1;
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = mesh.vertex(t, k);
      if (v != a && v != b) (i < 0 ? i : j) = k;
    }
  };
  auto visit = [&](uint32_t t, int i, int j) {
    star.min_tet = std::min(star.min_tet, t);
    if (changed[t]) star.min_changed = std::min(star.min_changed, t);
    star.on_surface |= mesh.facet_protected(t, i) || mesh.facet_protected(t, j);
  };
  int i0, j0;
  other_two(start, i0, j0);
  if (j0 < 0) return star;  // (start does not hold ab: not expected)
  visit(start, i0, j0);
  // Around the edge one way (leaving start across the facet opposite its vertex i0), and, when
  // that meets a facet without neighbour, the other way.
  for (int way = 0; way < 2; ++way) {
    uint32_t t = start;
    int leave = way == 0 ? i0 : j0;
    uint32_t kept = mesh.vertex(start, way == 0 ? j0 : i0);  // on the facet crossed, with a and b
    for (int steps = 0; steps < 4096; ++steps) {
      if (mesh.tet_adj[4 * size_t(t) + leave] == TetMesh::kNoNeighbour) break;
      const uint32_t n = mesh.neighbour(t, leave);
      if (n == start) return star;  // the ring closed: every tet seen
      const int entered = mesh.neighbour_facet(t, leave);  // n's vertex opposite the crossed facet
      int next = -1;
      for (int k = 0; k < 4; ++k)
        if (mesh.vertex(n, k) == kept) next = k;
      if (next < 0) return star;  // (not a valid mesh)
      visit(n, entered, next);
      kept = mesh.vertex(n, entered);
      leave = next;
      t = n;
    }
  }
  return star;
}

void update_edges(const TetMesh& mesh, const std::vector<double>& metrics, const std::vector<uint8_t>& changed,
                  const EdgeFilter& filter, EdgeList& previous, EdgeScratch& scratch) {
  const uint8_t* ch = changed.data();
  const size_t nt = mesh.num_tet_slots(), nv = mesh.num_vertices();
  constexpr size_t kChunk = 4096;
  // When most tets changed (refinement's first passes), collecting every edge is cheaper than
  // measuring each changed tet's six (an edge is in about five of them); only the vetoes of the
  // edges whose tets did not change are carried over.
  size_t changed_live = 0;
  for (size_t t = 0; t < nt; ++t) changed_live += ch[t] && !mesh.is_deleted(uint32_t(t));
  if (2 * changed_live > mesh.num_live_tets()) {
    std::vector<uint64_t> vetoed;
    for (const Edge& e : previous)
      if (e.vetoed && !mesh.is_deleted(e.tet) && !ch[e.tet] &&
          edge_star(mesh, e.a, e.b, e.tet, ch).min_changed == TetMesh::kNone)
        vetoed.push_back(e.key());
    EdgeList().swap(previous);
    collect_edges(mesh, metrics, previous, scratch);
    mark_vetoed(previous, vetoed, filter.split_length);
    return;
  }
  // The wanted edges of the changed tets (once per tet holding them), measured, in tet order.
  struct Found {
    uint32_t a, b;  // a < b
    uint32_t tet;   // a changed tet holding it
    double length;
  };
  const size_t tet_chunks = (nt + kChunk - 1) / kChunk;
  std::vector<std::vector<Found>> found_parts(tet_chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tet_chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c)
      for (size_t t = c * kChunk; t < std::min(nt, (c + 1) * kChunk); ++t) {
        if (!ch[t] || mesh.is_deleted(uint32_t(t)) || mesh.is_ghost(uint32_t(t))) continue;
        for (int k = 0; k < 6; ++k) {
          uint32_t a = mesh.vertex(uint32_t(t), kEdgeVertex[k][0]), b = mesh.vertex(uint32_t(t), kEdgeVertex[k][1]);
          if (a > b) std::swap(a, b);
          const double length = normalized_length(mesh, metrics, a, b);
          if (filter.wanted(mesh, a, b, length)) found_parts[c].push_back({a, b, uint32_t(t), length});
        }
      }
  });
  std::vector<Found> found;
  for (const std::vector<Found>& part : found_parts) found.insert(found.end(), part.begin(), part.end());
  std::vector<std::vector<Found>>().swap(found_parts);
  // Grouped by the lower end (a counting sort: the items' indices in `found`).
  std::vector<uint32_t> start, in_bucket, counts;
  parallel_bucket_by_key(
      nv, found.size(),
      [&](size_t first, size_t last, auto&& emit) {
        for (size_t k = first; k < last; ++k) emit(found[k].a, uint32_t(k));
      },
      start, in_bucket, counts);
  // The edges of `previous` still wanted whose tets did not change: e.tet is live and was not made
  // again (a destroyed edge's tets are all gone), and no changed tet holds the edge (it is not in
  // a's group). Then each found edge once (its first entry in its group), with its star.
  auto in_found = [&](uint32_t a, uint32_t b) {
    for (uint32_t k = start[a]; k < start[a + 1]; ++k)
      if (found[in_bucket[k]].b == b) return true;
    return false;
  };
  const size_t carried_chunks = (previous.size() + kChunk - 1) / kChunk;
  const size_t vertex_chunks = (nv + kChunk - 1) / kChunk;
  std::vector<std::vector<Edge>> parts(carried_chunks + vertex_chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, parts.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t c = r.begin(); c != r.end(); ++c) {
      std::vector<Edge>& out = parts[c];
      if (c < carried_chunks) {
        for (size_t k = c * kChunk; k < std::min(previous.size(), (c + 1) * kChunk); ++k) {
          const Edge& e = previous[k];
          if (filter.wanted(mesh, e.a, e.b, e.length) && !mesh.is_deleted(e.tet) && !ch[e.tet] && !in_found(e.a, e.b))
            out.push_back(e);
        }
        continue;
      }
      std::vector<uint32_t>& seen = scratch.where.local();  // per upper end: in the group scanned
      if (seen.size() < nv) seen.resize(nv, TetMesh::kNone);
      const size_t v0 = (c - carried_chunks) * kChunk;
      for (size_t a = v0; a < std::min(nv, v0 + kChunk); ++a) {
        for (uint32_t k = start[a]; k < start[a + 1]; ++k) {
          const Found& f = found[in_bucket[k]];
          if (seen[f.b] != TetMesh::kNone) continue;
          seen[f.b] = 0;
          const EdgeStar star = edge_star(mesh, f.a, f.b, f.tet, ch);
          out.push_back({f.a, f.b, star.min_tet, star.on_surface, false, f.length});
        }
        for (uint32_t k = start[a]; k < start[a + 1]; ++k) seen[found[in_bucket[k]].b] = TetMesh::kNone;
      }
    }
  });
  size_t total = 0;
  for (const std::vector<Edge>& part : parts) total += part.size();
  EdgeList next;
  next.reserve(total);
  for (const std::vector<Edge>& part : parts) next.insert(next.end(), part.begin(), part.end());
  previous.swap(next);
}

void mark_vetoed(EdgeList& edges, std::vector<uint64_t>& keys, double split_length) {
  if (keys.empty()) return;
  std::sort(keys.begin(), keys.end());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, edges.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      Edge& e = edges[k];
      if (e.length > split_length && std::binary_search(keys.begin(), keys.end(), e.key())) e.vetoed = true;
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

void summarize_edge_lengths(const TetMesh& mesh, const std::vector<double>& metrics, double collapse_length,
                            double split_length, double& mean, double& in_range) {
  // collect_edges's buckets with 4 bytes per tet edge (its upper end, the top bit for "on a
  // protected facet"), and no edge list: 24 bytes per tet slot where the list and its buckets
  // took about 76, at the end of refinement, its peak memory (issue 49).
  constexpr uint32_t kSurface = 1u << 31;
  const size_t nv = mesh.num_vertices();
  std::vector<uint32_t> start, counts;
  UninitVector<uint32_t> upper;
  parallel_bucket_by_key(
      nv, mesh.num_tet_slots(),
      [&](size_t first, size_t last, auto&& emit) {
        for_each_edge(mesh, uint32_t(first), uint32_t(last),
                      [&](uint32_t a, uint32_t b, uint32_t, bool s) { emit(a, b | (s ? kSurface : 0u)); });
      },
      start, upper, counts);
  std::vector<uint32_t>().swap(counts);
  // Per chunk of lower ends, on every core: each edge once (its entries merged: on a protected
  // facet when any tet says so), counted when not on one. The chunks' sums add in chunk order (the
  // same figures on any number of threads).
  struct Sums {
    size_t counted = 0, inside = 0;
    double sum = 0.0;
  };
  constexpr size_t kChunk = 8192;
  std::vector<Sums> sums((nv + kChunk - 1) / kChunk);
  tbb::enumerable_thread_specific<std::vector<uint32_t>> where_local;  // per upper end: its edge in `bucket`
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sums.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<uint32_t>& where = where_local.local();
    if (where.size() < nv) where.resize(nv, TetMesh::kNone);
    std::vector<uint32_t> bucket;  // the edges of one lower end, upper end and surface bit
    for (size_t c = r.begin(); c != r.end(); ++c) {
      Sums& s = sums[c];
      for (size_t a = c * kChunk; a < std::min(nv, (c + 1) * kChunk); ++a) {
        bucket.clear();
        for (uint32_t k = start[a]; k < start[a + 1]; ++k) {
          const uint32_t b = upper[k] & ~kSurface;
          if (where[b] == TetMesh::kNone) {
            where[b] = uint32_t(bucket.size());
            bucket.push_back(upper[k]);
          } else {
            bucket[where[b]] |= upper[k] & kSurface;
          }
        }
        for (uint32_t e : bucket) {
          where[e & ~kSurface] = TetMesh::kNone;
          if (e & kSurface) continue;
          const double length = normalized_length(mesh, metrics, uint32_t(a), e);
          ++s.counted;
          s.sum += length;
          if (length >= collapse_length && length <= split_length) ++s.inside;
        }
      }
    }
  });
  Sums all;
  for (const Sums& s : sums) {
    all.counted += s.counted;
    all.inside += s.inside;
    all.sum += s.sum;
  }
  mean = all.counted ? all.sum / double(all.counted) : 0.0;
  in_range = all.counted ? double(all.inside) / double(all.counted) : 1.0;
}

}  // namespace anitet::refine_detail

#include "core/tet_ops.hpp"

#include <algorithm>
#include <iterator>

#include "predicates/predicates.hpp"

namespace anitet::meshops {

namespace {
constexpr uint16_t kBallMark = 1u << 10;  // a scratch bit of tet_flags (tflag::kScratchMask)
}  // namespace

bool tet_has_vertex(const TetMesh& mesh, uint32_t t, uint32_t v) {
  if (t >= mesh.num_tet_slots() || mesh.is_deleted(t)) return false;
  const uint32_t* tv = &mesh.tet_v[4 * size_t(t)];
  return tv[0] == v || tv[1] == v || tv[2] == v || tv[3] == v;
}

void VertexTets::build(const TetMesh& mesh) {
  map_.assign(mesh.num_vertices(), TetMesh::kNone);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && !mesh.is_ghost(t)) note(mesh, t);
}

void VertexTets::note(const TetMesh& mesh, uint32_t t) {
  if (map_.size() < mesh.num_vertices()) map_.resize(mesh.num_vertices(), TetMesh::kNone);
  for (int i = 0; i < 4; ++i) map_[mesh.vertex(t, i)] = t;
}

uint32_t VertexTets::known_tet(const TetMesh& mesh, uint32_t v) const {
  const uint32_t t = v < map_.size() ? map_[v] : TetMesh::kNone;
  return t != TetMesh::kNone && tet_has_vertex(mesh, t, v) ? t : TetMesh::kNone;
}

uint32_t VertexTets::tet_of(const TetMesh& mesh, uint32_t v) {
  if (v >= map_.size()) map_.resize(mesh.num_vertices(), TetMesh::kNone);
  const uint32_t t = map_[v];
  if (t == TetMesh::kNone || tet_has_vertex(mesh, t, v)) return t;
  ++rescans;
  map_[v] = TetMesh::kNone;
  for (uint32_t s = 0; s < mesh.num_tet_slots(); ++s)
    if (!mesh.is_ghost(s) && tet_has_vertex(mesh, s, v)) return map_[v] = s;
  return TetMesh::kNone;
}

void vertex_ball(TetMesh& mesh, uint32_t v, uint32_t start, std::vector<uint32_t>& ball) {
  ball.clear();
  if (!tet_has_vertex(mesh, start, v)) return;
  ball.push_back(start);
  mesh.tet_flags[start] |= kBallMark;
  for (size_t k = 0; k < ball.size(); ++k) {
    const uint32_t t = ball[k];
    for (int i = 0; i < 4; ++i) {
      if (mesh.vertex(t, i) == v) continue;  // the facet opposite v does not hold v
      if (mesh.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour) continue;
      const uint32_t n = mesh.neighbour(t, i);
      if (mesh.tet_flags[n] & kBallMark) continue;
      mesh.tet_flags[n] |= kBallMark;
      ball.push_back(n);
    }
  }
  for (uint32_t t : ball) mesh.tet_flags[t] &= uint16_t(~kBallMark);
}

bool vertex_ball_unmarked(const TetMesh& mesh, uint32_t v, uint32_t start, std::vector<uint32_t>& ball,
                          size_t max_tets) {
  ball.clear();
  if (!tet_has_vertex(mesh, start, v)) return false;
  // The tets seen, in an open-addressing table at most half full.
  constexpr size_t kTable = 512;
  max_tets = std::min(max_tets, kTable / 2);
  uint32_t seen[kTable];
  std::fill(std::begin(seen), std::end(seen), TetMesh::kNone);
  auto insert = [&](uint32_t t) {  // false when t was there
    size_t h = (uint64_t(t) * 0x9E3779B97F4A7C15ull) >> 55;  // 9 bits
    while (seen[h] != TetMesh::kNone) {
      if (seen[h] == t) return false;
      h = (h + 1) & (kTable - 1);
    }
    seen[h] = t;
    return true;
  };
  insert(start);
  ball.push_back(start);
  for (size_t k = 0; k < ball.size(); ++k) {
    const uint32_t t = ball[k];
    for (int i = 0; i < 4; ++i) {
      if (mesh.vertex(t, i) == v) continue;
      if (mesh.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour) continue;
      const uint32_t n = mesh.neighbour(t, i);
      if (!insert(n)) continue;
      if (ball.size() == max_tets) return false;
      ball.push_back(n);
    }
  }
  return true;
}

bool edge_ring(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t start, std::vector<uint32_t>& tets,
               std::vector<uint32_t>& ring, size_t max_tets) {
  tets.clear();
  ring.clear();
  if (!tet_has_vertex(mesh, start, a) || !tet_has_vertex(mesh, start, b)) return false;
  uint32_t t = start, x = TetMesh::kNone, y = TetMesh::kNone;
  for (int i = 0; i < 4; ++i) {
    const uint32_t w = mesh.vertex(start, i);
    if (w != a && w != b) (x == TetMesh::kNone ? x : y) = w;
  }
  ring.push_back(x);
  for (int steps = 0; steps < 64; ++steps) {
    tets.push_back(t);
    ring.push_back(y);
    // Leave t through the facet (a b y), opposite x.
    int ix = -1;
    for (int i = 0; i < 4; ++i)
      if (mesh.vertex(t, i) == x) ix = i;
    if (ix < 0 || mesh.tet_adj[4 * size_t(t) + ix] == TetMesh::kNoNeighbour || mesh.facet_protected(t, ix))
      return false;
    const uint32_t n = mesh.neighbour(t, ix);
    if (n == start) {
      ring.pop_back();  // ring[last] == ring[0]
      return ring.size() == tets.size();
    }
    if (tets.size() >= max_tets) return false;
    uint32_t z = TetMesh::kNone;
    for (int i = 0; i < 4; ++i) {
      const uint32_t w = mesh.vertex(n, i);
      if (w != a && w != b && w != y) z = w;
    }
    x = y;
    y = z;
    t = n;
  }
  return false;
}

bool all_positive(const TetMesh& mesh, const std::vector<uint32_t>& tets) {
  for (uint32_t t : tets)
    if (predicates::orient3d(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                             mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3))) <= 0)
      return false;
  return true;
}

namespace {

uint64_t pair_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

}  // namespace

namespace {

// The checks of a replacement that need no marks on the mesh: the old tets live, real and of
// one region, the constrained-edges rule, every new tet real and positive by the exact orient3d
// (vertex `moved` read at moved_to when given). Fills scratch.constrained.
bool fresh_tets_fit(const TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                    ReplaceScratch& scratch, ConstrainedEdges rule, uint32_t moved, const double* moved_to) {
  if (old_tets.empty() || fresh.empty()) return false;
  const int32_t region = mesh.tet_region[old_tets[0]];
  std::vector<uint64_t>& constrained = scratch.constrained;
  constrained.clear();
  for (uint32_t t : old_tets) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t) || mesh.tet_region[t] != region) return false;
    if (!(mesh.tet_flags[t] & tflag::kEdgeConstrainedMask)) continue;
    if (rule == ConstrainedEdges::kRefuse) return false;
    for (int k = 0; k < 6; ++k)
      if (mesh.edge_constrained(t, k))
        constrained.push_back(pair_key(mesh.vertex(t, kEdgeVertex[k][0]), mesh.vertex(t, kEdgeVertex[k][1])));
  }
  auto point = [&](uint32_t x) { return moved_to && x == moved ? moved_to : mesh.point(x); };
  for (const TetVerts& v : fresh) {
    for (uint32_t w : v)
      if (w == TetMesh::kGhost) return false;
    if (predicates::orient3d(point(v[0]), point(v[1]), point(v[2]), point(v[3])) <= 0) return false;
  }
  // Every constrained edge must survive.
  std::sort(constrained.begin(), constrained.end());
  constrained.erase(std::unique(constrained.begin(), constrained.end()), constrained.end());
  for (uint64_t e : constrained) {
    bool found = false;
    for (size_t n = 0; n < fresh.size() && !found; ++n)
      for (int k = 0; k < 6 && !found; ++k)
        found = pair_key(fresh[n][kEdgeVertex[k][0]], fresh[n][kEdgeVertex[k][1]]) == e;
    if (!found) return false;
  }
  return true;
}

std::array<uint32_t, 3> facet_key(uint32_t p, uint32_t q, uint32_t r) {
  std::array<uint32_t, 3> k = {p, q, r};
  std::sort(k.begin(), k.end());
  return k;
}

// The old tets' outer facets t/i (`inside`: whether the neighbour across is an old tet) and the
// new tets' facets into scratch.facets, sorted; false when a protected facet lies between two
// old tets or the new tets do not close up against the old boundary: every key must appear
// exactly twice, (old boundary, new) or (new, new).
template <class Inside>
bool facets_close(const TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  ReplaceScratch& scratch, Inside&& inside) {
  using Facet = ReplaceScratch::Facet;
  std::vector<Facet>& facets = scratch.facets;
  facets.clear();
  for (uint32_t t : old_tets) {
    for (int i = 0; i < 4; ++i) {
      const uint32_t adj = mesh.tet_adj[4 * size_t(t) + i];
      if (adj != TetMesh::kNoNeighbour && inside(uint32_t(adj >> 2))) {
        if (mesh.facet_protected(t, i)) return false;  // a protected facet between two old tets
        continue;
      }
      const int* f = kFacetVertex[i];
      facets.push_back({facet_key(mesh.vertex(t, f[0]), mesh.vertex(t, f[1]), mesh.vertex(t, f[2])), adj, 0,
                        uint8_t(mesh.facet_protected(t, i))});
    }
  }
  for (size_t n = 0; n < fresh.size(); ++n)
    for (int i = 0; i < 4; ++i) {
      const int* f = kFacetVertex[i];
      facets.push_back({facet_key(fresh[n][f[0]], fresh[n][f[1]], fresh[n][f[2]]), 4 * uint32_t(n) + uint32_t(i), 1, 0});
    }
  std::sort(facets.begin(), facets.end(), [](const Facet& x, const Facet& y) {
    return x.key != y.key ? x.key < y.key : x.is_new < y.is_new;
  });
  for (size_t k = 0; k < facets.size(); k += 2) {
    if (k + 1 >= facets.size() || facets[k].key != facets[k + 1].key || !facets[k + 1].is_new) return false;
    if (k + 2 < facets.size() && facets[k + 2].key == facets[k].key) return false;
  }
  return true;
}

}  // namespace

bool replacement_fits(const TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                      ReplaceScratch& scratch, ConstrainedEdges rule, uint32_t moved, const double* moved_to) {
  if (!fresh_tets_fit(mesh, old_tets, fresh, scratch, rule, moved, moved_to)) return false;
  std::vector<uint32_t>& sorted = scratch.sorted_old;
  sorted.assign(old_tets.begin(), old_tets.end());
  std::sort(sorted.begin(), sorted.end());
  return facets_close(mesh, old_tets, fresh, scratch,
                      [&](uint32_t t) { return std::binary_search(sorted.begin(), sorted.end(), t); });
}

bool replace_tets(TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  ReplaceScratch& scratch, ConstrainedEdges rule) {
  using Facet = ReplaceScratch::Facet;
  if (!fresh_tets_fit(mesh, old_tets, fresh, scratch, rule, TetMesh::kNone, nullptr)) return false;
  const int32_t region = mesh.tet_region[old_tets[0]];
  const std::vector<uint64_t>& constrained = scratch.constrained;
  // Marks on the old tets tell the inner facets (faster than replacement_fits' search).
  for (uint32_t t : old_tets) mesh.tet_flags[t] |= kBallMark;
  const bool closes =
      facets_close(mesh, old_tets, fresh, scratch, [&](uint32_t t) { return (mesh.tet_flags[t] & kBallMark) != 0; });
  for (uint32_t t : old_tets) mesh.tet_flags[t] &= uint16_t(~kBallMark);
  if (!closes) return false;
  const std::vector<Facet>& facets = scratch.facets;

  ReplaceScratch::SlotPool& pool = scratch.pool;
  if (scratch.use_pool && pool.free.size() + old_tets.size() + (pool.end - pool.next) < fresh.size()) return false;
  for (uint32_t t : old_tets) {
    if (!scratch.use_pool) {
      mesh.delete_tet(t);
      continue;
    }
    mesh.tet_flags[t] = tflag::kDeleted;
    pool.free.push_back(t);
  }
  std::vector<uint32_t>& created = scratch.created;
  created.clear();
  for (const TetVerts& v : fresh) {
    uint32_t t;
    if (!scratch.use_pool) {
      t = mesh.new_tet(v[0], v[1], v[2], v[3], region);
    } else {
      if (!pool.free.empty()) {
        t = pool.free.back();
        pool.free.pop_back();
      } else {
        t = pool.next++;
      }
      mesh.fill_tet(t, v[0], v[1], v[2], v[3], region);
    }
    for (int k = 0; k < 6 && !constrained.empty(); ++k)
      if (std::binary_search(constrained.begin(), constrained.end(),
                             pair_key(v[kEdgeVertex[k][0]], v[kEdgeVertex[k][1]])))
        mesh.set_edge_constrained(t, k, true);
    created.push_back(t);
  }
  for (size_t k = 0; k < facets.size(); k += 2) {
    const Facet& a = facets[k];
    const Facet& b = facets[k + 1];
    const uint32_t tb = created[b.half_face >> 2];
    const int ib = static_cast<int>(b.half_face & 3);
    if (a.is_new) {
      mesh.link(created[a.half_face >> 2], static_cast<int>(a.half_face & 3), tb, ib);
    } else {
      mesh.tet_adj[4 * size_t(tb) + ib] = a.half_face;
      if (a.half_face != TetMesh::kNoNeighbour) mesh.tet_adj[a.half_face] = 4 * uint32_t(tb) + uint32_t(ib);
      if (a.protect) mesh.set_facet_protected(tb, ib, true);
    }
  }
  return true;
}

uint32_t append_pool_slots(TetMesh& mesh, size_t n) {
  const auto first = static_cast<uint32_t>(mesh.num_tet_slots());
  mesh.tet_v.resize(mesh.tet_v.size() + 4 * n, 0);
  mesh.tet_adj.resize(mesh.tet_adj.size() + 4 * n, TetMesh::kNoNeighbour);
  mesh.tet_flags.resize(mesh.tet_flags.size() + n, tflag::kDeleted);
  mesh.tet_region.resize(mesh.tet_region.size() + n, 0);
  return first;
}

void return_pool_slots(TetMesh& mesh, ReplaceScratch::SlotPool& pool) {
  mesh.free_tets.insert(mesh.free_tets.end(), pool.free.begin(), pool.free.end());
  for (uint32_t t = pool.end; t > pool.next; --t) mesh.free_tets.push_back(t - 1);
  pool.free.clear();
  pool.next = pool.end = 0;
}

bool replace_tets(TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  VertexTets& vt, ReplaceScratch& scratch, ConstrainedEdges rule) {
  if (!replace_tets(mesh, old_tets, fresh, scratch, rule)) return false;
  for (uint32_t t : scratch.created) vt.note(mesh, t);
  return true;
}

}  // namespace anitet::meshops

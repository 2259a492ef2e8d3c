#include "recovery/local_flips.hpp"

#include <algorithm>
#include <array>

#include "core/tet_ops.hpp"
#include "delaunay/delaunay.hpp"
#include "predicates/predicates.hpp"

namespace anitet {

namespace {

constexpr uint32_t kNoNeighbour = TetMesh::kNoNeighbour;

uint64_t pair_key(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t(a) << 32) | b;
}

int orient(const TetMesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  return predicates::orient3d(m.point(a), m.point(b), m.point(c), m.point(d));
}

// The recovery's replace: constrained edges (defended subsegments) must survive a flip.
bool replace(TetMesh& mesh, const std::vector<uint32_t>& old, const std::vector<uint32_t>& fresh,
             std::vector<uint32_t>* created) {
  thread_local meshops::ReplaceScratch scratch;
  thread_local std::vector<meshops::TetVerts> tets;
  tets.clear();
  for (size_t k = 0; k + 3 < fresh.size(); k += 4) tets.push_back({fresh[k], fresh[k + 1], fresh[k + 2], fresh[k + 3]});
  if (!meshops::replace_tets(mesh, old, tets, scratch, meshops::ConstrainedEdges::kKeep)) return false;
  if (created) *created = scratch.created;
  return true;
}

}  // namespace

bool edge_ring(const TetMesh& mesh, uint32_t t, uint32_t p, uint32_t q, EdgeRing& ring, size_t max_size) {
  ring.p = p;
  ring.q = q;
  if (!meshops::edge_ring(mesh, p, q, t, ring.tets, ring.link)) return false;
  if (ring.tets.size() < 3 || ring.tets.size() > max_size) return false;
  for (uint32_t v : ring.link)
    if (v == TetMesh::kGhost) return false;
  if (orient(mesh, p, q, ring.link[0], ring.link[1]) < 0) {
    // Walked the other way round: reverse so that tets[i] holds link[i], link[i+1].
    std::reverse(ring.link.begin(), ring.link.end());
    std::reverse(ring.tets.begin(), ring.tets.end());
    std::rotate(ring.tets.begin(), ring.tets.begin() + 1, ring.tets.end());
  }
  return true;
}

bool flip23(TetMesh& mesh, uint32_t t, int facet, std::vector<uint32_t>* created, const DegeneracyOracle* oracle) {
  if (mesh.is_ghost(t) || mesh.facet_protected(t, facet)) return false;
  const uint32_t adj = mesh.tet_adj[4 * size_t(t) + facet];
  if (adj == kNoNeighbour) return false;
  const auto n = static_cast<uint32_t>(adj >> 2);
  if (mesh.is_ghost(n)) return false;
  const uint32_t a = mesh.vertex(t, facet), b = mesh.vertex(n, static_cast<int>(adj & 3));
  uint32_t f[3];
  for (int k = 0; k < 3; ++k) f[k] = mesh.vertex(t, kFacetVertex[facet][k]);
  // f's normal points into t (towards a): the new tets (f_k f_k+1 b a) are positive exactly when
  // segment ab crosses f's interior.
  std::vector<uint32_t> fresh;
  for (int k = 0; k < 3; ++k) {
    const uint32_t u = f[k], w = f[(k + 1) % 3];
    // A tet the oracle calls flat is refused, as one with a zero volume is.
    if (oracle && oracle->flat(u, w, b, a)) return false;
    for (uint32_t v : {u, w, b, a}) fresh.push_back(v);
  }
  return replace(mesh, {t, n}, fresh, created);
}

bool remove_edge(TetMesh& mesh, const EdgeRing& ring, const uint32_t* want, int want_n,
                 std::vector<uint32_t>* created, const DegeneracyOracle* oracle) {
  const size_t n = ring.link.size();
  if (n < 3) return false;
  // Edge pq must not be a constraint and no facet (p q link[i]) protected.
  for (uint32_t t : ring.tets) {
    for (int k = 0; k < 6; ++k) {
      const uint32_t a = mesh.vertex(t, kEdgeVertex[k][0]), b = mesh.vertex(t, kEdgeVertex[k][1]);
      if (pair_key(a, b) == pair_key(ring.p, ring.q) && mesh.edge_constrained(t, k))
        return false;
    }
    for (int i = 0; i < 4; ++i) {
      const uint32_t opp = mesh.vertex(t, i);
      if (opp != ring.p && opp != ring.q && mesh.facet_protected(t, i)) return false;
    }
  }
  // Rotate the link so that want[0] is vertex 0; positions of the other wanted vertices.
  size_t rot = 0;
  int pos[3] = {0, 0, 0};
  if (want_n > 0) {
    const auto it = std::find(ring.link.begin(), ring.link.end(), want[0]);
    if (it == ring.link.end()) return false;
    rot = static_cast<size_t>(it - ring.link.begin());
    for (int k = 1; k < want_n; ++k) {
      const auto jt = std::find(ring.link.begin(), ring.link.end(), want[k]);
      if (jt == ring.link.end()) return false;
      pos[k] = static_cast<int>((static_cast<size_t>(jt - ring.link.begin()) + n - rot) % n);
    }
    if (want_n == 3 && pos[1] > pos[2]) std::swap(pos[1], pos[2]);
  }
  // Vertex of extended index i (0..n, index n is vertex 0 again).
  auto V = [&](int i) { return ring.link[(rot + static_cast<size_t>(i)) % n]; };
  auto tri_ok = [&](int i, int k, int j) {
    return orient(mesh, V(i), V(k), V(j), ring.q) > 0 && orient(mesh, V(i), V(j), V(k), ring.p) > 0 &&
           !(oracle && (oracle->flat(V(i), V(k), V(j), ring.q) || oracle->flat(V(i), V(j), V(k), ring.p)));
  };
  // ok[i][j]: the sub-polygon i..j (closed by the chord j-i) has a valid triangulation; split[i][j]
  // its apex on the chord.
  const int N = static_cast<int>(n);
  std::vector<int8_t> ok((n + 1) * (n + 1), 0);
  std::vector<int8_t> split((n + 1) * (n + 1), -1);
  auto OK = [&](int i, int j) -> int8_t& { return ok[size_t(i) * (n + 1) + size_t(j)]; };
  auto SPLIT = [&](int i, int j) -> int8_t& { return split[size_t(i) * (n + 1) + size_t(j)]; };
  for (int i = 0; i < N; ++i) OK(i, i + 1) = 1;
  for (int len = 2; len <= N; ++len)
    for (int i = 0; i + len <= N; ++i) {
      const int j = i + len;
      if (i == 0 && j == N) continue;  // not a polygon: vertex 0 twice
      for (int k = i + 1; k < j && !OK(i, j); ++k)
        if (OK(i, k) && OK(k, j) && tri_ok(i, k, j)) {
          OK(i, j) = 1;
          SPLIT(i, j) = static_cast<int8_t>(k);
        }
    }
  std::vector<std::array<int, 3>> tris;
  std::vector<std::array<int, 2>> todo;
  if (want_n == 0) {
    if (!OK(0, N - 1)) return false;
    todo.push_back({0, N - 1});
  } else if (want_n == 2) {
    const int m = pos[1];
    if (m <= 1 || m >= N - 1 || !OK(0, m) || !OK(m, N)) return false;  // a side is no new edge
    todo.push_back({0, m});
    todo.push_back({m, N});
  } else {
    const int b = pos[1], c = pos[2];
    if (!(0 < b && b < c && c < N) || !tri_ok(0, b, c) || !OK(0, b) || !OK(b, c) || !OK(c, N)) return false;
    tris.push_back({0, b, c});
    todo.push_back({0, b});
    todo.push_back({b, c});
    todo.push_back({c, N});
  }
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j - i < 2) continue;
    const int k = SPLIT(i, j);
    tris.push_back({i, k, j});
    todo.push_back({i, k});
    todo.push_back({k, j});
  }
  std::vector<uint32_t> fresh;
  for (const auto& tr : tris) {
    for (uint32_t v : {V(tr[0]), V(tr[1]), V(tr[2]), ring.q}) fresh.push_back(v);
    for (uint32_t v : {V(tr[0]), V(tr[2]), V(tr[1]), ring.p}) fresh.push_back(v);
  }
  return replace(mesh, ring.tets, fresh, created);
}

// Makes (u w) an edge by one flip, when one does it: a 2-3 flip of the facet opposite u in a tet
// whose neighbour there has apex w, or the removal of an edge of such a facet whose ring holds w.
bool flip_in_edge(TetMesh& mesh, uint32_t u, uint32_t w, const std::vector<uint32_t>& ball,
                  std::vector<uint32_t>& created, const DegeneracyOracle* oracle) {
  const std::vector<uint32_t> tets = ball;  // the flips change the mesh under it
  EdgeRing ring;
  const uint32_t want[2] = {u, w};
  for (uint32_t t : tets) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    int i = 0;
    while (mesh.vertex(t, i) != u) ++i;
    const uint32_t adj = mesh.tet_adj[4 * size_t(t) + i];
    if (adj == TetMesh::kNoNeighbour) continue;
    const uint32_t n = static_cast<uint32_t>(adj >> 2);
    if (!mesh.is_ghost(n) && mesh.vertex(n, static_cast<int>(adj & 3)) == w) {
      if (flip23(mesh, t, i, &created, oracle)) return true;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = mesh.vertex(t, kFacetVertex[i][k]), q = mesh.vertex(t, kFacetVertex[i][(k + 1) % 3]);
      if (!edge_ring(mesh, t, p, q, ring)) continue;
      if (std::find(ring.link.begin(), ring.link.end(), w) == ring.link.end()) continue;
      if (remove_edge(mesh, ring, want, 2, &created, oracle)) return true;
    }
  }
  return false;
}

// Makes triangle (a b c), whose edges are present, a facet by removing one edge whose ring holds
// all three (the 3-2 flip when the ring is just a b c).
bool flip_in_face(TetMesh& mesh, uint32_t a, uint32_t b, uint32_t c, const std::vector<uint32_t>& ball,
                  std::vector<uint32_t>& created, const DegeneracyOracle* oracle) {
  const std::vector<uint32_t> tets = ball;  // the flips change the mesh under it
  EdgeRing ring;
  const uint32_t want[3] = {a, b, c};
  for (uint32_t t : tets) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
    int i = 0;
    while (mesh.vertex(t, i) != a) ++i;
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = mesh.vertex(t, kFacetVertex[i][k]), q = mesh.vertex(t, kFacetVertex[i][(k + 1) % 3]);
      if (p == b || p == c || q == b || q == c) continue;
      if (!edge_ring(mesh, t, p, q, ring)) continue;
      const auto has = [&](uint32_t v) { return std::find(ring.link.begin(), ring.link.end(), v) != ring.link.end(); };
      if (!has(b) || !has(c)) continue;
      if (remove_edge(mesh, ring, want, 3, &created, oracle)) return true;
    }
  }
  return false;
}


}  // namespace anitet

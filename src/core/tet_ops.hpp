// Local topological operations on a TetMesh, shared by boundary recovery (flips), refinement
// (edge collapse) and optimization (flips, vertex moves):
//   - a vertex -> tet map kept up to date by the operations,
//   - the ball of a vertex and the ring of tets around an edge,
//   - replace_tets(): swap a set of tets for another set filling the same region; every new tet
//     must be positive by the exact orient3d and every boundary facet of the old set must be
//     matched by exactly one new facet, so a rejected operation leaves the mesh untouched.
// Protected facets and facets without neighbour are carried over, never created or removed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"

namespace anitet::meshops {

// True when t is live and holds vertex v.
bool tet_has_vertex(const TetMesh& mesh, uint32_t t, uint32_t v);

// One live tet per vertex (kNone: the vertex is in no tet, e.g. removed by a collapse).
class VertexTets {
 public:
  void build(const TetMesh& mesh);
  // Sized for every vertex of the mesh, so that note() on disjoint vertices may run concurrently.
  void reserve(const TetMesh& mesh) {
    if (map_.size() < mesh.num_vertices()) map_.resize(mesh.num_vertices(), TetMesh::kNone);
  }
  // A live tet holding v; repairs a stale entry by a scan of the mesh (rare).
  uint32_t tet_of(const TetMesh& mesh, uint32_t v);
  // The entry of v when it is a live tet holding v, else kNone (no repair: callers on several
  // threads may ask at once).
  uint32_t known_tet(const TetMesh& mesh, uint32_t v) const;
  void note(const TetMesh& mesh, uint32_t t);  // t's vertices now point at t
  void forget(uint32_t v) { if (v < map_.size()) map_[v] = TetMesh::kNone; }
  bool removed(uint32_t v) const { return v < map_.size() && map_[v] == TetMesh::kNone; }
  size_t rescans = 0;

 private:
  std::vector<uint32_t> map_;
};

// The tets holding v (a traversal across the facets through v, from a tet holding v).
void vertex_ball(TetMesh& mesh, uint32_t v, uint32_t start, std::vector<uint32_t>& ball);
// The same traversal (the same tets in the same order) without marking the mesh, so that
// several threads may run it at once; false, `ball` incomplete, when v has more than max_tets
// tets, or than 256 (it keeps the tets seen in a small table on the stack).
bool vertex_ball_unmarked(const TetMesh& mesh, uint32_t v, uint32_t start, std::vector<uint32_t>& ball,
                          size_t max_tets);

// The tets around edge ab, in order, and the ring vertices: ring[i] and ring[i+1] are the other
// two vertices of tets[i]. False when the edge touches a facet without neighbour or a protected
// facet (an edge of the mesh boundary), or a tet of the ring is not found. Ghost tets are not
// special here: their ghost vertex shows in `ring`. Also false, as soon as it is known, when the
// ring has more than max_tets tets (a caller that only wants rings of 3 stops after 3 steps).
bool edge_ring(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t start, std::vector<uint32_t>& tets,
               std::vector<uint32_t>& ring, size_t max_tets = 64);

using TetVerts = std::array<uint32_t, 4>;

// Scratch memory of replace_tets (reuse one per loop).
struct ReplaceScratch {
  struct Facet {
    std::array<uint32_t, 3> key;  // sorted vertex ids
    uint32_t half_face;           // old boundary: the outside half-face; new: 4*index + facet
    uint8_t is_new;
    uint8_t protect;
  };
  std::vector<Facet> facets;
  std::vector<uint64_t> constrained;  // constrained edges of the old tets (vertex pair keys)
  std::vector<uint32_t> created;
  std::vector<uint32_t> sorted_old;  // replacement_fits
  // Slots of one task among several replacing tets at once (the mesh's own free list and arrays
  // are not touched while they run): the old tets' slots go to `free`, new tets come from `free`,
  // then from [next, end). A replacement that needs more fails (mesh unchanged). Unused when
  // `use_pool` is false.
  struct SlotPool {
    std::vector<uint32_t> free;
    uint32_t next = 0, end = 0;
  };
  bool use_pool = false;
  SlotPool pool;
};

// Appends n slots to the mesh's arrays, deleted but not on its free list (for SlotPools); returns
// the first.
uint32_t append_pool_slots(TetMesh& mesh, size_t n);
// Gives a pool's unused slots back to the mesh's free list (its free slots in order, then its
// unused range from the top down) and empties it.
void return_pool_slots(TetMesh& mesh, ReplaceScratch::SlotPool& pool);

// What replace_tets does with the constrained-edge bits of the old tets.
enum class ConstrainedEdges : uint8_t {
  kRefuse,  // fail when an old tet has one (refinement, optimization: S's edges never move)
  kKeep,    // every constrained edge must be an edge of the new tets, which get its bit
};

// Replaces the live, non-ghost tets `old_tets` (one region) by `fresh` (given in positive
// orientation, no ghost vertex). Fails (mesh unchanged) when a new tet is not positive by the
// exact orient3d, the new tets do not close up against the old boundary, a protected facet lies
// between two old tets, or the constrained edges rule says no. On success scratch.created lists
// the new tet ids (in the order of `fresh`).
bool replace_tets(TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  ReplaceScratch& scratch, ConstrainedEdges rule = ConstrainedEdges::kRefuse);
// Whether replace_tets would succeed, without changing anything (several threads may ask at
// once, each with its own scratch), with vertex `moved` read at moved_to when that is given (a
// move tried before it is made). The pool is not looked at.
bool replacement_fits(const TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                      ReplaceScratch& scratch, ConstrainedEdges rule, uint32_t moved = TetMesh::kNone,
                      const double* moved_to = nullptr);
// The same, also pointing the new tets' vertices at them in vt.
bool replace_tets(TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  VertexTets& vt, ReplaceScratch& scratch, ConstrainedEdges rule = ConstrainedEdges::kRefuse);

// Exact check that every tet of `tets` is positive.
bool all_positive(const TetMesh& mesh, const std::vector<uint32_t>& tets);

}  // namespace anitet::meshops

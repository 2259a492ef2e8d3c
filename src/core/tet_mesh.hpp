// TetMesh: the flat-array tetrahedral mesh every meshing stage works on.
//
// Local numbering of a tet t with vertices v0 v1 v2 v3 (tet_v[4t+i]):
//
//                 v3
//                /|\          positive orientation: orient3d(v0, v1, v2, v3) > 0, i.e.
//               / | \         (v1-v0) x (v2-v0) . (v3-v0) > 0.
//              /  |  \        (v0 v1 v2 turn counter-clockwise seen from v3)
//            v0---|---v2      facet i is the triangle opposite vertex i.
//              \  |  /        kFacetVertex[i] lists it oriented so that its normal (right-hand
//               \ | /         rule) points INTO the tet: orient3d(f0, f1, f2, vi) > 0.
//                \|/            facet 0 = (v1 v3 v2)   facet 1 = (v0 v2 v3)
//                 v1            facet 2 = (v0 v3 v1)   facet 3 = (v0 v1 v2)
//
// Adjacency is by half-faces: tet_adj[4t+i] = 4*n + j means facet i of t is facet j of tet n, in
// 32 bits (16 bytes per tet, not 32: the largest array per tet, issue 49), so a mesh holds at most
// kMaxTetSlots tet slots.
// A ghost vertex (kGhost) closes the convex hull: every hull facet has a ghost tet behind it, so
// every facet of a live tet has a neighbour. A ghost tet keeps the ghost in slot 3 (its facet 3
// is the hull triangle, seen from the ghost's side).
//
// tet_flags[t]: bits 0-3 "facet i is protected" (a constraint face: cavities stop there),
// bits 4-9 "edge k is constrained" (edges in kEdgeVertex order), bits 10-14 scratch marks of a
// running algorithm (zero between calls), bit 15 "deleted" (on the free list, slot free for reuse).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

namespace vflag {
constexpr uint8_t kOnInputSurface = 1u << 0;  // a vertex of S: never moved or removed
constexpr uint8_t kOnFront = 1u << 1;         // a vertex of S1
constexpr uint8_t kBoundaryLayer = 1u << 2;
constexpr uint8_t kLocked = 1u << 3;
}  // namespace vflag

namespace tflag {
constexpr uint16_t kFacetProtectedMask = 0x000f;
constexpr uint16_t kEdgeConstrainedShift = 4;
constexpr uint16_t kEdgeConstrainedMask = 0x03f0;
// The bit of a tet's edge k (kEdgeVertex order): a constrained edge, which no flip or cavity
// removes (a subsegment of an input edge).
constexpr uint16_t edge_constrained_bit(int k) { return uint16_t(1u << (kEdgeConstrainedShift + k)); }
constexpr uint16_t kScratchMask = 0x7c00;  // transient marks of a running algorithm
constexpr uint16_t kDeleted = 1u << 15;
}  // namespace tflag

constexpr int kFacetVertex[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
constexpr int kEdgeVertex[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

class TetMesh {
 public:
  static constexpr uint32_t kGhost = 0xfffffffeu;  // the ghost vertex
  static constexpr uint32_t kNone = 0xffffffffu;   // no vertex / no tet
  static constexpr uint32_t kNoNeighbour = ~uint32_t(0);
  // 4 * slot + facet stays below kNoNeighbour.
  static constexpr size_t kMaxTetSlots = size_t(1) << 30;

  std::vector<double> xyz;         // 3 per vertex
  std::vector<uint8_t> vflags;     // 1 per vertex, vflag bits
  std::vector<uint32_t> tet_v;     // 4 per tet slot
  std::vector<uint32_t> tet_adj;   // 4 per tet slot, 4*neighbour + facet
  std::vector<uint16_t> tet_flags; // 1 per tet slot, tflag bits
  std::vector<int32_t> tet_region; // 1 per tet slot
  std::vector<uint32_t> free_tets; // deleted slots, reused first

  size_t num_vertices() const { return xyz.size() / 3; }
  size_t num_tet_slots() const { return tet_v.size() / 4; }
  // Live tets, ghosts included.
  size_t num_live_tets() const { return num_tet_slots() - free_tets.size(); }

  // Room for `tets` tet slots in the four tet arrays at once: filled by new_tet one tet at a time,
  // they would end with up to twice the capacity they need, copied as they grew.
  void reserve_tets(size_t tets) {
    tet_v.reserve(4 * tets);
    tet_adj.reserve(4 * tets);
    tet_flags.reserve(tets);
    tet_region.reserve(tets);
  }

  uint32_t add_vertex(const double p[3], uint8_t flags = 0);
  const double* point(uint32_t v) const { return &xyz[3 * size_t(v)]; }

  // A new tet slot (reused from the free list when possible), adjacency unset.
  uint32_t new_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t region = 0);
  // Fills existing slot t with the tet a b c d: no neighbours, no flags, `region` (new_tet() and
  // the callers that take slots from pools of their own).
  void fill_tet(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t d, int32_t region = 0);
  void delete_tet(uint32_t t);

  bool is_deleted(uint32_t t) const { return (tet_flags[t] & tflag::kDeleted) != 0; }
  bool is_ghost(uint32_t t) const { return tet_v[4 * size_t(t) + 3] == kGhost; }
  uint32_t vertex(uint32_t t, int i) const { return tet_v[4 * size_t(t) + i]; }
  // kNone across a facet without a neighbour.
  uint32_t neighbour(uint32_t t, int i) const {
    const uint32_t a = tet_adj[4 * size_t(t) + i];
    return a == kNoNeighbour ? kNone : a >> 2;
  }
  int neighbour_facet(uint32_t t, int i) const { return static_cast<int>(tet_adj[4 * size_t(t) + i] & 3); }
  void link(uint32_t t, int i, uint32_t n, int j) {
    tet_adj[4 * size_t(t) + i] = 4 * n + uint32_t(j);
    tet_adj[4 * size_t(n) + j] = 4 * t + uint32_t(i);
  }
  bool facet_protected(uint32_t t, int i) const { return (tet_flags[t] >> i) & 1u; }
  bool edge_constrained(uint32_t t, int k) const { return (tet_flags[t] & tflag::edge_constrained_bit(k)) != 0; }
  void set_edge_constrained(uint32_t t, int k, bool on) {
    if (on) tet_flags[t] |= tflag::edge_constrained_bit(k);
    else tet_flags[t] &= uint16_t(~tflag::edge_constrained_bit(k));
  }
  void set_facet_protected(uint32_t t, int i, bool on) {
    if (on) tet_flags[t] |= uint16_t(1u << i);
    else tet_flags[t] &= uint16_t(~(1u << i));
  }

  // Builds the adjacency of all live tets by matching facets (used after bulk construction and by
  // readers); facets without a partner get kNoNeighbour. Fails on a facet shared by > 2 tets.
  Status build_adjacency();

  // The live non-ghost tets as a compact VolumeMesh, in slot order. Vertices keep their order;
  // with drop_unused_vertices those of no tet are dropped and the rest renumbered, and
  // `vertex_map` (when given) gets old id -> new id (kNone for a dropped one).
  VolumeMesh to_volume_mesh(bool drop_unused_vertices = true, std::vector<uint32_t>* vertex_map = nullptr) const;
  // The same with boundary triangles (3 vertex ids of this mesh each, one patch label each)
  // renumbered with the vertices: their vertices are never dropped, so a triangle that is no face
  // of the tets stays in the output for the writers' check to find.
  VolumeMesh to_volume_mesh(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                            const std::vector<int32_t>& bnd_patch, std::vector<uint32_t>* vertex_map = nullptr) const;
  // The same, made of this mesh's own arrays, compacted in place (no second copy of the tets: the
  // pipeline's output, at the end of a run, issue 49); the mesh is left empty.
  VolumeMesh take_volume_mesh(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                              const std::vector<int32_t>& bnd_patch, std::vector<uint32_t>* vertex_map = nullptr);
  static TetMesh from_volume_mesh(const VolumeMesh& m);

 private:
  // to_volume_mesh's vertex numbers: remap[v] is v's output id, kNone for a dropped vertex.
  void number_output_vertices(bool drop_unused_vertices, const std::vector<uint32_t>& bnd_tri,
                              std::vector<uint32_t>& remap) const;
};

struct MeshCheckOptions {
  bool check_delaunay = false;        // exact empty-sphere test on every interior facet
  bool require_closed = false;        // every facet of a non-ghost tet has a neighbour
  // Ghost tets close a convex hull: each ghost's hull facet has a real tet behind it and ghosts
  // beside it, and the hull is locally convex at every hull edge (coplanar facets allowed).
  // Implied by check_delaunay (local Delaunay facets plus a convex hull make a Delaunay mesh).
  bool check_convex_hull = false;
};

// Structural and geometric audit: adjacency symmetric and facets matching, every non-ghost tet
// positive by exact orient3d, no vertex index out of range, deleted slots on the free list,
// protected flags agreeing on both sides of a facet, and (optionally) the Delaunay property and
// the convexity of the hull closed by the ghost tets.
// Returns the first problems found in the message.
Status check_mesh(const TetMesh& mesh, const MeshCheckOptions& options = {});

}  // namespace anitet

// Local topological operations on a TetMesh without ghost tets, shared by refinement (edge
// collapse) and optimization (flips, vertex moves):
//   - a vertex -> tet map kept up to date by the operations,
//   - the ball of a vertex and the ring of tets around an edge,
//   - replace_tets(): swap a set of tets for another set filling the same region; every new tet
//     must be positive by the exact orient3d and every boundary facet of the old set must be
//     matched by exactly one new facet, so a rejected operation leaves the mesh untouched.
// Protected facets (S) and facets without neighbour are carried over, never created or removed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"

namespace anitet::meshops {

// Radius ratio 3 r_in / R_circ of (a b c d), in floating point: 1 for the regular tet, <= 0 when
// the tet is flat or negatively oriented (so that it also ranks inverted candidates).
double radius_ratio(const double* a, const double* b, const double* c, const double* d);
double tet_radius_ratio(const TetMesh& mesh, uint32_t t);

// The shape measure the optimizer maximizes: min(radius ratio, smallest sine of the six dihedral
// angles / sin(acos(1/3))) -- 1 for the regular tet; the sine term also catches the tets with a
// small or a large dihedral angle that the radius ratio ranks fairly well. <= 0 when inverted.
double shape_quality(const double* a, const double* b, const double* c, const double* d);
double tet_shape_quality(const TetMesh& mesh, uint32_t t);

// True when t is live and holds vertex v.
bool tet_has_vertex(const TetMesh& mesh, uint32_t t, uint32_t v);

// One live tet per vertex (kNone: the vertex is in no tet, e.g. removed by a collapse).
class VertexTets {
 public:
  void build(const TetMesh& mesh);
  // A live tet holding v; repairs a stale entry by a scan of the mesh (rare).
  uint32_t tet_of(const TetMesh& mesh, uint32_t v);
  void note(const TetMesh& mesh, uint32_t t);  // t's vertices now point at t
  void forget(uint32_t v) { if (v < map_.size()) map_[v] = TetMesh::kNone; }
  bool removed(uint32_t v) const { return v < map_.size() && map_[v] == TetMesh::kNone; }
  size_t rescans = 0;

 private:
  std::vector<uint32_t> map_;
};

// The tets holding v (a traversal across the facets through v, from a tet holding v).
void vertex_ball(TetMesh& mesh, uint32_t v, uint32_t start, std::vector<uint32_t>& ball);

// The tets around edge ab, in order, and the ring vertices: ring[i] and ring[i+1] are the other
// two vertices of tets[i]. False when the edge touches a facet without neighbour or a protected
// facet (an edge of the mesh boundary), or a tet of the ring is not found.
bool edge_ring(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t start, std::vector<uint32_t>& tets,
               std::vector<uint32_t>& ring);

using TetVerts = std::array<uint32_t, 4>;

// Scratch memory of replace_tets (reuse one per loop).
struct ReplaceScratch {
  struct Facet {
    std::array<uint32_t, 3> key;  // sorted vertex ids
    uint64_t half_face;           // old boundary: the outside half-face; new: 4*index + facet
    uint8_t is_new;
    uint8_t protect;
  };
  std::vector<Facet> facets;
  std::vector<uint32_t> created;
};

// Replaces the tets `old_tets` (live, one region, no constrained edge) by `fresh` (given in
// positive orientation). Fails (mesh unchanged) when a new tet is not positive by the exact
// orient3d or the new tets do not close up against the old boundary. On success
// scratch.created lists the new tet ids (in the order of `fresh`) and vt is updated.
bool replace_tets(TetMesh& mesh, const std::vector<uint32_t>& old_tets, const std::vector<TetVerts>& fresh,
                  VertexTets& vt, ReplaceScratch& scratch);

// Exact check that every tet of `tets` is positive.
bool all_positive(const TetMesh& mesh, const std::vector<uint32_t>& tets);

// Lowest shape_quality over the tets.
double min_quality(const TetMesh& mesh, const std::vector<uint32_t>& tets);

}  // namespace anitet::meshops

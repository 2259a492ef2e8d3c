// Stage 3a: coupling (paper, section 5.1 and Table 1). Joins T1 (the layers of stage 1, bounded by
// S and the front S1) and T2 (stage 2: the Delaunay mesh inside S1 with S1 recovered conformingly
// as S2) into one conformal mesh. S2 may split S1's edges and faces with Steiner points; T1 is
// split to match:
//   1. every Steiner point on an S1 edge splits all T1 tets around that edge (an edge split: each
//      tet abxy becomes amxy and mbxy), in order along the edge;
//   2. every S1 face F whose pieces in T1 still differ from its subfaces in S2 has its T1 tets
//      (all share the apex v of the one T1 tet on F, Claim 5.2; edge splits keep it) replaced by
//      the cone from v over F's S2 subfaces (Table 1: v F_i for every F_i in F).
// No tet with a face on S is touched: S and S1 share no vertex, so no edge or face of S is split
// (Lemma 5.1). Every new tet is checked positive with the exact orient3d; a Steiner point that
// would make one non-positive is reported as an error, never accepted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "layers/layers.hpp"
#include "recovery/recovery.hpp"

namespace anitet {

struct CoupleStats {
  size_t edge_steiner_points = 0;  // Steiner points on S1 edges
  size_t face_steiner_points = 0;  // Steiner points inside S1 faces
  size_t edge_split_tets = 0;      // T1 tets split by edge splits
  size_t faces_reconed = 0;        // S1 faces whose T1 tets were replaced by the cone over S2
  size_t t1_tets = 0, t2_tets = 0, tets = 0;
  size_t bodies = 0;   // connected bodies (regions 0 .. bodies - 1)
  size_t bl_tets = 0;  // boundary-layer tets (regions bodies .. 2 bodies - 1)
  double seconds = 0.0;
};

struct CoupledMesh {
  // T1' and T2 in one mesh: T1's vertices first (the input's own at the start, flagged
  // vflag::kOnInputSurface), then the Steiner points of T2. No ghost tets; adjacency built; the
  // facets on S have no neighbour and are protected. Tet regions: one per connected body,
  // numbered 0 .. bodies - 1 by the smallest input triangle bounding it; the boundary-layer tets
  // (T1 tets with a nonzero region, see BoundaryLayerOptions::region) of body k get region
  // bodies + k (1 for the usual single body) and their vertices vflag::kBoundaryLayer.
  TetMesh mesh;
  CoupleStats stats;
};

// surface: S (stage 1's input); t1: stage 1's output; s1_vertex_map: front_surface()'s map from
// S1 vertex ids (the ids stage 2 saw) to T1 ids; t2: recover_boundary() run on that S1.
Result<CoupledMesh> couple_meshes(const SurfaceMesh& surface, LayersOutput t1,
                                  const std::vector<uint32_t>& s1_vertex_map, const RecoveryOutput& t2);

}  // namespace anitet

// Conforming boundary recovery (paper, section 4): the Delaunay tetrahedralization of a closed
// surface's points, with Steiner points inserted ON the surface's edges and faces through the
// modified Delaunay kernel (PointInserter) until every input edge is a chain of mesh edges and
// every input face a union of protected mesh facets; then the tets outside the domain are removed.
//
// Exactness. A Steiner point is computed in floating point (a point of an input segment, or of an
// input triangle) and is in general not exactly on the segment or the plane. The recovery is
// therefore combinatorial: the subfaces of an input face F are the mesh triangles whose three
// vertices are all F's corners or Steiner points hosted by F or its edges, and F is recovered when
// they triangulate F's boundary chain plus its Steiner points (a disk whose boundary is exactly the
// chain of F's subsegments). Every tet is positive by the exact orient3d (the kernel guarantees it),
// so the recovered surface S2 is a valid closed polyhedral surface lying within rounding of S.
//
// Claim 5.1 of the paper: every subface of S2 carries the id of the one input face it lies in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"

namespace anitet {

struct RecoveryOptions {
  uint64_t seed = 0x5eed;
  size_t max_passes = 400;          // sweeps over the missing constraints before giving up
  double max_seconds = 120;         // and a wall-time safety net (the caps above bound the work)
  double max_steiner_per_face = 24; // Steiner cap: this many per input triangle (+ 1000)
  bool remove_outside = true;      // false: keep the whole convex hull and the ghost tets
  // Mark each subsegment constrained as soon as it is present, so that the kernel keeps it. Off
  // at first: it stalls on some surfaces (face points blocked by defended edges) where splitting
  // destroyed subsegments again works; the last retry uses it.
  bool defend_edges = false;
  // Try flips (2-3, edge removal) before Steiner points for a missing edge or an unsplit face.
  // Off at first: flips save many Steiner points on some surfaces but make others stall in the
  // face phase. The retry below uses them.
  bool use_flips = false;
  // When the recovery fails with the options above, start again with use_flips, then again with
  // defend_edges (each from scratch); the split strategy, again with split_crossing_flips = 3 and
  // split_edge_crossings switched, then again as asked without split_exact_degeneracies.
  // RecoveryStats::strategy tells which one succeeded.
  bool retry_strategies = true;
  // First recover by splitting the constraint triangles themselves (split_recovery.hpp): every
  // decision combinatorial. When it fails (or is off), the fuzzy-face strategies above run when
  // fuzzy_faces is on, each from scratch.
  bool split_constraints = true;
  bool fuzzy_faces = true;
  // Its own wall-time safety net (the fallbacks get max_seconds each); the cascade test and the
  // Steiner cap below stop it first, within seconds, on the surfaces it cannot do.
  double split_max_seconds = 120;
  double split_max_steiner_per_face = 6;  // and Steiner cap (+ 1000): its successes need ~1
  // A missing input-edge subsegment gets one flip before a split, and a missing triangle whose
  // edges are present one edge removal (fewer Steiner points).
  bool split_flips = true;
  // A missing constraint edge is split at a point of it that a walk from one end shows to be
  // joined to that end (the cavity reaches back to it), instead of at its middle or a
  // power-of-two distance, which recovers only Delaunay pieces and cascades on needle triangles
  // (stage 1 fronts over CAD parts).
  bool split_walk = true;
  // The walk's chain of tets joins the cavity of its point whatever the empty-sphere test says
  // (InsertOptions::force_keep): a point far along a missing edge is joined to the edge's end
  // through tets that are not Delaunay, where the empty-sphere rule stops the walk within a step
  // or two on needle fans.
  bool split_forced_walk = true;
  // A missing edge that runs through (or near) an edge of the first facet it meets
  // is split where it passes that edge, the edge's ring forced into the cavity, before the walk's
  // points are tried (the walk's points creep towards such a crossing without reaching it).
  bool split_edge_crossings = true;
  // An input-edge subsegment is marked constrained (the kernel keeps it) as soon as a sweep finds
  // it present, and so are the pieces of a split: later points no longer destroy what earlier ones
  // recovered. Otherwise, on needle-rich fronts, the count of missing edges can grow from pass to
  // pass up to the Steiner cap.
  bool split_defend_edges = true;
  // A missing edge inside an input face that flips within the face do not make is made by flips
  // of the mesh along it, or split (with its two triangles) like an input edge.
  bool split_face_edges = true;
  // How many times a missing triangle's crossing edges are removed (edge removals) before it is
  // split instead. No one count recovers every front: when the split strategy fails with 1, it
  // runs again with 3 (retry_strategies).
  int split_crossing_flips = 1;
  // First split the long edge of every input triangle with an angle above this at the apex's
  // projection (180: never).
  double split_cap_degrees = 170.0;
  // No insertion may make a tet that is flat in exact geometry: three points of one input
  // segment, or four of one plane of exactly coplanar input triangles (DegeneracyOracle).
  bool split_exact_degeneracies = true;
  // Optional, 3 per input triangle: a point each piece of that triangle must see on the side its
  // orientation gives it as the triangle does (the pipeline gives the T1 apex of each S1 face, so
  // that every cone of the coupling is positive). The split strategy refuses a split or flip
  // that breaks it and tries another point. Empty: no such guard.
  std::vector<double> face_apex;
  // A boundary subsegment of a face that no subface uses gets a face point just inside it even
  // when no coplanar vertex explains the gap.
  bool apex_always = true;
};

// Where a vertex of the result lies on the input surface.
enum class SteinerHost : uint8_t { kEdge = 0, kFace = 1 };

struct SteinerPoint {
  uint32_t vertex;    // mesh vertex id (>= number of input vertices)
  SteinerHost host;
  uint32_t host_id;   // kEdge: index into RecoveryOutput::input_edges / 2; kFace: input triangle id
};

struct RecoveryStats {
  size_t input_vertices = 0, input_triangles = 0;
  size_t steiner_on_edges = 0, steiner_on_faces = 0;
  size_t passes = 0;
  // 3: split constraints (the first try by default), 4: split constraints retried with more
  // crossing-edge removals and split_edge_crossings switched, 5: split constraints retried without
  // split_exact_degeneracies; 0: fuzzy faces with the options as given, 1: retried with flips, 2:
  // with defended edges
  size_t strategy = 0;
  size_t caps_split = 0;          // split constraints: caps split at their apex's projection
  size_t flips = 0;               // constraints recovered by a flip instead of a point
  size_t walk_splits = 0;         // split constraints: edges split at a walk's point (split_walk)
  size_t edge_crossing_splits = 0;  // of which: where the segment passes a mesh edge (its ring forced)
  size_t blocked_insertions = 0;  // insertions the kernel refused (another point was tried)
  size_t early_refusals = 0;      // of which refused before their cavity grew (InsertOptions::early_refusal)
  size_t tets = 0;                // tets of the result
  size_t regions = 0;
  double seconds_delaunay = 0, seconds_recovery = 0, seconds_carve = 0, seconds_total = 0;
};

struct RecoveryOutput {
  // Vertices 0..n-1 are the input vertices, then the Steiner points. After remove_outside: no
  // ghost tets; the facets on S2 are protected and have no neighbour; tet_region holds the body
  // (0, 1, ...: inside components numbered by the smallest input face bounding them).
  TetMesh mesh;
  // S2: 3 vertex ids per subface, oriented like the input face (outward from the material).
  std::vector<uint32_t> s2_tri;
  std::vector<uint32_t> s2_face;   // per subface: the input triangle it lies in (Claim 5.1)
  std::vector<int32_t> s2_patch;   // per subface: that triangle's patch label
  std::vector<uint32_t> input_edges;  // 2 per input edge (sorted vertex ids)
  std::vector<SteinerPoint> steiner;
  RecoveryStats stats;
};

// "split constraints", "fuzzy faces", "fuzzy faces with flips", "fuzzy faces with defended edges".
const char* recovery_strategy_name(size_t strategy);

// S must be a valid closed, consistently oriented surface (validate_surface()); duplicate points
// are refused. Fails with RecoveryFailed naming the constraint that could not be recovered.
Result<RecoveryOutput> recover_boundary(const SurfaceMesh& S, const RecoveryOptions& options = {});

}  // namespace anitet

// Stage 1: advancing-front layers that hide the input surface S (paper, section 3).
//
// Input: a validated surface S (closed, manifold, every shell oriented with its right-hand normals
// pointing OUT of the material, no self-intersection; see validate/validate.hpp). Output: a tet
// mesh T1 of a few layers along S, and its inner boundary S1 (the new front) such that no vertex,
// edge or triangle of S is on S1. Every triangle of S is a facet of T1 and no point is added on S.
//
// Two tet-building steps, each validated by the exact test of tet_fit.hpp against the current
// front (kept in a loose octree so that a test only touches nearby triangles):
//  * face step (paper, Lemmas 3.1-3.2): on a front triangle ABC with centroid M and unit normal N
//    into the region, the tet PABC with P = M + eps N. eps starts at the height that makes PABC
//    most regular in the metric and is halved until the tet fits.
//    Termination (Lemma 3.1): as eps -> 0 the tet shrinks to ABC. A front triangle disjoint from
//    ABC is at a positive distance from it; one that shares an edge or corner with ABC leaves it at
//    a positive angle inside the region (the front is a valid closed surface), while the tet's
//    facets tilt from ABC by an angle that tends to 0. So some finite number of halvings makes the
//    tet fit (Lemma 3.2 takes the smallest eps over all nearby triangles). In floating point P is
//    rounded; the exact test judges the rounded P, and a cap on halvings (options.max_halvings)
//    turns a pathological case into an error instead of a loop.
//  * push step (the paper's edge push, done per vertex): a vertex A of the layer's starting front
//    moves to A' = A + s disp, where disp sees every triangle of A's current star from the region
//    (disp . n > 0 for each); A' is joined to every triangle of the star, one tet at a time, each
//    validated on the front left by the previous ones (the later tets close the facets A A' u
//    the earlier ones opened; a front transaction undoes a push that fails half-way). s starts
//    at 1 and is multiplied by options.shrink (the paper halves) until the whole push fits.
//    Termination: the star lies on the region side of A' (disp inside the visibility cone makes
//    every tet of the cone positive), and as s -> 0 the cone of tets shrinks to the star: the
//    argument above applies. Afterwards A is off the front, replaced by A'.
//    Choices (push_step.cpp), all floating-point heuristics; validity is only ever decided by
//    the exact test:
//     - before a layer's first push every vertex gets a plan: the direction that sees its star
//       best (angle-weighted mean normal, or the max-min direction for edge-on triangles), a
//       height (options.push_height sizes, capped at 1 / (2 k + 1) of the free distance to the
//       front across when k layers remain, so thin parts get evenly thin layers), and the
//       planned points are smoothed tangentially so that the next front is even;
//     - a push must leave each waiting neighbour a direction that sees its new star with a
//       margin (else it is shortened like a push that does not fit);
//     - directions, margins and corner angles are measured in the metric at the vertex when it
//       is anisotropic there (the star mapped by M^(1/2)): a push off stretched triangles that is
//       fair in the metric is then not shortened for making walls of them in space;
//     - the start height is chosen among fractions of the planned one by the radius ratio (in
//       the metric) of the cone's tets and of the tets the neighbours will build on it;
//     - a vertex whose star no direction sees (saddles on scanned surfaces, < 0.1% of vertices)
//       is pushed last, and if its star is still not visible it is taken off in runs of
//       consecutive triangles that one direction sees, each checked to fit very close to A.
//    Two cores (options.push_tasks_min_vertices): a plane across the layer's vertices is chosen
//    (on one of the three axes, at the 30th-70th percentile, the one that few vertices' reach
//    crosses, their star, their neighbours' stars and their apex, with sides of about the same
//    size); the vertices whose reach crosses it are pushed first, one by one; then the planned
//    pushes of the others are made by two tasks, one per side, each on its own copy of its side
//    of the front, and merged (low side first); those whose planned push did not fit are pushed
//    after, one by one. The two tasks never meet the same triangle, and the split and the merge
//    order do not depend on the threads: one core gives the same bits as two (the tasks give the
//    bits of a one-by-one layer in that order).
//
// Schemes. kFacesThenPush is the paper's layer: face step on every triangle of the layer's
// starting front, then push step on every vertex of it. It triples the front's triangle count per
// layer, most of its tets (the push tets on the tents' flanks) have radius ratio ~0.35, and the
// tents make many stars that no direction sees (slow partial pushes from the second layer on).
// kPushOnly runs the push step alone: pushing every vertex of the front in turn sweeps each
// triangle ABC into a prism ABC-A'B'C' cut into three tets (radius ratio ~0.75-0.8 at a height of
// ~0.8 edge), keeps S1 an offset copy of the front (same connectivity, same triangle count), and
// hides S just as well: S's triangles go at the first push of one of their corners, its edges and
// vertices when every vertex has been pushed. kPushOnly is the default.
//
// Several layers: the same on the new front (each layer is a valid mesh before the next starts).
// After each layer, the new front vertices whose worst tet is poor are moved further into the
// region when that helps and is valid (improve_step.cpp: the cone from the new position must fit
// exactly and every tet of the vertex stay positive). A push that never fits falls back to partial
// pushes; a non-input vertex that no push can take off stays on the front for that layer
// (stats.stopped_vertices), so a layer never fails for it.
//
// Boundary-layer mode (BoundaryLayerOptions): n thin prism layers on the wall patches first (the
// same push step with smoothed normals and heights h0 r^i, reduced where needed), then the
// ordinary layers on the whole front. BL tets carry options.boundary_layer.region.
//
// Output conventions:
//  * T1: input vertices first (vflag::kOnInputSurface, input order and ids), new vertices after;
//    positive tets; adjacency built (facets on S and on S1 have no neighbour); facets on S are
//    marked protected. No ghost tets; no deleted slots.
//  * S1 (front_tri): triangles on T1's vertex ids, oriented like S: counter-clockwise seen from
//    outside the region still to mesh, i.e. normals point away from that region (into T1).
//    S1's vertices carry vflag::kOnFront. front_tet[i] is the T1 tet having S1 triangle i as its
//    facet front_facet[i] (paper, Claim 5.2).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"

namespace anitet {

enum class LayerScheme : int {
  kPushOnly = 0,       // prism layers: vertex pushes only (default)
  kFacesThenPush = 1,  // the paper's two steps: face tets, then vertex pushes
};

// Boundary-layer mode (CFD): on the wall patches, n layers of thin prisms (each split into three
// tets by the push order, so every quad side has one diagonal shared by both prisms) normal to
// the surface, layer i of height first_height * growth^i along the smoothed vertex normal. The
// height is reduced locally, never left invalid: where the fronts would collide (the free
// distance along the normal, shared with the front across), where the smoothed normal sees the
// star's triangles only at a grazing angle, next to a reduced neighbour (gradation), and where a
// push does not fit (shrunk like any push). Such vertices are counted as reduced. The ordinary
// layers (LayersOptions::layers) follow on the whole front, wall and other patches alike. BL tets
// carry `region` in TetMesh::tet_region (all other T1 tets: 0).
// A wall may meet other patches only where they are slide patches: the pipeline first
// re-triangulates them around the columns that slide along them (slide_patches.hpp), which sets
// column_next; stage 1 then pushes each junction vertex to the next point of its column. A vertex
// of a wall and of any other patch without such a column is InvalidArgument.
struct BoundaryLayerOptions {
  std::vector<int32_t> wall_patches;  // patch labels of the input; empty: no boundary layer
  std::vector<int32_t> slide_patches; // labels the layers' columns may slide along (re-triangulated)
  double first_height = 0.0;          // h0, in length units (> 0 when walls are given)
  double growth = 1.2;                // r >= 1
  int layers = 0;                     // n; 0: from total_thickness
  double total_thickness = 0.0;       // used when layers == 0: the least n reaching it
  int normal_smoothing = 10;          // passes of vertex-normal smoothing
  double grazing_margin = 0.25;       // below this min d.n over the star, the height shrinks
  double gradation = 1.5;             // neighbours' heights differ by at most this factor,
  int gradation_rings = 3;            // up to this many edges away from a reduced vertex
  double gap_share = 0.4;             // the BL may fill this share of the free distance across
  // Mitred edges and corners: a column whose direction d meets its star's normals at most at
  // cosine c < 1 (a convex or concave edge, a trailing edge, a wing's root) is lengthened to
  // h / max(c, mitre_min_cosine), so that the layer keeps its thickness h across every wall there
  // (without it, a right-angled edge's layers are 0.71 h thick across each wall).
  bool mitre = false;
  double mitre_min_cosine = 0.5;
  int32_t region = 1;                 // tet_region of BL tets
  // A vertex that is not an input vertex whose planned BL height is below this fraction of
  // h0 r^i (fronts colliding: thin gaps, trailing edges) stops for that layer (reported) instead
  // of moving that little: such pushes left S1 vertices 1e-14 apart in folded BL fronts, which
  // stage 2 cannot recover.
  double min_height_ratio = 0.05;
  // Per surface vertex: the next point of its junction column (TetMesh::kNone: none), as
  // slide_boundary_layer() gives it for the surface it made; empty: no junction.
  std::vector<uint32_t> column_next;

  bool enabled() const { return !wall_patches.empty(); }
};

// The number of boundary layers the options ask for: `layers`, or the least count whose heights
// h0 r^i add up to total_thickness (at most 1000).
int boundary_layer_count(const BoundaryLayerOptions& bl);

// The first-layer height for a target y+ by the flat-plate estimate: skin friction
// Cf = 0.026 Re^(-1/7), friction velocity u_tau = U sqrt(Cf / 2), so
// h0 = y+ nu / u_tau = y+ L / (Re sqrt(Cf / 2)) with Re = U L / nu on the reference length L.
// Error::InvalidArgument unless all three are positive and finite.
Result<double> first_height_from_yplus(double yplus, double reynolds, double ref_length);

struct LayersOptions {
  // 1 or more. One layer hides S (every input vertex leaves the front) and is the default: the
  // second layer's prisms copied S's poor triangles onto S1, away from S where they count against
  // the interior, and cost half of stage 1 (the pipeline still tries 2 and 3 when S1 is not
  // recovered).
  int layers = 1;
  LayerScheme scheme = LayerScheme::kPushOnly;
  // Face step: initial apex height relative to the height of the regular tet on the base, both in
  // the metric at the centroid (candidates around it are tried, the most regular one kept).
  double face_height = 1.0;
  // Push step: initial push distance, in metric units (sizes) along the push direction.
  double push_height = 0.8;
  int max_halvings = 40;  // per tet or push; hitting it is an error (Error::Internal)
  // Factor applied to a push or apex height that does not fit (the paper halves: 0.5). Any
  // factor in (0, 1) terminates; a larger one keeps heights closer to the largest that fits.
  double shrink = 0.5;
  // Push step: a push must leave every waiting neighbour a direction that sees its star with
  // this fraction of its starting margin (min d . n, capped at 0.5).
  double keep_margin = 0.5;
  int smoothing_passes = 3;  // tangential smoothing of the planned points of a layer
  // Push step: choose each push's height among fractions of the planned one by the quality of
  // the tets it makes and of those the waiting neighbours will make on it.
  bool choose_height = true;
  // Push step: planned heights of neighbouring vertices differ by at most this factor (heights
  // are only lowered); <= 1 turns the limit off.
  double height_gradation = 1.25;
  int gradation_rings = 2;  // how far (in edges) the limit reaches from a low vertex
  // Push step: the chosen height is at least this fraction of the planned one (before a push that
  // does not fit is shrunk).
  double min_height_fraction = 0.5;
  // Ordinary layers with at least this many planned vertices push on two tasks (see the push
  // step above; on one core they run one after the other, with the same result). 0: never.
  size_t push_tasks_min_vertices = 2000;
  // After each ordinary layer: passes moving the new front vertices whose worst tet has a radius
  // ratio below improve_below (last layer) or improve_below_inner (the layers before: a move
  // into the region takes room from the next layer) further in, each checked exactly (0: off).
  int improve_passes = 3;
  // After the last layer: passes over T1's interior vertices (see LayerBuilder::smooth_interior),
  // each moved only to raise the worst tet around it. 0: off.
  int interior_smoothing_passes = 3;
  double improve_below = 0.3;
  double improve_below_inner = 0.06;
  BoundaryLayerOptions boundary_layer;
};

struct LayerStats {
  size_t front_triangles_before = 0;
  size_t face_tets = 0;
  size_t push_tets = 0;
  size_t halvings = 0;         // epsilon halvings in this layer (faces and pushes)
  size_t halved_columns = 0;   // columns with a tet from a halved apex or push
  bool boundary_layer = false; // a BL layer (wall patches only)
  double seconds = 0.0;
};

struct LayersStats {
  size_t tets = 0;
  size_t new_vertices = 0;
  size_t face_tets = 0, push_tets = 0;
  // Face step: tets tried, those that needed at least one halving, halvings in all, the most.
  size_t faces = 0, faces_halved = 0, face_halvings = 0, max_face_halvings = 0;
  // Push step: the same per pushed vertex.
  size_t pushes = 0, pushes_halved = 0, push_halvings = 0, max_push_halvings = 0;
  size_t direction_fixes = 0;  // pushes whose direction is not the mean normal (edge-on triangles)
  size_t lookahead_halvings = 0;  // halvings made to keep a waiting neighbour's star visible
  size_t replans = 0;             // waiting neighbours given a new direction by a push
  size_t deferred_pushes = 0;     // vertices whose star no direction saw at the layer's start
  size_t partial_pushes = 0;      // pushes of a visible part of a star no direction sees whole
  size_t task_pushes = 0;         // pushes made by the two push tasks (the rest one by one)
  size_t stopped_vertices = 0;    // front vertices left in place by a layer (no push fitted)
  size_t push_fallbacks = 0;      // whole-star pushes that never fit, redone as partial pushes
  size_t improved_vertices = 0;   // front vertices moved after their layer (improve_passes)
  size_t smoothed_vertices = 0;   // interior T1 vertex moves after the last layer
  uint64_t fit_tests = 0, fit_candidates = 0, tri_tests = 0;
  // The epsilon-halving loop: halvings made in all (faces and pushes), and per layer the share of
  // the front's columns (input triangles) where some tet came from a halved apex or push.
  size_t halving_loops = 0;
  size_t halved_columns = 0;  // summed over layers
  double halved_column_share = 0.0;  // halved_columns / (columns * layers)
  std::vector<LayerStats> per_layer;
  // Boundary-layer mode.
  int bl_layers = 0;
  size_t bl_wall_vertices = 0;      // input vertices on wall patches
  size_t bl_pushes = 0;
  size_t bl_reduced_pushes = 0;     // pushes below 90% of h0 r^i
  size_t bl_reduced_vertices = 0;   // wall vertices with at least one reduced layer
  size_t bl_junction_pushes = 0;    // pushes of junction vertices along their slide patch
  size_t bl_junction_stops = 0;     // junction pushes that did not fit (the column waits)
  double bl_reduced_share = 0.0;    // bl_reduced_vertices / bl_wall_vertices
  double bl_max_height_error = 0.0; // max |h / (h0 r^i) - 1| over the pushes not reduced
  double bl_min_height_ratio = 1.0; // min h / (h0 r^i) over all pushes
  double bl_seconds = 0.0;
  double seconds = 0.0;
};

struct LayersOutput {
  TetMesh mesh;                     // T1
  std::vector<uint32_t> front_tri;  // S1: 3 per triangle, T1 vertex ids
  std::vector<uint32_t> front_tet;  // 1 per S1 triangle: the T1 tet that has it
  std::vector<uint8_t> front_facet; // 1 per S1 triangle: its facet index in that tet
  // Provenance, for diagnostics and quality reports:
  std::vector<uint16_t> tet_layer;    // 1 per T1 tet: the layer that built it (1-based; BL
                                      // layers first, then the ordinary ones)
  std::vector<uint32_t> tet_column;   // 1 per T1 tet: the input triangle it stands above
  std::vector<uint32_t> vertex_origin; // 1 per T1 vertex: the vertex it was pushed from (kNone:
                                       // an input vertex or a face apex)
  LayersStats stats;

  size_t num_front_triangles() const { return front_tri.size() / 3; }
};

// Builds the layers. Errors: InvalidArgument (bad options, or S not closed and consistently
// oriented, or a degenerate triangle), EmptyInput, BadIndex, Internal (halving cap reached, or no
// direction sees a vertex's whole star; the message names the element and the layer).
Result<LayersOutput> build_layers(const SurfaceMesh& surface, const SizingField& sizing,
                                  const LayersOptions& options = {});

// S1 as a compact SurfaceMesh (vertices renumbered 0..n-1 in T1 order; vertex_map[i] = the T1
// id of S1 vertex i) for the stages that take a surface. Patch labels are 0.
SurfaceMesh front_surface(const LayersOutput& out, std::vector<uint32_t>* vertex_map = nullptr);

}  // namespace anitet

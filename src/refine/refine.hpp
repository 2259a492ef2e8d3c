// Stage 3b (paper, section 5.2): refinement and coarsening by normalized edge length.
//
// Each pass measures every edge in the metric (the geometric mean of its length in the metrics
// at its two ends), then
//   - splits the edges longer than split_length (sqrt 2), longest first, by inserting their metric
//     midpoint through the modified Delaunay kernel (PointInserter: cavities stop at protected
//     facets, so S is never cut). A midpoint closer than `spacing` (in the metrics of both
//     points) to a point inserted earlier in the same pass is put off to the next pass (a
//     multi-level hash grid), so a batch does not crowd points together;
//   - collapses the edges shorter than collapse_length (1/sqrt 2), shortest first: both ends onto
//     the midpoint when neither is on S, the free end onto the other when one is (a vertex of S
//     never moves and is never removed). A collapse is applied only when every changed tet is
//     positive by the exact orient3d, no protected facet is lost, no new edge is longer than
//     max_collapse_result (or, from the kept point to a vertex of S, than that vertex's longest
//     edge of S, which nothing shortens) and no changed tet falls below min_collapse_quality
//     (the shape measure of refine/mesh_ops.hpp, taken in the metric at the collapse point), or
//     below the worst tet it replaces when that one was worse. An edge shorter than
//     degenerate_length (points a recovery put within rounding of each other) may create edges
//     up to the longer of its ends' old edges to the same vertex instead: next to surface
//     triangles larger than the size, every edge there is already too long, and such clusters
//     stayed.
// Anisotropic metrics (some vertex's metric is not a multiple of I): lengths, the metric
// midpoint, the spacing filter and the collapse shape test all use the tensor, and
//   - midpoints go in through an anisotropic Delaunay kernel (cavity: the edge's ring grown by
//     the insphere test in the metric of the new point, made star-shaped by exact orient3d)
//     instead of the Euclidean one, which would connect points across the stretched direction;
//   - 2-3 / 3-2 flips raising the worst shape in the metric run before the first pass and after
//     every pass (RefineStats::metric_flips);
//   - the ring-crowding test on splits is off and refused collapses are retried each pass (the
//     flips change the neighbourhoods);
//   - a collapse may create edges up to anisotropic_max_collapse_result (still in range): with
//     max_collapse_result's 1.3, the stretched neighbourhoods refused most collapses and many
//     edges stayed short.
// Isotropic fields take exactly the isotropic path. optimize/ measures in the metric too, and
// the pipeline runs refinement and optimization again on an anisotropic field (see
// pipeline/mesher.hpp).
// Passes repeat until fewer than stop_fraction of the edges change or max_passes is reached.
// Edges of S (on a protected facet, both ends on S) are never split: no point is added on S.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "core/metric_measures.hpp"
#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/tet_mesh.hpp"

namespace anitet {

struct RefineOptions {
  // Global size scale: every target length is multiplied by it (2 = a mesh twice as coarse).
  double size_scale = 1.0;
  double split_length = kUnitRangeMax;
  double collapse_length = kUnitRangeMin;
  double spacing = 0.7;                // min metric distance between points of one batch
  // A split point closer than this (metric length, at the point) to a protected facet (S's
  // triangles, in a BVH built once) is not inserted: next to a surface triangle much larger than
  // the size, each split of an edge running along it would halve the distance again, down to
  // flat tets.
  double facet_clearance = 0.2;
  // The same with an anisotropic metric. A kept surface is coarse there (the UGAWG cube's side
  // faces are up to ~100 long in the metric), so a point near one only makes flat tets on its
  // triangles, which the optimizer then collapses: at 0.2, it collapsed 1550 of the ~4400
  // vertices refinement made on the UGAWG cube to its .sol (80% of them within metric distance
  // 1 of a side wall); at 0.5, refinement makes 21.0k tets instead of 25.8k and the optimizer
  // collapses 933, with as many edges in range.
  double anisotropic_facet_clearance = 0.5;
  double max_collapse_result = 1.3;    // longest edge a collapse may create (normalized)
  double anisotropic_max_collapse_result = 1.41;  // the same, with an anisotropic metric
  double min_collapse_quality = 0.05;  // lowest meshops::shape_quality a collapse may create
  // Edges shorter than this (normalized) are collapsed even where max_collapse_result refuses
  // every new edge, as long as no new edge is longer than the ends' old ones (see the top).
  double degenerate_length = 0.01;
  // A collapse may make an edge from its kept point to a vertex x of S as long as x's longest
  // edge of S (which no split shortens), beyond max_collapse_result. false: max_collapse_result
  // for every edge (as before 4ca970c).
  bool collapse_to_s_edge_length = true;
  int max_passes = 30;
  double stop_fraction = 1e-3;  // stop when a pass changes fewer than this share of the edges
  bool collapse = true;
  // Each collapse pass takes its short edges in blocks of collapse_trial_block (in length order):
  // it first tries each edge's collapse on every core against the mesh as the block starts, then
  // makes them in order (the edges next to a collapse made meanwhile tried again). false: each
  // edge tried in turn, one by one, as on one thread. The same mesh either way.
  bool collapse_trials = true;
  size_t collapse_trial_block = 2048;
  // A split point whose Delaunay cavity (Euclidean or metric) would take a frozen tet (negative
  // region: the halo of a part in distributed/) behind a protected facet is put off
  // (InsertOptions::refuse_frozen_conflict), so that each part stays Delaunay up to its frozen
  // interface and the next round, with the interface moved, inserts it as the whole mesh would.
  bool defer_at_frozen = false;
  // Threads for the split points' measures (midpoint, metric, vetoes): 0 TBB's default, n an
  // arena of n threads. The mesh does not depend on it.
  int num_threads = 0;
  // Called after each pass with the share of the work done: the live tets over expected_tets
  // when that is given (estimate_refined_tets), else passes over max_passes; at most 0.95 until
  // the end. For progress display only (it cannot stop the stage).
  std::function<void(double fraction)> progress;
  double expected_tets = 0;
  // The split points of a pass (isotropic metric) are inserted by BatchInserter: this many slabs,
  // one task each, then the points whose cavity crossed a slab one by one. The mesh depends on
  // it, never on the thread count; 1: one by one throughout.
  int insert_partitions = 2;
  // check_mesh() and the protected-facet count after every pass (on by default in debug builds).
#ifdef NDEBUG
  bool check_each_pass = false;
#else
  bool check_each_pass = true;
#endif
};

struct RefineStats {
  int passes = 0;
  size_t splits = 0;
  size_t split_rejected = 0;  // midpoints the kernel refused (blocked, outside) or spacing put off
  size_t parallel_splits = 0;  // split points inserted by the slab tasks (insert_partitions)
  size_t collapses = 0;
  size_t collapse_rejected = 0;
  size_t metric_flips = 0;  // anisotropic metrics only: 2-3 / 3-2 flips raising the metric shape
  // The passes ran out (max_passes) before fewer than stop_fraction of the edges changed: the
  // lengths are less even than asked.
  bool stopped_at_pass_cap = false;
  // Vertices whose metric was not SPD to rounding (an extreme anisotropy), measured as Euclidean.
  size_t metric_not_spd = 0;
  size_t vertices_before = 0, vertices_after = 0;  // live vertices
  size_t tets_before = 0, tets_after = 0;
  // Normalized edge lengths after the last pass.
  double length_mean = 0.0;
  double length_in_range = 0.0;  // share of edges (not on S) in [collapse_length, split_length]
  double seconds = 0.0;
  // Where the time went: edge lists (collect_edges), the split points' choice (midpoints, metric,
  // spacing grid, vetoes), their insertion, the collapses, the metric flips (anisotropic only).
  double seconds_edges = 0.0, seconds_choice = 0.0, seconds_insertion = 0.0, seconds_collapses = 0.0,
         seconds_flips = 0.0;
};

// Scales a field's lengths: metric(p) = base.metric(p) / scale^2.
class ScaledSizing final : public SizingField {
 public:
  ScaledSizing(const SizingField& base, double scale) : base_(base), inv2_(1.0 / (scale * scale)) {}
  void metric(const double p[3], double m[6]) const override {
    base_.metric(p, m);
    for (int k = 0; k < 6; ++k) m[k] *= inv2_;
  }

 private:
  const SizingField& base_;
  double inv2_;
};

// The scalar size of a metric: det(M)^(-1/6) (h for I/h^2).
double metric_size(const double m[6]);

// The number of tets refinement will leave in `mesh` for `field` (the field as refine_mesh is
// given it, with options.size_scale applied here), estimated before refining: the metric volume
// of the mesh (each tet's volume times sqrt(det M), M averaged over its corners and centroid)
// over the metric volume a tet of the meshes refinement and optimization make takes, measured
// (kMetricVolumePerTet). On every core. Within 10-30% on the shared surfaces; meant for a guard
// against asking for far more tets than memory holds, and for progress.
double estimate_refined_tets(const TetMesh& mesh, const SizingField& field, double size_scale = 1.0);
// Its terms: the tets predicted inside each tet slot (0 for deleted and ghost slots); their sum is
// estimate_refined_tets up to rounding. The weights of the coarse mesh's partition in parts.
std::vector<double> estimate_refined_tets_per_tet(const TetMesh& mesh, const SizingField& field,
                                                  double size_scale = 1.0);

// Refines and coarsens `mesh` (no ghost tets; adjacency built; S = the protected facets, whose
// vertices carry vflag::kOnInputSurface) towards unit edge lengths in `field`. Vertices removed
// by collapses stay in mesh.xyz but belong to no tet (TetMesh::to_volume_mesh(true) drops them).
Result<RefineStats> refine_mesh(TetMesh& mesh, const SizingField& field, const RefineOptions& options = {});

// Renumbers the mesh for memory locality: the used vertices from first_vertex on in the order of a
// Hilbert curve through the mesh (those before first_vertex keep their ids; the unused ones go
// last), and the live tets grouped by the curve's rank of their first vertex, deleted slots
// dropped. The mesh is the same; only ids change. Neighbouring tets and vertices then sit close in
// memory, which the passes that walk balls and rings over a large mesh need (refinement appends
// each pass's points along its own curve and reuses freed slots anywhere).
void order_for_locality(TetMesh& mesh, uint32_t first_vertex);

// Counts the protected facets of live tets (each S triangle once: it has no neighbour).
size_t count_protected_facets(const TetMesh& mesh);

}  // namespace anitet

// The Mesher: the stages in order, behind one class.
//   validate -> stage 1 (layers) -> stage 2 (Delaunay of S1 + conforming recovery) -> coupling
//   -> refinement/coarsening (refine/) -> optimization (optimize/) -> a VolumeMesh.
// Boundary layers (layers.boundary_layer with wall patches): the BL tets come out of coupling in
// their own region (couple.hpp) and are frozen for refinement and optimization: every facet of a
// BL tet is protected (cavities, flips and collapses stop there) and every BL vertex locked
// (never moved or removed), so the layers and their heights reach the output unchanged.
// Same input and options, same mesh, bit for bit (every stage is deterministic and sequential).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/process_memory.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "couple/couple.hpp"
#include "core/sizing.hpp"
#include "layers/layers.hpp"
#include "layers/slide_patches.hpp"
#include "metric/surface_sizing.hpp"
#include "optimize/optimize.hpp"
#include "pipeline/bl_report.hpp"
#include "recovery/recovery.hpp"
#include "refine/refine.hpp"
#include "validate/validate.hpp"

namespace anitet {

// Called at the start and end of every stage with the stage's name and the fraction of the whole
// run done; returning false cancels the run (Error::Cancelled) at that point. Stages are not
// interrupted in the middle.
using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

struct MesherOptions {
  LayersOptions layers;
  RecoveryOptions recovery;
  // When stage 2 cannot recover S1, run stages 1 and 2 again with layers.layers - 1, ..., 1, then
  // layers.layers + 1, ..., max(layers.layers + 1, 3) (each run from scratch);
  // MesherResult::layers_used tells which count worked.
  bool retry_layer_counts = true;
  // Wall time for those attempts together (stages 1, 2 and the coupling, each run): a recovery
  // is given at most what is left (its own caps still apply), and no attempt starts after it ran
  // out: on an S1 that no strategy recovers, the attempts' own caps add up to many minutes.
  // <= 0: no budget.
  double attempts_seconds = 240;
  ValidationOptions validation;
  ProgressCallback progress;  // may be empty
  // Threads for every stage: the whole run executes in one TBB task arena of this size (the
  // sizing grid built beside stage 2 is a task of it too); 0: the caller's arena (TBB's default:
  // all cores). The mesh does not depend on it.
  int num_threads = 0;
  // Stage 3b/3c. The sizing field they follow: `sizing` when given (a user metric; it must
  // outlive the run), else the paper's grid built from the surface (metric::surface_sizing_field
  // with `surface_sizing`). refine.size_scale scales it (2 = twice as coarse).
  RefineOptions refine;
  OptimizeOptions optimize;
  bool run_refine = true;
  bool run_optimize = true;
  // Refinement is refused (Error::InvalidArgument, before it starts) when the sizing field asks
  // for more tets than this, estimated on the coupled mesh (estimate_refined_tets); 0: no limit.
  double max_tets = 0;
  // With an anisotropic field (OptimizeStats::anisotropic), this many more rounds of refinement
  // then optimization after the first (see refine_optimize_cycles). Needs both stages on.
  int anisotropic_cycles = 2;
  // The cycles stop after a round whose refinement left the share of edges in range less than
  // this above the round's before (0: all anisotropic_cycles run). Where the rounds only churn
  // (the UGAWG cube meshed to its .sol: 87.0, 87.5, 87.3, 87.5, 87.2% in five rounds, each
  // adding 5k tets that the next optimization removes) they cost a third of the time each for
  // nothing; where the optimizer's moves leave lengths to even (bench/aniso_cube: 89.8, 97.7,
  // 98.9%) they go on.
  double anisotropic_cycle_gain = 0.01;
  // And no round runs after an optimization that raised the share of edges in range by less than
  // this (OptimizeStats::length_in_range_before/after; 0: off). Since the optimizer's moves keep
  // refinement's lengths in range (OptimizeOptions::keep_lengths_in_range) it no longer takes
  // 4-8 points that a second round gave back: on the UGAWG cube, to its .sol and to polar1, one
  // round ends at 88.9% after optimization and the next two add 0.5 point at twice and three
  // times the time; where the optimizer's moves leave lengths to even (bench/aniso_cube: +6
  // points) the next round runs. 4.5 points since the flips keep lengths too (they took ~1.5
  // points of the optimizer's gain before): the UGAWG cube, to its .sol and to polar1, gains 3.1
  // and 3.5 points and stops after one round, where a second adds 0.6 point at twice the time;
  // bench/aniso_cube gains 7.6 and goes on.
  double anisotropic_cycle_optimizer_gain = 0.045;
  // With a boundary layer (growth > 1): the sizing field of stages 3b/3c is intersected with the
  // boundary-layer metric (metric::BoundaryLayerField: normal size h0 + (r - 1) d at distance d
  // from the walls), so the interior continues the layers' heights instead of jumping to the
  // surface's sizes. The metric is then anisotropic near the walls: refinement and optimization
  // are many times slower and run anisotropic_cycles more times. Off by default.
  bool boundary_layer_sizing = false;
  // With boundary_layer_sizing: beyond the layers' top, the normal size grows at this rate
  // (>= the layers' growth) up to the field's sizes; 0: at the layers' growth. The first tets on
  // the top still get the next layer's height; a faster growth there makes fewer of the thin
  // interior tets that the layers' own growth makes (issue 48's pipe, r 1.15: 3.4 times the
  // isotropic interior's tets; 2.4 times with 1.3).
  double boundary_layer_sizing_growth = 0.0;
  const SizingField* sizing = nullptr;
  // When set, runs stages 3b and 3c (and the anisotropic cycles) in place of refine_mesh and
  // optimize_mesh: given the coupled mesh and the sizing field (unscaled: refine.size_scale
  // applies), it leaves the final mesh in `mesh` and its figures in `refine` and `optimize`.
  // The MPI driver (mpi/) runs them in parts, one per rank (distributed::run_in_parts). Needs
  // run_refine and run_optimize.
  std::function<Status(TetMesh& mesh, const SizingField& field, RefineStats& refine, OptimizeStats& optimize)> stage3;
  // stage3 leaves no tets in `mesh` (anitet-mpi writing one piece per rank): the boundary layer's
  // columns are then measured on the coupled mesh before it (its tets are frozen through stages
  // 3b/3c, so the columns and heights are the final mesh's), and its cell figures (dual faces,
  // the transition to the interior), which need the interior's final tets, are not measured.
  bool stage3_leaves_no_mesh = false;
  metric::SurfaceSizingOptions surface_sizing = default_surface_sizing();

  static metric::SurfaceSizingOptions default_surface_sizing() {
    metric::SurfaceSizingOptions o;
    o.triangle_size = metric::TriangleSize::Mean;  // S's edges then measure about 1
    return o;
  }
};

struct StageReport {
  std::string name;
  double seconds = 0.0;
  size_t tets = 0;  // tets the stage leaves (its own output)
  // The process's peak resident memory when the stage ended (VmHWM: the highest so far as the
  // kernel counts it, lazily; the caller's memory included), in bytes; 0 where unknown.
  double peak_bytes = peak_resident_bytes();
};

// Something the run did otherwise, or less, than asked (the front-layer count changed by the
// retries, refinement stopped at its pass cap, tets left flat to rounding, a metric value that is
// not SPD measured as Euclidean): a stable kind and a sentence for people.
struct Notice {
  std::string kind;
  std::string message;
};

struct MesherResult {
  // Vertices: the input's first, in input order (but those of no input triangle, which no tet
  // uses); tets positive; regions per body; boundary triangles: the input's, with their patch
  // labels.
  VolumeMesh mesh;
  // [v]: the vertex of `mesh` that input vertex v became; TetMesh::kNone for one of no triangle.
  std::vector<uint32_t> input_vertex;
  std::vector<StageReport> stages;
  LayersStats layers;      // of the stage-1 run that stage 2 recovered
  int layers_used = 0;     // the layer count of that run
  size_t layers_retries = 0;  // stage 1 + 2 runs before it (other layer counts, see MesherOptions)
  RecoveryStats recovery;
  CoupleStats couple;
  BoundaryLayerReport boundary_layer;  // zero without wall patches
  // With wall patches, for merge_bl_prisms (core/bl_prisms.hpp): per vertex of `mesh`, the
  // vertex its boundary-layer column pushed it from (~0u: none), and the first BL region (the
  // BL tets of body k have region bl_first_region + k). Empty and 0 without wall patches.
  std::vector<uint32_t> bl_vertex_origin;
  int32_t bl_first_region = 0;
  // With slide patches: the boundary triangles (mesh.bnd_tri) are the input's but on those
  // patches, whose new triangles follow the input's others.
  SlideReport slide;
  RefineStats refine;      // zero when the stage did not run
  OptimizeStats optimize;  // zero when the stage did not run
  int anisotropic_cycles = 0;  // extra refine + optimize rounds run (anisotropic field; at most the option's)
  // With an anisotropic field (optimize.anisotropic): radius ratios measured in the field's
  // metric (summarize_metric_quality); tets == 0 otherwise.
  QualitySummary metric_quality;
  std::vector<Notice> notices;  // what was done otherwise than asked (empty: everything as asked)
  double estimated_tets = 0;    // the refinement's tets estimated before it ran (0: not estimated)
  double seconds = 0.0;
};

// Stages 3b + 3c again on a refined and optimized mesh: up to `cycles` more rounds of refine_mesh
// then optimize_mesh with the same field and options (refine_mesh scales the field by
// refine.size_scale itself; optimize_mesh gets it scaled), stopping after a round whose
// refinement raised the share of edges in range (RefineStats::length_in_range) by less than
// min_gain over the round's before (`refine` holds the first's at the call), and running no
// round after an optimization that raised the share by less than min_optimizer_gain (0: off;
// `optimize` holds the first's at the call); `cycles_run` gets the rounds made. The figures are
// added to `refine` and `optimize`, except the lengths, the counts after and the quality after,
// which are the last round's. For anisotropic fields: the
// optimizer's moves let through collapses and splits that the stretched neighbourhoods refused,
// and each smoothing evens the lengths further (bench/aniso_cube --direct measures it).
Status refine_optimize_cycles(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                              const OptimizeOptions& optimize_options, int cycles, RefineStats& refine,
                              OptimizeStats& optimize, double min_gain = 0.0, int* cycles_run = nullptr,
                              double min_optimizer_gain = 0.0);

class Mesher {
 public:
  explicit Mesher(MesherOptions options = {}) : options_(std::move(options)) {}

  // Validates (and safely repairs a copy of) the surface, then meshes it.
  Result<MesherResult> run(const SurfaceMesh& surface) const;
  // Meshes a surface that validate_surface() has already accepted (and repaired). A surface
  // whose coordinates or extent lie outside the range the stages are measured to handle
  // (|x| <= 1e30, extent >= 1e-30) is meshed scaled by a power of two, which is exact and keeps
  // every predicate's sign, and the mesh scaled back (a notice says so); one that no such scaling
  // brings into range is refused (Error::NotImplemented).
  Result<MesherResult> run_validated(const SurfaceMesh& surface) const;

 private:
  Result<MesherResult> run_in_arena(const SurfaceMesh& surface) const;
  Result<MesherResult> run_scaled(const SurfaceMesh& surface) const;
  Result<MesherResult> run_in_range(const SurfaceMesh& surface) const;
  MesherOptions options_;
};

}  // namespace anitet

#include "pipeline/mesher.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <functional>
#include <new>
#include <optional>
#include <system_error>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "core/bvh.hpp"
#include "core/exact_scaling.hpp"
#include "core/sizing.hpp"
#include "metric/boundary_layer.hpp"
#include "metric/metric_field.hpp"
#include "pipeline/bl_report.hpp"
#include "pipeline/stage1.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Share of the run's time each stage takes, roughly, for the progress fraction.
constexpr double kDoneAfterValidate = 0.03, kDoneAfterLayers = 0.2, kDoneAfterRecovery = 0.35,
                 kDoneAfterCoupling = 0.4, kDoneAfterSizing = 0.45, kDoneAfterRefine = 0.7, kDoneAfterOptimize = 0.95;

// Freezes the boundary layer (the tets of region >= first_bl_region) for refinement and
// optimization: every facet of a BL tet protected on both sides, every BL vertex locked.
// Returns the number of BL vertices.
size_t freeze_boundary_layer(TetMesh& mesh, int32_t first_bl_region) {
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t) || mesh.is_ghost(t) || mesh.tet_region[t] < first_bl_region) continue;
    for (int i = 0; i < 4; ++i) {
      mesh.set_facet_protected(t, i, true);
      const uint32_t adj = mesh.tet_adj[4 * size_t(t) + i];
      if (adj != TetMesh::kNoNeighbour) mesh.set_facet_protected(mesh.neighbour(t, i), mesh.neighbour_facet(t, i), true);
    }
  }
  size_t n = 0;
  for (uint8_t& f : mesh.vflags)
    if (f & vflag::kBoundaryLayer) {
      f |= vflag::kLocked;
      ++n;
    }
  return n;
}

// What the run could not do as asked, for the report (also counted in the stats).
std::vector<Notice> shortfalls(const MesherResult& r, const MesherOptions& o) {
  std::vector<Notice> out;
  if (r.layers_retries > 0)
    out.push_back({"front_layers_changed", "stage 2 could not recover S1 with " + std::to_string(o.layers.layers) +
                                               " front layer(s); after " + std::to_string(r.layers_retries) +
                                               " retries, " + std::to_string(r.layers_used) + " front layer(s) were used"});
  if (r.refine.stopped_at_pass_cap)
    out.push_back({"refinement_pass_cap", "refinement stopped at its cap of " + std::to_string(o.refine.max_passes) +
                                              " passes before the edge lengths settled"});
  if (r.refine.metric_not_spd > 0)
    out.push_back({"metric_not_spd", std::to_string(r.refine.metric_not_spd) +
                                         " vertices had a metric that is not SPD to rounding; it was measured as "
                                         "the Euclidean metric there"});
  if (r.optimize.flat_left > 0)
    out.push_back({"flat_tets_left", std::to_string(r.optimize.flat_left) +
                                         " tets are left flat to double rounding (positive in exact arithmetic; a "
                                         "volume computed in doubles may find them flat or inverted)"});
  return out;
}

}  // namespace

namespace {

// Runs f in a task arena of `threads` (0: as the caller runs), unless the caller's arena has that
// size already.
template <class F>
auto in_arena(int threads, F&& f) {
  if (threads <= 0 || tbb::this_task_arena::max_concurrency() == threads) return f();
  tbb::task_arena arena(threads);
  return arena.execute(f);
}

}  // namespace

Result<MesherResult> Mesher::run(const SurfaceMesh& surface) const {
  return in_arena(options_.num_threads, [&] { return run_in_arena(surface); });
}

Result<MesherResult> Mesher::run_in_arena(const SurfaceMesh& surface) const {
  SurfaceMesh repaired = surface;
  if (options_.progress && !options_.progress("validate", 0.0))
    return Status(Error::Cancelled, "cancelled before validation");
  const ValidationReport report = validate_surface(repaired, options_.validation);
  if (!report.ok()) return report.status();
  return run_validated(repaired);
}

namespace {

// A field given in the caller's coordinates, asked at points scaled by 2^k: lengths scale with
// the points, so the metric (1/length^2) by 2^-2k. Exact.
class PowerOfTwoScaledField final : public SizingField {
 public:
  PowerOfTwoScaledField(const SizingField& base, int k) : base_(base), k_(k) {}
  void metric(const double p[3], double m[6]) const override {
    const double q[3] = {std::ldexp(p[0], -k_), std::ldexp(p[1], -k_), std::ldexp(p[2], -k_)};
    base_.metric(q, m);
    for (int i = 0; i < 6; ++i) m[i] = std::ldexp(m[i], -2 * k_);
  }
  bool isotropic() const override { return base_.isotropic(); }

 private:
  const SizingField& base_;
  int k_;
};

}  // namespace

Result<MesherResult> Mesher::run_validated(const SurfaceMesh& surface) const {
  return in_arena(options_.num_threads, [&] { return run_scaled(surface); });
}

Result<MesherResult> Mesher::run_scaled(const SurfaceMesh& surface) const {
  Result<int> scaling = exact_power_of_two_scaling({{surface.xyz.data(), surface.num_vertices()}});
  if (!scaling.ok()) return Status(scaling.status().code(), "meshing this surface is not implemented: " + scaling.status().message());
  const int k = scaling.value();
  if (k == 0) return run_in_range(surface);
  // Meshed scaled by 2^k, then scaled back: the same mesh as the scaled surface gets, exactly.
  SurfaceMesh scaled = surface;
  for (double& x : scaled.xyz) x = std::ldexp(x, k);
  MesherOptions options = options_;
  std::optional<PowerOfTwoScaledField> field;
  if (options_.sizing) options.sizing = &field.emplace(*options_.sizing, k);
  BoundaryLayerOptions& bl = options.layers.boundary_layer;
  bl.first_height = std::ldexp(bl.first_height, k);
  bl.total_thickness = std::ldexp(bl.total_thickness, k);
  Result<MesherResult> run = Mesher(std::move(options)).run_in_range(scaled);
  if (!run.ok()) return run;
  MesherResult& r = run.value();
  for (double& x : r.mesh.xyz) x = std::ldexp(x, -k);
  for (double& x : r.slide.surface.xyz) x = std::ldexp(x, -k);
  BoundaryLayerReport& report = r.boundary_layer;
  for (double* x : {&report.first_height_min, &report.first_height_mean, &report.first_height_max, &report.max_displacement})
    *x = std::ldexp(*x, -k);
  r.notices.push_back({"scaled", "the surface was meshed scaled by 2^" + std::to_string(k) +
                                     " (exact) to bring its coordinates into the range meshed, and scaled back"});
  return run;
}

namespace {

// The default sizing grid needs the surface only: it is built on another core while stage 2 runs on
// one. Not during stage 1, whose plans and improvement passes use both cores. A task of the run's
// own arena (so that --threads / num_threads bounds it too); stages 1-2 and the coupling run
// isolated (MeshingRun::isolated), so that no TBB wait inside their parallel loops takes the grid
// task up and runs it nested there (they would then wait for the grid). On one thread the task runs
// at the wait.
class DefaultGrid {
 public:
  DefaultGrid(const SurfaceMesh& surface, const metric::SurfaceSizingOptions& options, bool wanted)
      : surface_(surface), options_(options), wanted_(wanted) {}
  ~DefaultGrid() {  // a run that ends early drops a grid not started yet
    if (waited_) return;
    group_.cancel();
    group_.wait();
  }
  void start() {
    if (started_ || !wanted_) return;
    started_ = true;
    group_.run([this] { build(); });
  }
  Result<metric::MetricField> take() {
    start();
    group_.wait();
    waited_ = true;
    if (!grid_) build();
    return std::move(*grid_);
  }

 private:
  void build() {
    // An exception must not leave the task (the group's wait would rethrow it).
    try {
      grid_.emplace(metric::surface_sizing_field(surface_, options_));
    } catch (const std::bad_alloc&) {
      grid_.emplace(Status(Error::OutOfMemory, "out of memory"));
    } catch (const std::exception& e) {
      grid_.emplace(Status(Error::Internal, std::string("building it threw: ") + e.what()));
    }
  }
  const SurfaceMesh& surface_;
  const metric::SurfaceSizingOptions& options_;
  bool wanted_, started_ = false, waited_ = false;
  tbb::task_group group_;
  std::optional<Result<metric::MetricField>> grid_;
};

// The field stages 3b and 3c follow and what it is built from (the caller's field, or the default
// grid; intersected with the boundary layer's metric with boundary_layer_sizing). `field` points
// into the object: it is not copied or moved.
struct StageField {
  StageField() = default;
  StageField(const StageField&) = delete;
  StageField& operator=(const StageField&) = delete;
  std::optional<metric::MetricField> grid;
  std::optional<metric::BoundaryLayerField> bl_field;
  const SizingField* field = nullptr;
};

// One run of the pipeline after validation, its steps in order (Mesher::run_in_range).
class MeshingRun {
 public:
  // `surface`: the one meshed; `sizing_surface`: the one the default sizes come from (the input,
  // when the slide patches' thin band triangles are in `surface`).
  MeshingRun(const MesherOptions& options, const SurfaceMesh& surface, const SurfaceMesh& sizing_surface)
      : o_(options),
        surface_(surface),
        sizing_surface_(sizing_surface),
        grid_(sizing_surface, options.surface_sizing, (options.run_refine || options.run_optimize) && !options.sizing) {}

  Result<MesherResult> run() {
    const auto start = Clock::now();
    // The default grid's OpenVDB module opens during stage 1 (see metric::VdbModulePreload; at
    // once when the caller opened it already).
    std::optional<metric::VdbModulePreload> preload;
    if ((o_.run_refine || o_.run_optimize) && !o_.sizing && tbb::this_task_arena::max_concurrency() > 1)
      preload.emplace();
    if (Status st = check_options(); !st.ok()) return st;
    if (Status st = progress("layers", kDoneAfterValidate); !st.ok()) return st;
    Result<CoupledMesh> coupled = stages_1_and_2();
    if (!coupled.ok()) return coupled.status();
    TetMesh& mesh = coupled->mesh;
    const auto bodies = int32_t(coupled->stats.bodies);
    if (o_.layers.boundary_layer.enabled()) result_.boundary_layer.vertices = freeze_boundary_layer(mesh, bodies);
    if (o_.layers.boundary_layer.enabled() && o_.stage3 && o_.stage3_leaves_no_mesh)
      measure_layers(mesh, bodies, false);
    if (o_.run_refine || o_.run_optimize) {
      if (Status st = progress("sizing", kDoneAfterCoupling); !st.ok()) return st;
      StageField field;  // (it points into itself: filled in place)
      if (Status st = stage_field(field); !st.ok()) return st;
      if (Status st = refine_and_optimize(mesh, *field.field); !st.ok()) return st;
    }
    finish(mesh, bodies);
    if (Status st = progress("done", 1.0); !st.ok()) return st;
    result_.seconds = since(start);
    return std::move(result_);
  }

 private:
  Status check_options() const {
    const BoundaryLayerOptions& bl = o_.layers.boundary_layer;
    if (bl.enabled() && bl.region == 0)
      return Status(Error::InvalidArgument, "boundary layer: region must be nonzero (coupling tells the BL tets by it)");
    if (o_.boundary_layer_sizing && !(bl.enabled() && bl.growth > 1.0))
      return Status(Error::InvalidArgument, "boundary-layer sizing needs a boundary layer (wall patches) with growth above 1");
    return Status::success();
  }

  Status progress(const char* stage, double fraction) {
    if (cancel_asked_ || (o_.progress && !o_.progress(stage, fraction)))
      return Status(Error::Cancelled, std::string("cancelled at stage '") + stage + "'");
    return Status::success();
  }

  template <class F>
  static auto isolated(F&& f) {
    return tbb::this_task_arena::isolate(f);
  }

  // Stages 1 and 2 and the coupling are tried with these layer counts and recovery strategies in
  // turn until one attempt gives a coupled mesh. When stage 2 cannot recover S1, stage 1 runs again
  // with another number of layers (fewer first, down to 1, then more, up to 3): S1 changes shape
  // and its recovery may then succeed. The fast split-constraints recovery is tried with every
  // layer count before the slower fuzzy-face strategies are: another layer count it recovers costs
  // far less than they do. A recovered S2 whose subfaces do not all give positive cones from their
  // T1 apexes (rounding, on slivers) fails the coupling, and the next attempt is tried as for a
  // recovery failure.
  std::vector<std::pair<int, RecoveryOptions>> attempts() const {
    std::vector<int> layer_counts = {o_.layers.layers};
    if (o_.retry_layer_counts) {
      for (int n = o_.layers.layers - 1; n >= 1; --n) layer_counts.push_back(n);
      // Then more layers, up to 3 at least (the default of 1 gets 2 and 3).
      for (int n = o_.layers.layers + 1; n <= std::max(o_.layers.layers + 1, 3); ++n) layer_counts.push_back(n);
    }
    std::vector<std::pair<int, RecoveryOptions>> out;
    const RecoveryOptions& ro = o_.recovery;
    if (ro.split_constraints && ro.fuzzy_faces) {
      RecoveryOptions split = ro, fuzzy = ro;
      split.fuzzy_faces = false;
      fuzzy.split_constraints = false;
      for (int n : layer_counts) out.push_back({n, split});
      for (int n : layer_counts) out.push_back({n, fuzzy});
    } else {
      for (int n : layer_counts) out.push_back({n, ro});
    }
    return out;
  }

  // The recovery's options for S1: every piece of an S1 face must see that face's T1 apex, so
  // that the coupling's cones over them are positive (split-constraints strategy); the attempts'
  // budget bounds its time.
  RecoveryOptions recovery_options(RecoveryOptions ro, const LayersOutput& layers, const SurfaceMesh& s1,
                                   double budget_left) const {
    ro.face_apex.resize(3 * s1.num_triangles());
    for (size_t i = 0; i < s1.num_triangles(); ++i) {
      const uint32_t apex = layers.mesh.vertex(layers.front_tet[i], int(layers.front_facet[i]));
      std::copy(layers.mesh.point(apex), layers.mesh.point(apex) + 3, &ro.face_apex[3 * i]);
    }
    if (o_.attempts_seconds > 0) {
      // The fuzzy faces run up to three variants, each with max_seconds.
      const double left = std::max(1.0, budget_left);
      ro.split_max_seconds = std::min(ro.split_max_seconds, left);
      const double variants = ro.retry_strategies ? 3.0 : 1.0;
      ro.max_seconds = std::min(ro.max_seconds, left / variants);
    }
    return ro;
  }

  Result<CoupledMesh> stages_1_and_2() {
    const IsotropicSurfaceSizing surface_sizing(sizing_surface_);
    const LayerSizing sizing(surface_sizing, o_.sizing);
    const std::vector<std::pair<int, RecoveryOptions>> tries = attempts();
    Result<CoupledMesh> coupled = Status(Error::Internal, "no layer count tried");
    Status first_failure;
    std::string failed_stage;
    const auto attempts_start = Clock::now();
    const double budget = o_.attempts_seconds;
    size_t attempts_run = 0;
    bool out_of_time = false;
    auto failed = [&](const Status& st, const char* stage) {
      if (!first_failure.ok()) return;
      first_failure = st;
      failed_stage = stage;
    };
    for (size_t attempt = 0; attempt < tries.size(); ++attempt) {
      if (attempt > 0 && budget > 0 && since(attempts_start) >= budget) {
        out_of_time = true;
        break;
      }
      ++attempts_run;
      auto t = Clock::now();
      LayersOptions layer_options = o_.layers;
      layer_options.layers = tries[attempt].first;
      Result<LayersOutput> layers = isolated([&] { return build_layers(surface_, sizing, layer_options); });
      if (!layers.ok()) return Status(layers.status().code(), "stage 1 (layers): " + layers.status().message());
      result_.layers = layers->stats;
      result_.layers_retries = attempt;
      result_.layers_used = layer_options.layers;
      result_.stages.push_back({attempt == 0 ? "layers" : "layers (retry)", since(t), layers->stats.tets});
      grid_.start();

      if (Status st = progress("recovery", kDoneAfterLayers); !st.ok()) return st;
      t = Clock::now();
      std::vector<uint32_t> s1_map;
      const SurfaceMesh s1 = front_surface(layers.value(), &s1_map);
      const RecoveryOptions ro = recovery_options(tries[attempt].second, layers.value(), s1, budget - since(attempts_start));
      Result<RecoveryOutput> recovered = isolated([&] { return recover_boundary(s1, ro); });
      result_.stages.push_back({attempt == 0 ? "recovery" : "recovery (retry)", since(t),
                                recovered.ok() ? recovered->stats.tets : 0});
      if (!recovered.ok()) {
        const bool retry = recovered.status().code() == Error::RecoveryFailed;
        if (!retry) first_failure = Status();  // this one is the error to report
        failed(recovered.status(), "stage 2 (recovery of S1): ");
        if (retry) continue;
        break;
      }
      if (o_.layers.boundary_layer.enabled()) {
        t1_origin_ = layers->vertex_origin;
        t1_xyz_ = layers->mesh.xyz;
      }
      if (Status st = progress("coupling", kDoneAfterRecovery); !st.ok()) return st;
      t = Clock::now();
      coupled = isolated([&] { return couple_meshes(surface_, std::move(layers).value(), s1_map, recovered.value()); });
      result_.stages.push_back({attempt == 0 ? "coupling" : "coupling (retry)", since(t),
                                coupled.ok() ? coupled->stats.tets : 0});
      if (coupled.ok()) {
        result_.recovery = recovered->stats;
        result_.couple = coupled->stats;
        return coupled;
      }
      failed(coupled.status(), "stage 3 (coupling): ");
    }
    std::string msg = failed_stage + first_failure.message();
    if (tries.size() > 1)
      msg += " (" + std::to_string(attempts_run) + " of " + std::to_string(tries.size()) +
             " attempts: layer counts and recovery strategies";
    if (out_of_time)
      msg += "; the others not run: the attempts' budget of " + std::to_string(int(budget)) +
             " s ran out (attempts_seconds; --attempts-seconds on the command line)";
    if (tries.size() > 1) msg += ")";
    return Status(first_failure.code(), msg);
  }

  Status stage_field(StageField& out) {
    const auto t = Clock::now();
    out.field = o_.sizing;
    if (!out.field) {
      Result<metric::MetricField> built = grid_.take();
      if (!built.ok()) return Status(built.status().code(), "sizing field: " + built.status().message());
      out.field = &out.grid.emplace(std::move(built).value());
    }
    // boundary_layer_sizing: the interior's sizes continue the layers' heights (normal size
    // h0 + (r - 1) d at distance d from the walls, intersected with the field above), so the tets
    // on the BL's top are about as thin as its last layer and grow from there.
    const BoundaryLayerOptions& bl = o_.layers.boundary_layer;
    if (bl.enabled() && o_.boundary_layer_sizing) {
      metric::BoundaryLayerOptions bo;
      bo.first_height = bl.first_height;
      bo.growth = bl.growth;
      bo.wall_patches = bl.wall_patches;
      if (o_.boundary_layer_sizing_growth > 0.0) {
        const int n = boundary_layer_count(bl);
        bo.layers_thickness = bl.first_height * (std::pow(bl.growth, n) - 1.0) / (bl.growth - 1.0);
        bo.interior_growth = o_.boundary_layer_sizing_growth;
      }
      Result<metric::BoundaryLayerField> built = metric::BoundaryLayerField::create(surface_, *out.field, bo);
      if (!built.ok()) return Status(built.status().code(), "boundary-layer sizing: " + built.status().message());
      out.field = &out.bl_field.emplace(std::move(built).value());
    }
    result_.stages.push_back({"sizing", since(t), 0});
    return Status::success();
  }

  Status refine_and_optimize(TetMesh& mesh, const SizingField& field) {
    const ScaledSizing scaled(field, o_.refine.size_scale > 0.0 ? o_.refine.size_scale : 1.0);
    if (o_.run_refine) {
      result_.estimated_tets = estimate_refined_tets(mesh, scaled);
      if (o_.max_tets > 0 && result_.estimated_tets > o_.max_tets) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      "the sizing field asks for about %.3g tets (estimated before refinement), more than the limit of %.3g",
                      result_.estimated_tets, o_.max_tets);
        return Status(Error::InvalidArgument, msg);
      }
      // (Refinement makes up to about half more than estimated; a mesh holds 2^30 tet slots.)
      if (1.5 * result_.estimated_tets > double(TetMesh::kMaxTetSlots)) {
        char msg[240];
        std::snprintf(msg, sizeof msg,
                      "the sizing field asks for about %.3g tets (estimated before refinement): more than one mesh "
                      "holds (2^30 tet slots); use a coarser size",
                      result_.estimated_tets);
        return Status(Error::InvalidArgument, msg);
      }
    }
    if (o_.stage3) {
      if (!o_.run_refine || !o_.run_optimize)
        return Status(Error::NotImplemented, "stages 3b/3c in parts need both refinement and optimization");
      if (Status st = progress("refine", kDoneAfterSizing); !st.ok()) return st;
      const auto t = Clock::now();
      if (Status st = o_.stage3(mesh, field, result_.refine, result_.optimize); !st.ok())
        return Status(st.code(), "stages 3b/3c in parts: " + st.message());
      result_.stages.push_back({"refine+optimize in parts", since(t), result_.optimize.after.tets});
    } else {
      if (o_.run_refine)
        if (Status st = refine(mesh, field); !st.ok()) return st;
      if (o_.run_optimize)
        if (Status st = optimize(mesh, scaled); !st.ok()) return st;
      if (o_.run_refine && o_.run_optimize && result_.optimize.anisotropic && o_.anisotropic_cycles > 0) {
        if (Status st = progress("cycles", kDoneAfterOptimize); !st.ok()) return st;
        const auto t = Clock::now();
        if (Status st = refine_optimize_cycles(mesh, field, o_.refine, o_.optimize, o_.anisotropic_cycles,
                                               result_.refine, result_.optimize, o_.anisotropic_cycle_gain,
                                               &result_.anisotropic_cycles, o_.anisotropic_cycle_optimizer_gain);
            !st.ok())
          return st;
        result_.stages.push_back({"cycles", since(t), result_.optimize.after.tets});
      }
    }
    if (result_.optimize.anisotropic) result_.metric_quality = summarize_metric_quality(mesh, scaled);
    return Status::success();
  }

  // Refinement and optimization tell their progress within the stage; a cancel asked there takes
  // effect at the next stage, and the callback is not called again meanwhile.
  std::function<void(double)> within(const char* stage, double from, double to) {
    return [this, stage, from, to](double f) {
      if (o_.progress && !cancel_asked_ && !o_.progress(stage, from + f * (to - from))) cancel_asked_ = true;
    };
  }

  Status refine(TetMesh& mesh, const SizingField& field) {
    if (Status st = progress("refine", kDoneAfterSizing); !st.ok()) return st;
    const auto t = Clock::now();
    RefineOptions options = o_.refine;
    options.expected_tets = result_.estimated_tets;
    options.progress = within("refine", kDoneAfterSizing, kDoneAfterRefine);
    const auto coupled_vertices = static_cast<uint32_t>(mesh.num_vertices());
    Result<RefineStats> refined = refine_mesh(mesh, field, options);
    if (!refined.ok()) return Status(refined.status().code(), "stage 3b (refinement): " + refined.status().message());
    // The optimizer walks balls and rings all over the mesh, which refinement's passes leave
    // scattered in memory: renumbered, neighbours sit close. The coupled mesh's vertices keep their
    // ids (stage 1's boundary-layer figures are measured by them).
    order_for_locality(mesh, coupled_vertices);
    result_.refine = refined.value();
    result_.stages.push_back({"refine", since(t), refined->tets_after});
    return Status::success();
  }

  Status optimize(TetMesh& mesh, const SizingField& scaled) {
    if (Status st = progress("optimize", kDoneAfterRefine); !st.ok()) return st;
    const auto t = Clock::now();
    OptimizeOptions options = o_.optimize;
    options.progress = within("optimize", kDoneAfterRefine, kDoneAfterOptimize);
    Result<OptimizeStats> optimized = optimize_mesh(mesh, scaled, options);
    if (!optimized.ok())
      return Status(optimized.status().code(), "stage 3c (optimization): " + optimized.status().message());
    result_.optimize = optimized.value();
    result_.stages.push_back({"optimize", since(t), optimized->after.tets});
    return Status::success();
  }

  // The boundary layer's figures on `mesh`: its columns, and with `cells` its dual faces and
  // transition (result_.boundary_layer.vertices, set when the layers were frozen, is kept).
  void measure_layers(const TetMesh& mesh, int32_t bodies, bool cells) {
    const BoundaryLayerOptions& bl = o_.layers.boundary_layer;
    BoundaryLayerReport& r = result_.boundary_layer;
    measure_boundary_layer(surface_, bl, result_.layers.bl_layers, t1_origin_, t1_xyz_, mesh, bodies, r);
    if (cells) measure_boundary_layer_cells(mesh, bodies, r);
    r.tets = 0;
    for (uint32_t k = 0; k < mesh.num_tet_slots(); ++k)
      if (!mesh.is_deleted(k) && !mesh.is_ghost(k) && mesh.tet_region[k] >= bodies) ++r.tets;
    r.reduced_vertices = result_.layers.bl_reduced_vertices;
  }

  // The boundary layer's figures, then the VolumeMesh: vertices of no tet are dropped (those
  // coarsening removed, and input vertices of no triangle, e.g. a volume mesh's interior ones);
  // the input's others stay first, in input order. The boundary triangles are the input's,
  // renumbered with the vertices.
  // The VolumeMesh is made of the TetMesh's own arrays (the run's last use of it), compacted in
  // place: no second copy of the tets at the end of large runs (issue 49).
  void finish(TetMesh& mesh, int32_t bodies) {
    const auto t = Clock::now();
    const BoundaryLayerOptions& bl = o_.layers.boundary_layer;
    if (bl.enabled() && !(o_.stage3 && o_.stage3_leaves_no_mesh)) measure_layers(mesh, bodies, true);
    std::vector<uint32_t> vertex_map;
    result_.mesh = mesh.take_volume_mesh(/*drop_unused_vertices=*/true, surface_.tri, surface_.patch, &vertex_map);
    result_.input_vertex.assign(vertex_map.begin(), vertex_map.begin() + std::ptrdiff_t(surface_.num_vertices()));
    if (bl.enabled()) {
      // Stage 1's vertex ids are the final TetMesh's (BL vertices are locked).
      result_.bl_first_region = bodies;
      result_.bl_vertex_origin.assign(result_.mesh.num_vertices(), TetMesh::kNone);
      for (size_t v = 0; v < t1_origin_.size() && v < vertex_map.size(); ++v) {
        const uint32_t from = t1_origin_[v];
        if (vertex_map[v] != TetMesh::kNone && from != TetMesh::kNone && vertex_map[from] != TetMesh::kNone)
          result_.bl_vertex_origin[vertex_map[v]] = vertex_map[from];
      }
    }
    result_.stages.push_back({"output", since(t), result_.mesh.num_tets()});
    result_.notices = shortfalls(result_, o_);
  }

  const MesherOptions& o_;
  const SurfaceMesh& surface_;
  const SurfaceMesh& sizing_surface_;
  DefaultGrid grid_;
  MesherResult result_;
  std::vector<uint32_t> t1_origin_;  // kept for the boundary-layer figures (stage 1's vertex ids
  std::vector<double> t1_xyz_;       // survive the later stages)
  bool cancel_asked_ = false;        // by a progress call within a stage
};

}  // namespace

Result<MesherResult> Mesher::run_in_range(const SurfaceMesh& surface) const {
  const BoundaryLayerOptions& bl = options_.layers.boundary_layer;
  if (!bl.enabled() || bl.slide_patches.empty()) return MeshingRun(options_, surface, surface).run();
  // Walls meeting slide patches: those are re-triangulated around the layers' columns first,
  // and the pipeline meshes that surface (its other patches the input's, exactly).
  const auto t = Clock::now();
  if (options_.progress && !options_.progress("slide patches", 0.0))
    return Status(Error::Cancelled, "cancelled before the slide patches");
  Result<SlideSurface> slid = slide_and_validate(surface, bl, options_.validation);
  if (!slid.ok()) return slid.status();
  MesherOptions options = options_;
  options.layers.boundary_layer.column_next = std::move(slid->column_next);
  const double seconds = since(t);
  Result<MesherResult> run = MeshingRun(options, slid->surface, surface).run();
  if (!run.ok()) return run;
  MesherResult& r = run.value();
  r.slide = slide_report(std::move(slid).value());
  r.stages.insert(r.stages.begin(), {"slide patches", seconds, 0});
  r.seconds += seconds;
  return run;
}

Status refine_optimize_cycles(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                              const OptimizeOptions& optimize_options, int cycles, RefineStats& refine,
                              OptimizeStats& optimize, double min_gain, int* cycles_run,
                              double min_optimizer_gain) {
  const ScaledSizing scaled(field, refine_options.size_scale > 0.0 ? refine_options.size_scale : 1.0);
  if (cycles_run) *cycles_run = 0;
  bool gained = true;
  for (int c = 0; c < cycles && gained; ++c) {
    if (min_optimizer_gain > 0.0 && optimize.anisotropic &&
        optimize.length_in_range_after < optimize.length_in_range_before + min_optimizer_gain)
      break;
    const double in_range_before = refine.length_in_range;
    const auto kept_vertices = static_cast<uint32_t>(mesh.num_vertices());
    Result<RefineStats> r = refine_mesh(mesh, field, refine_options);
    if (!r.ok()) return Status(r.status().code(), "stage 3b (refinement, cycle " + std::to_string(c + 2) + "): " + r.status().message());
    order_for_locality(mesh, kept_vertices);
    refine.passes += r->passes;
    refine.stopped_at_pass_cap = refine.stopped_at_pass_cap || r->stopped_at_pass_cap;
    refine.metric_not_spd = std::max(refine.metric_not_spd, r->metric_not_spd);
    refine.splits += r->splits;
    refine.split_rejected += r->split_rejected;
    refine.parallel_splits += r->parallel_splits;
    refine.collapses += r->collapses;
    refine.collapse_rejected += r->collapse_rejected;
    refine.metric_flips += r->metric_flips;
    refine.vertices_after = r->vertices_after;
    refine.tets_after = r->tets_after;
    refine.length_mean = r->length_mean;
    refine.length_in_range = r->length_in_range;
    // The round's optimization runs whatever the gain (its refinement changed the mesh).
    gained = r->length_in_range >= in_range_before + min_gain;
    refine.seconds += r->seconds;
    refine.seconds_edges += r->seconds_edges;
    refine.seconds_choice += r->seconds_choice;
    refine.seconds_insertion += r->seconds_insertion;
    refine.seconds_collapses += r->seconds_collapses;
    refine.seconds_flips += r->seconds_flips;
    Result<OptimizeStats> o = optimize_mesh(mesh, scaled, optimize_options);
    if (!o.ok()) return Status(o.status().code(), "stage 3c (optimization, cycle " + std::to_string(c + 2) + "): " + o.status().message());
    optimize.moves += o->moves;
    optimize.moves_rejected += o->moves_rejected;
    optimize.flips23 += o->flips23;
    optimize.edge_removals += o->edge_removals;
    optimize.perturbations += o->perturbations;
    optimize.collapses += o->collapses;
    optimize.flat_found = o->flat_found;
    optimize.flat_left = o->flat_left;
    optimize.after = o->after;
    optimize.anisotropic = optimize.anisotropic || o->anisotropic;
    optimize.length_in_range_before = o->length_in_range_before;
    optimize.length_in_range_after = o->length_in_range_after;
    optimize.seconds += o->seconds;
    optimize.seconds_setup += o->seconds_setup;
    optimize.seconds_cvt += o->seconds_cvt;
    optimize.seconds_flips += o->seconds_flips;
    optimize.seconds_slivers += o->seconds_slivers;
    optimize.seconds_certify += o->seconds_certify;
    if (cycles_run) ++*cycles_run;
  }
  return Status::success();
}

}  // namespace anitet

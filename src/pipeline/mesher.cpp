#include "pipeline/mesher.hpp"

#include <chrono>
#include <optional>

#include "core/sizing.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Share of the run's time each stage takes, roughly, for the progress fraction.
constexpr double kDoneAfterValidate = 0.03, kDoneAfterLayers = 0.2, kDoneAfterRecovery = 0.35,
                 kDoneAfterCoupling = 0.4, kDoneAfterSizing = 0.45, kDoneAfterRefine = 0.7;

}  // namespace

Result<MesherResult> Mesher::run(const SurfaceMesh& surface) const {
  SurfaceMesh repaired = surface;
  if (options_.progress && !options_.progress("validate", 0.0))
    return Status(Error::Cancelled, "cancelled before validation");
  const ValidationReport report = validate_surface(repaired, options_.validation);
  if (!report.ok()) return report.status();
  return run_validated(repaired);
}

Result<MesherResult> Mesher::run_validated(const SurfaceMesh& surface) const {
  const auto start = Clock::now();
  auto progress = [&](const char* stage, double fraction) -> Status {
    if (options_.progress && !options_.progress(stage, fraction))
      return Status(Error::Cancelled, std::string("cancelled at stage '") + stage + "'");
    return Status::success();
  };
  MesherResult result;

  if (Status st = progress("layers", kDoneAfterValidate); !st.ok()) return st;
  auto t = Clock::now();
  const IsotropicSurfaceSizing sizing(surface);
  Result<LayersOutput> layers = build_layers(surface, sizing, options_.layers);
  if (!layers.ok()) return Status(layers.status().code(), "stage 1 (layers): " + layers.status().message());
  result.layers = layers->stats;
  result.stages.push_back({"layers", since(t), layers->stats.tets});

  if (Status st = progress("recovery", kDoneAfterLayers); !st.ok()) return st;
  t = Clock::now();
  std::vector<uint32_t> s1_map;
  const SurfaceMesh s1 = front_surface(layers.value(), &s1_map);
  Result<RecoveryOutput> recovered = recover_boundary(s1, options_.recovery);
  if (!recovered.ok())
    return Status(recovered.status().code(), "stage 2 (recovery of S1): " + recovered.status().message());
  result.recovery = recovered->stats;
  result.stages.push_back({"recovery", since(t), recovered->stats.tets});

  if (Status st = progress("coupling", kDoneAfterRecovery); !st.ok()) return st;
  t = Clock::now();
  Result<CoupledMesh> coupled = couple_meshes(surface, std::move(layers).value(), s1_map, recovered.value());
  if (!coupled.ok()) return Status(coupled.status().code(), "stage 3 (coupling): " + coupled.status().message());
  result.couple = coupled->stats;
  result.stages.push_back({"coupling", since(t), coupled->stats.tets});

  TetMesh& mesh = coupled->mesh;
  if (options_.run_refine || options_.run_optimize) {
    if (Status st = progress("sizing", kDoneAfterCoupling); !st.ok()) return st;
    t = Clock::now();
    const SizingField* field = options_.sizing;
    std::optional<metric::MetricField> grid;
    if (!field) {
      Result<metric::MetricField> built = metric::surface_sizing_field(surface, options_.surface_sizing);
      if (!built.ok()) return Status(built.status().code(), "sizing field: " + built.status().message());
      grid.emplace(std::move(built).value());
      field = &*grid;
    }
    result.stages.push_back({"sizing", since(t), 0});
    const ScaledSizing scaled(*field, options_.refine.size_scale > 0.0 ? options_.refine.size_scale : 1.0);
    if (options_.run_refine) {
      if (Status st = progress("refine", kDoneAfterSizing); !st.ok()) return st;
      t = Clock::now();
      Result<RefineStats> refined = refine_mesh(mesh, *field, options_.refine);
      if (!refined.ok()) return Status(refined.status().code(), "stage 3b (refinement): " + refined.status().message());
      result.refine = refined.value();
      result.stages.push_back({"refine", since(t), refined->tets_after});
    }
    if (options_.run_optimize) {
      if (Status st = progress("optimize", kDoneAfterRefine); !st.ok()) return st;
      t = Clock::now();
      Result<OptimizeStats> optimized = optimize_mesh(mesh, scaled, options_.optimize);
      if (!optimized.ok())
        return Status(optimized.status().code(), "stage 3c (optimization): " + optimized.status().message());
      result.optimize = optimized.value();
      result.stages.push_back({"optimize", since(t), optimized->after.tets});
    }
  }

  t = Clock::now();
  // Vertices removed by coarsening are dropped; the input's stay first, in input order (they
  // bound S's facets, so they are all used).
  result.mesh = mesh.to_volume_mesh(/*drop_unused_vertices=*/options_.run_refine);
  result.mesh.bnd_tri = surface.tri;
  result.mesh.bnd_patch = surface.patch;
  result.stages.push_back({"output", since(t), result.mesh.num_tets()});
  if (Status st = progress("done", 1.0); !st.ok()) return st;
  result.seconds = since(start);
  return result;
}

}  // namespace anitet

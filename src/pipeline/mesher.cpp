#include "pipeline/mesher.hpp"

#include <chrono>

#include "core/sizing.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Share of the run's time each stage takes, roughly, for the progress fraction.
constexpr double kDoneAfterValidate = 0.05, kDoneAfterLayers = 0.45, kDoneAfterRecovery = 0.9;

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

  t = Clock::now();
  result.mesh = coupled->mesh.to_volume_mesh(/*drop_unused_vertices=*/false);
  result.mesh.bnd_tri = surface.tri;
  result.mesh.bnd_patch = surface.patch;
  result.stages.push_back({"output", since(t), result.mesh.num_tets()});
  if (Status st = progress("done", 1.0); !st.ok()) return st;
  result.seconds = since(start);
  return result;
}

}  // namespace anitet

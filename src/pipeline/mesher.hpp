// The Mesher: the stages in order, behind one class.
//   validate -> stage 1 (layers) -> stage 2 (Delaunay of S1 + conforming recovery) -> coupling
//   -> (refinement and optimization: not implemented yet) -> a VolumeMesh.
// Same input and options, same mesh, bit for bit (every stage is deterministic and sequential).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "couple/couple.hpp"
#include "layers/layers.hpp"
#include "recovery/recovery.hpp"
#include "validate/validate.hpp"

namespace anitet {

// Called at the start and end of every stage with the stage's name and the fraction of the whole
// run done; returning false cancels the run (Error::Cancelled) at that point. Stages are not
// interrupted in the middle.
using ProgressCallback = std::function<bool(const std::string& stage, double fraction)>;

struct MesherOptions {
  LayersOptions layers;
  RecoveryOptions recovery;
  ValidationOptions validation;
  ProgressCallback progress;  // may be empty
};

struct StageReport {
  std::string name;
  double seconds = 0.0;
  size_t tets = 0;  // tets the stage leaves (its own output)
};

struct MesherResult {
  // Vertices: the input's first, in input order; tets positive; regions per body; boundary
  // triangles: the input's, with their patch labels.
  VolumeMesh mesh;
  std::vector<StageReport> stages;
  LayersStats layers;
  RecoveryStats recovery;
  CoupleStats couple;
  double seconds = 0.0;
};

class Mesher {
 public:
  explicit Mesher(MesherOptions options = {}) : options_(std::move(options)) {}

  // Validates (and safely repairs a copy of) the surface, then meshes it.
  Result<MesherResult> run(const SurfaceMesh& surface) const;
  // Meshes a surface that validate_surface() has already accepted (and repaired).
  Result<MesherResult> run_validated(const SurfaceMesh& surface) const;

 private:
  MesherOptions options_;
};

}  // namespace anitet

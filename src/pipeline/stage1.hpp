// Stage 1 alone (`anitet mesh --stop-after layers`, anitet_layers_run): the advancing-front
// layers on a validated surface, audited, and T1 as a volume mesh.
#pragma once

#include <cstdint>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "layers/layers.hpp"
#include "layers/layers_check.hpp"
#include "pipeline/bl_report.hpp"

namespace anitet {

// S1's patch label in T1: one more than the surface's largest label (at least 1).
int32_t front_patch_label(const SurfaceMesh& surface);

struct Stage1Result {
  LayersOutput layers;
  LayersCheck check;
  // T1: the surface's triangles as boundary triangles under their labels and S1's under
  // front_label; vertices of no tet (input vertices of no triangle) dropped.
  VolumeMesh mesh;
  int32_t front_label = 1;
  BoundaryLayerReport boundary_layer;  // measured on T1 (when options ask for one)
};

// The layers follow the surface's own sizes (IsotropicSurfaceSizing), as in the full pipeline
// without a metric. Errors: build_layers'; Error::Internal when the audit fails (a bug).
Result<Stage1Result> run_stage1(const SurfaceMesh& surface, const LayersOptions& options);

}  // namespace anitet

// Stage 1 alone (`anitet mesh --stop-after layers`, anitet_layers_run): the advancing-front
// layers on a validated surface, audited, and T1 as a volume mesh.
#pragma once

#include <cstdint>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "layers/layers.hpp"
#include "layers/layers_check.hpp"
#include "layers/slide_patches.hpp"
#include "pipeline/bl_report.hpp"
#include "validate/validate.hpp"

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
  // With slide patches (options.boundary_layer.slide_patches): the surface stage 1 ran on (the
  // input, those patches re-triangulated), whose triangles T1's boundary holds.
  SlideReport slide;
  const SurfaceMesh& surface(const SurfaceMesh& input) const { return slide.surface.tri.empty() ? input : slide.surface; }
};

// Stage 1's sizing, the same in the pipeline and in run_stage1: the user's field (`user`, e.g. the
// OpenVDB MetricField of --metric, the one refinement and CVT follow) wherever it is anisotropic,
// so that the layers' heights, directions and margins are measured in its tensor; the surface's
// own sizes (`surface`, heights in proportion to the triangles they stand on) where it is
// isotropic or when there is none. With the surface's sizes, the layers on stretched triangles
// came out far thinner than the metric asks, and refinement cannot make up for that. Without a
// metric the sizing grid (metric::surface_sizing_field) is not used here: it is built during
// stage 2, and its pinned voxels hold the triangles' shortest edge, not the mean edge the
// layers' heights are planned from (docs/sizing-and-metrics.md, "Stage 1").
class LayerSizing final : public SizingField {
 public:
  LayerSizing(const SizingField& surface, const SizingField* user) : surface_(surface), user_(user) {}
  void metric(const double p[3], double m[6]) const override {
    if (user_) {
      user_->metric(p, m);
      if (!metric_is_isotropic(m)) return;
    }
    surface_.metric(p, m);
  }
  bool isotropic() const override { return !user_ && surface_.isotropic(); }

 private:
  const SizingField& surface_;
  const SizingField* user_;
};

// The layers follow LayerSizing: the input's own sizes (IsotropicSurfaceSizing) and `metric`
// where it is anisotropic, as in the full pipeline; with slide patches they run on the surface
// slide_and_validate gives (the sizes still the input's). Errors: build_layers' and
// slide_and_validate's; Error::Internal when the audit fails (a bug).
Result<Stage1Result> run_stage1(const SurfaceMesh& surface, const LayersOptions& options,
                                const SizingField* metric = nullptr);

// Walls meeting slide patches (slide_patches.hpp): the surface with those patches re-triangulated
// around the junction columns, validated again (Error::Internal when it is not valid as it is: a
// bug). Messages start with "boundary layer: ".
Result<SlideSurface> slide_and_validate(const SurfaceMesh& surface, const BoundaryLayerOptions& bl,
                                        const ValidationOptions& validation = {});

}  // namespace anitet

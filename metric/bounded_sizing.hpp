// The sizing field stages 3b/3c follow, with the user's size bounds and gradation applied: the
// one place that turns "a field (or none) and --hmin/--hmax/--hgrad" into a field, for the CLI and
// the C ABI alike.
#pragma once

#include <memory>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "metric/metric_field.hpp"
#include "metric/surface_sizing.hpp"

namespace anitet {
namespace metric {

// Size bounds (absolute lengths, <= 0: none) and gradation (> 1; 0: none).
struct SizeBounds {
  double hmin = 0.0, hmax = 0.0, hgrad = 0.0;
  bool any() const { return hmin > 0.0 || hmax > 0.0 || hgrad > 0.0; }
};
// Error::InvalidArgument unless hmin, hmax >= 0 and finite, hmin <= hmax when both are given, and
// hgrad is 0 or > 1.
Status check_bounds(const SizeBounds& bounds);

// A field together with the fields it refers to (BoundedField and BackgroundMeshField hold
// references), so the caller gets one owner.
class OwningField final : public SizingField {
 public:
  void metric(const double p[3], double m[6]) const override { top_->metric(p, m); }
  bool isotropic() const override { return top_->isotropic(); }
  template <class F>
  F& keep(F&& field) {
    auto owned = std::make_unique<F>(std::move(field));
    F& ref = *owned;
    parts_.push_back(std::move(owned));
    top_ = &ref;
    return ref;
  }
  const SizingField& keep_owned(std::unique_ptr<SizingField> field) {
    top_ = field.get();
    parts_.push_back(std::move(field));
    return *top_;
  }
  // A field owned elsewhere (it must outlive this one), as the top.
  void refer(const SizingField& field) { top_ = &field; }
  const SizingField& top() const { return *top_; }

 private:
  std::vector<std::unique_ptr<SizingField>> parts_;
  const SizingField* top_ = nullptr;
};

// `field` sampled as a voxel field over the surface's box (padded by two voxels), spacing the
// surface's mean edge length grown until the box has at most 2^24 voxels.
Result<MetricField> sample_on_surface_box(const SizingField& field, const SurfaceMesh& surface);

// The field with the bounds applied. `base` null: the default grid of `surface` (surface_sizing
// with `default_sizing`), bounded and graded on its dense lattice before the sparse storage prunes
// it. `base` a MetricField (a .vdb): bounded and graded on its voxels. Any other field: bounded
// point-wise, and with a gradation sampled on a lattice over the surface's box first (gradation
// needs neighbours). `base` must outlive the result when it is not copied into it.
Result<std::unique_ptr<SizingField>> bounded_sizing_field(const SurfaceMesh& surface, const SizingField* base,
                                                          const SizeBounds& bounds,
                                                          const SurfaceSizingOptions& default_sizing = {});

}  // namespace metric
}  // namespace anitet

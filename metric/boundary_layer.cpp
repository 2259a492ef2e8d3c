// BoundaryLayerField's side in the library: every call goes to the OpenVDB module
// (vdb_backend.hpp).
#include "boundary_layer.hpp"

#include "vdb_backend.hpp"

namespace anitet {
namespace metric {

void BoundaryLayerField::ImplDeleter::operator()(Impl* impl) const {
  if (impl) loaded_vdb_backend().destroy(impl);
}

BoundaryLayerField::BoundaryLayerField(Impl* impl) : impl_(impl) {}
BoundaryLayerField::BoundaryLayerField(BoundaryLayerField&&) noexcept = default;
BoundaryLayerField& BoundaryLayerField::operator=(BoundaryLayerField&&) noexcept = default;
BoundaryLayerField::~BoundaryLayerField() = default;

Result<BoundaryLayerField> BoundaryLayerField::create(const SurfaceMesh& surface,
                                                      const SizingField& background,
                                                      const BoundaryLayerOptions& options,
                                                      BoundaryLayerStats* stats) {
  std::string error;
  const VdbBackend* vdb = vdb_backend(&error);
  if (!vdb) return Status(Error::NotImplemented, error);
  Impl* impl = nullptr;
  Status st = vdb->create_layer(surface, background, options, stats, &impl);
  if (!st.ok()) return st;
  return BoundaryLayerField(impl);
}

void BoundaryLayerField::metric(const double p[3], double m[6]) const {
  loaded_vdb_backend().layer_metric(*impl_, p, m);
}

bool BoundaryLayerField::wall_distance(const double p[3], double& d, double closest[3]) const {
  return loaded_vdb_backend().wall_distance(*impl_, p, d, closest);
}

}  // namespace metric
}  // namespace anitet

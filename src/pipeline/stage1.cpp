#include "pipeline/stage1.hpp"

#include <algorithm>
#include <utility>

#include "core/sizing.hpp"

namespace anitet {

int32_t front_patch_label(const SurfaceMesh& surface) {
  int32_t label = 1;
  for (int32_t p : surface.patch) label = std::max(label, p + 1);
  return label;
}

Result<Stage1Result> run_stage1(const SurfaceMesh& surface, const LayersOptions& options) {
  IsotropicSurfaceSizing sizing(surface);
  Result<LayersOutput> built = build_layers(surface, sizing, options);
  if (!built.ok()) return built.status();
  Stage1Result out;
  out.layers = std::move(built).value();
  const LayersOutput& r = out.layers;
  // The audit is the library's own independent check; a failure is a bug, reported as such.
  out.check = check_layers(surface, r);
  if (!out.check.ok()) return Status(Error::Internal, "the layers fail their audit: " + out.check.problems);
  out.front_label = front_patch_label(surface);
  std::vector<uint32_t> bnd_tri = surface.tri;
  std::vector<int32_t> bnd_patch = surface.patch;
  bnd_tri.insert(bnd_tri.end(), r.front_tri.begin(), r.front_tri.end());
  bnd_patch.insert(bnd_patch.end(), r.num_front_triangles(), out.front_label);
  out.mesh = r.mesh.to_volume_mesh(/*drop_unused_vertices=*/true, bnd_tri, bnd_patch);
  const BoundaryLayerOptions& bl = options.boundary_layer;
  if (bl.enabled()) {
    BoundaryLayerReport& b = out.boundary_layer;
    measure_boundary_layer(surface, bl, r.stats.bl_layers, r.vertex_origin, r.mesh.xyz, r.mesh, b);
    for (uint32_t k = 0; k < r.mesh.num_tet_slots(); ++k)
      if (!r.mesh.is_deleted(k) && r.mesh.tet_region[k] == bl.region) ++b.tets;
    b.reduced_vertices = r.stats.bl_reduced_vertices;
  }
  return out;
}

}  // namespace anitet

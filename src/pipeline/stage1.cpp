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

Result<SlideSurface> slide_and_validate(const SurfaceMesh& surface, const BoundaryLayerOptions& bl,
                                        const ValidationOptions& validation) {
  Result<SlideSurface> slid = slide_boundary_layer(surface, bl);
  if (!slid.ok()) return Status(slid.status().code(), "boundary layer: " + slid.status().message());
  SurfaceMesh checked = slid->surface;
  const ValidationReport report = validate_surface(checked, validation);
  if (!report.ok() || !report.repairs.empty())
    return Status(Error::Internal, "boundary layer: the slide patches re-triangulated around the layers do not give a "
                                   "valid surface: " +
                                       (report.ok() ? std::string("it needed repairs") : report.status().message()));
  return slid;
}

Result<Stage1Result> run_stage1(const SurfaceMesh& input, const LayersOptions& input_options,
                                const SizingField* metric) {
  const IsotropicSurfaceSizing surface_sizing(input);
  const LayerSizing sizing(surface_sizing, metric);
  Stage1Result out;
  LayersOptions options = input_options;
  if (options.boundary_layer.enabled() && !options.boundary_layer.slide_patches.empty()) {
    Result<SlideSurface> slid = slide_and_validate(input, options.boundary_layer);
    if (!slid.ok()) return slid.status();
    options.boundary_layer.column_next = std::move(slid->column_next);
    out.slide = slide_report(std::move(slid).value());
  }
  const SurfaceMesh& surface = out.surface(input);
  Result<LayersOutput> built = build_layers(surface, sizing, options);
  if (!built.ok()) return built.status();
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
    measure_boundary_layer(surface, bl, r.stats.bl_layers, r.vertex_origin, r.mesh.xyz, r.mesh, bl.region, b);
    measure_boundary_layer_cells(r.mesh, bl.region, b);
    for (uint32_t k = 0; k < r.mesh.num_tet_slots(); ++k)
      if (!r.mesh.is_deleted(k) && r.mesh.tet_region[k] == bl.region) ++b.tets;
    b.reduced_vertices = r.stats.bl_reduced_vertices;
  }
  return out;
}

}  // namespace anitet

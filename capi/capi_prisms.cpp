// Prism cells at the C ABI: the boundary layer's prisms kept beside the mesh's tets, written in
// place of them, and their getters.
#include <string>

#include "core/bl_prisms.hpp"
#include "prism_cells.hpp"
#include "shim.hpp"

namespace anitet::capi {

Status make_prism_cells(anitet_mesh& mesh) {
  VolumeMesh merged = mesh.mesh;
  // No pyramid cells at the ABI (no getters for them yet): a column that stopped in its layer
  // keeps its tets and, as before them, its layer's prisms beside it (3 bl_prisms + tets left =
  // BL tets still).
  Result<PrismMergeStats> stats = merge_bl_prisms(merged, mesh.run->bl_vertex_origin, mesh.run->bl_first_region,
                                                  &mesh.tet_prism, /*make_pyramids=*/false);
  if (!stats.ok()) return stats.status();
  mesh.prism = std::move(merged.prism);
  mesh.prism_region = std::move(merged.prism_region);
  mesh.prism_stats = stats.value();
  return Status::success();
}

VolumeMesh written_cells(const anitet_mesh& mesh) {
  const VolumeMesh& m = mesh.mesh;
  VolumeMesh out;
  out.xyz = m.xyz;
  out.bnd_tri = m.bnd_tri;
  out.bnd_patch = m.bnd_patch;
  out.vertex_metric = m.vertex_metric;
  for (size_t t = 0; t < m.num_tets(); ++t) {
    if (mesh.tet_prism[t] >= 0) continue;
    out.tet.insert(out.tet.end(), &m.tet[4 * t], &m.tet[4 * t + 4]);
    if (!m.region.empty()) out.region.push_back(m.region[t]);
  }
  out.prism = mesh.prism;
  out.prism_region = mesh.prism_region;
  return out;
}

}  // namespace anitet::capi

using namespace anitet::capi;

extern "C" {

int anitet_mesh_get_prism_count(const anitet_mesh* mesh, int64_t* num_prisms) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (num_prisms == nullptr) return null_argument(fn, "num_prisms");
    *num_prisms = int64_t(mesh->prism.size() / 6);
    return ok();
  });
}

int anitet_mesh_get_prisms(const anitet_mesh* mesh, int32_t* prisms, int64_t prisms_len, int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "prisms", mesh->prism, prisms, prisms_len,
                [&](uint32_t v) { return static_cast<int32_t>(v) + index_base; });
  });
}

int anitet_mesh_get_tet_prisms(const anitet_mesh* mesh, int32_t* tet_prism, int64_t tet_prism_len,
                               int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    const auto based = [&](int32_t p) { return p < 0 ? p : p + index_base; };
    if (!mesh->tet_prism.empty()) return fill(fn, "tet_prism", mesh->tet_prism, tet_prism, tet_prism_len, based);
    const std::vector<int32_t> none(mesh->mesh.num_tets(), -1);  // a mesh without prisms
    return fill(fn, "tet_prism", none, tet_prism, tet_prism_len, kSame);
  });
}

}  // extern "C"

#include "recovery/recovery_util.hpp"

#include <string>

#include "delaunay/delaunay.hpp"

namespace anitet::recovery_detail {

Status delaunay_of_surface_points(TetMesh& mesh, const SurfaceMesh& S) {
  Result<DelaunayStats> d = delaunay_tetrahedralize(mesh, S.xyz.data(), S.num_vertices());
  if (!d.ok()) return d.status();
  if (!d->duplicates.empty())
    return Status(Error::DuplicatePoint, "recover_boundary: input vertex " + std::to_string(d->duplicates[0].point) +
                                             " has the coordinates of vertex " +
                                             std::to_string(d->duplicates[0].same_as));
  return Status::success();
}

void keep_regions(TetMesh& mesh, const std::vector<int32_t>& comp, const std::vector<int32_t>& region) {
  const size_t nslots = mesh.num_tet_slots();
  for (uint32_t t = 0; t < nslots; ++t)
    if (!mesh.is_deleted(t) && region[comp[t]] >= 0) mesh.tet_region[t] = region[comp[t]];
  for (uint32_t t = 0; t < nslots; ++t) {
    if (mesh.is_deleted(t) || region[comp[t]] >= 0) continue;
    for (int i = 0; i < 4; ++i) {
      const uint64_t adj = mesh.tet_adj[4 * size_t(t) + i];
      if (adj == TetMesh::kNoNeighbour) continue;
      const auto n = static_cast<uint32_t>(adj >> 2);
      if (region[comp[n]] >= 0) mesh.tet_adj[adj] = TetMesh::kNoNeighbour;  // now a boundary facet
    }
    mesh.delete_tet(t);
  }
}

bool set_edge_constrained(TetMesh& mesh, const std::vector<uint32_t>& ball, uint32_t a, uint32_t b, bool on) {
  bool found = false;
  for (uint32_t t : ball)
    for (int k = 0; k < 6; ++k) {
      const uint32_t x = mesh.vertex(t, kEdgeVertex[k][0]), y = mesh.vertex(t, kEdgeVertex[k][1]);
      if (!((x == a && y == b) || (x == b && y == a))) continue;
      found = true;
      const auto bit = uint16_t(1u << (tflag::kEdgeConstrainedShift + k));
      if (on) mesh.tet_flags[t] |= bit;
      else mesh.tet_flags[t] &= uint16_t(~bit);
    }
  return found;
}

size_t count_live_tets(const TetMesh& mesh) {
  size_t tets = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && !mesh.is_ghost(t)) ++tets;
  return tets;
}

}  // namespace anitet::recovery_detail

#include "recovery/recovery_util.hpp"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "core/bvh.hpp"
#include "delaunay/delaunay.hpp"

namespace anitet::recovery_detail {

Status delaunay_of_surface_points(TetMesh& mesh, const SurfaceMesh& S, bool box) {
  const size_t n = S.num_vertices();
  std::vector<double> xyz(S.xyz.begin(), S.xyz.begin() + std::ptrdiff_t(3 * n));
  if (box && n > 0) {
    // Half the largest extent beyond S's bounding box on every side: far from S's points, near
    // enough that the corners' coordinates keep S's scale.
    const Box3 b = bounding_box(S.xyz.data(), n);
    double margin = 0;
    for (int d = 0; d < 3; ++d) margin = std::max(margin, 0.5 * (b.hi[d] - b.lo[d]));
    for (uint32_t c = 0; c < kBoxCorners; ++c)
      for (int d = 0; d < 3; ++d) xyz.push_back((c >> d) & 1u ? b.hi[d] + margin : b.lo[d] - margin);
  }
  Result<DelaunayStats> d = delaunay_tetrahedralize(mesh, xyz.data(), xyz.size() / 3);
  if (!d.ok()) return d.status();
  if (!d->duplicates.empty())
    return Status(Error::DuplicatePoint, "recover_boundary: input vertex " + std::to_string(d->duplicates[0].point) +
                                             " has the coordinates of vertex " +
                                             std::to_string(d->duplicates[0].same_as));
  return Status::success();
}

Status drop_box_corners(RecoveryOutput& out, size_t n_in) {
  TetMesh& mesh = out.mesh;
  const size_t first = n_in, last = n_in + kBoxCorners;  // [first, last) go
  if (mesh.num_vertices() < last) return Status(Error::InvalidMesh, "drop_box_corners: the mesh has no box corners");
  auto renumber = [&](uint32_t& v) {
    if (v >= last && v != TetMesh::kGhost && v != TetMesh::kNone) v -= kBoxCorners;
  };
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    for (int k = 0; k < 4; ++k) {
      uint32_t& v = mesh.tet_v[4 * size_t(t) + k];
      if (v >= first && v < last)
        return Status(Error::InvalidMesh, "drop_box_corners: a tet kept after carving has a box corner");
      renumber(v);
    }
  }
  mesh.xyz.erase(mesh.xyz.begin() + std::ptrdiff_t(3 * first), mesh.xyz.begin() + std::ptrdiff_t(3 * last));
  mesh.vflags.erase(mesh.vflags.begin() + std::ptrdiff_t(first), mesh.vflags.begin() + std::ptrdiff_t(last));
  for (SteinerPoint& s : out.steiner) renumber(s.vertex);
  for (uint32_t& v : out.s2_tri) renumber(v);
  return Status::success();
}

void keep_regions(TetMesh& mesh, const std::vector<int32_t>& comp, const std::vector<int32_t>& region) {
  const size_t nslots = mesh.num_tet_slots();
  for (uint32_t t = 0; t < nslots; ++t)
    if (!mesh.is_deleted(t) && region[comp[t]] >= 0) mesh.tet_region[t] = region[comp[t]];
  for (uint32_t t = 0; t < nslots; ++t) {
    if (mesh.is_deleted(t) || region[comp[t]] >= 0) continue;
    for (int i = 0; i < 4; ++i) {
      const uint32_t adj = mesh.tet_adj[4 * size_t(t) + i];
      if (adj == TetMesh::kNoNeighbour) continue;
      const auto n = static_cast<uint32_t>(adj >> 2);
      if (region[comp[n]] >= 0) mesh.tet_adj[adj] = TetMesh::kNoNeighbour;  // now a boundary facet
    }
    mesh.delete_tet(t);
  }
}

bool set_edge_constrained(TetMesh& mesh, const std::vector<uint32_t>& ball, uint32_t a, uint32_t b, bool on) {
  return set_edge_constrained(mesh, ball.data(), ball.size(), a, b, on);
}

bool set_edge_constrained(TetMesh& mesh, const uint32_t* tets, size_t n, uint32_t a, uint32_t b, bool on) {
  bool found = false;
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 6; ++k) {
      const uint32_t t = tets[i];
      const uint32_t x = mesh.vertex(t, kEdgeVertex[k][0]), y = mesh.vertex(t, kEdgeVertex[k][1]);
      if (!((x == a && y == b) || (x == b && y == a))) continue;
      found = true;
      mesh.set_edge_constrained(t, k, on);
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

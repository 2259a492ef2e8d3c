#include "pieces.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string>

#include "io/pvtu_format.hpp"

namespace anitet::mpi {

namespace {

std::string base_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// This rank's piece: its vertices with their final ids, its tets, the surface triangles on the
// facets of its tets.
Result<VtuPiece> piece_of(const distributed::RankMesh& rm, const distributed::GlobalIds& ids, const SurfaceMesh& surface,
                          int rank) {
  const TetMesh& m = rm.mesh;
  VtuPiece p;
  p.owner = rank;
  p.xyz = m.xyz;
  p.node_id.assign(ids.vertex.begin(), ids.vertex.end());
  // The surface's triangles by their sorted vertices.
  std::map<std::array<uint64_t, 3>, uint32_t> triangle;
  for (uint32_t b = 0; b < surface.num_triangles(); ++b) {
    std::array<uint64_t, 3> key = {surface.tri[3 * size_t(b)], surface.tri[3 * size_t(b) + 1],
                                   surface.tri[3 * size_t(b) + 2]};
    std::sort(key.begin(), key.end());
    triangle.emplace(key, b);
  }
  std::map<uint64_t, uint32_t> local;  // gid -> local vertex, for the surface's vertices
  for (uint32_t v = 0; v < m.num_vertices(); ++v)
    if (rm.gid[v] < surface.num_vertices()) local.emplace(rm.gid[v], v);
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (m.is_deleted(t) || m.is_ghost(t)) continue;
    p.tet.insert(p.tet.end(), &m.tet_v[4 * size_t(t)], &m.tet_v[4 * size_t(t)] + 4);
    p.region.push_back(m.tet_region[t]);
    p.tet_id.push_back(int64_t(ids.first_tet + p.tet_id.size()));
    for (int i = 0; i < 4; ++i) {
      if (m.tet_adj[4 * size_t(t) + size_t(i)] != TetMesh::kNoNeighbour) continue;
      std::array<uint64_t, 3> key;
      for (int k = 0; k < 3; ++k) key[size_t(k)] = rm.gid[m.vertex(t, kFacetVertex[i][k])];
      std::sort(key.begin(), key.end());
      const auto it = triangle.find(key);
      if (it == triangle.end()) continue;  // an interface facet
      for (int k = 0; k < 3; ++k) p.tri.push_back(local.at(surface.tri[3 * size_t(it->second) + size_t(k)]));
      p.patch.push_back(surface.patch.empty() ? 0 : surface.patch[it->second]);
    }
  }
  return p;
}

}  // namespace

Status write_pieces(const distributed::RankMesh& rm, const SurfaceMesh& surface, const std::string& output,
                    distributed::Comm& comm) {
  const std::string stem = output.substr(0, output.size() - 5);
  auto piece_path = [&](int r) { return stem + "_" + std::to_string(r) + ".vtu"; };
  Status st = Status::success();
  Result<distributed::GlobalIds> ids = distributed::number_globally(rm, comm);
  if (!ids.ok()) return ids.status();
  {
    Result<VtuPiece> piece = piece_of(rm, ids.value(), surface, comm.rank());
    st = piece.ok() ? write_vtu_piece(piece_path(comm.rank()), piece.value()) : piece.status();
  }
  if (st.ok() && comm.rank() == 0) {
    std::vector<std::string> names;
    for (int r = 0; r < comm.ranks(); ++r) names.push_back(base_name(piece_path(r)));
    st = write_pvtu_index(output, names);
  }
  Result<std::vector<double>> failed = comm.allreduce({st.ok() ? 0.0 : 1.0}, true);
  if (!failed.ok()) return failed.status();
  if (!st.ok()) return st;
  if (failed.value()[0] > 0) return Status(Error::Internal, "another rank failed to write its piece (see its message)");
  return Status::success();
}

}  // namespace anitet::mpi

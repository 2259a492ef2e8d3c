// A mesh written in pieces, one per rank, without gathering it: ParaView's parallel VTK XML
// format, a `.pvtu` index (PUnstructuredGrid) naming one `.vtu` piece per rank. A piece holds its
// rank's tets and the boundary triangles of their facets, the vertices they use (a vertex on an
// interface is in every piece that uses it) with their mesh-wide ids (point data GlobalNodeIds,
// the GlobalIds attribute), and per cell: region (-1 for triangles), patch (-1 for tets),
// GlobalCellIds (a tet's mesh-wide id; -1 for triangles) and owner (the rank). The arrays are
// binary, appended raw with UInt64 headers (read_vtu_piece reads any encoding). join_pieces makes
// one mesh of them again.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

struct VtuPiece {
  std::vector<double> xyz;          // 3 per vertex
  std::vector<int64_t> node_id;     // per vertex, mesh-wide
  std::vector<uint32_t> tet;        // 4 per tet, local vertex ids
  std::vector<int32_t> region;      // per tet
  std::vector<int64_t> tet_id;      // per tet, mesh-wide
  std::vector<uint32_t> tri;        // 3 per boundary triangle
  std::vector<int32_t> patch;       // per boundary triangle
  int32_t owner = 0;
};

Status write_vtu_piece(const std::string& path, const VtuPiece& piece);
// The index: `pieces` as written in the file (names relative to the index's directory).
Status write_pvtu_index(const std::string& path, const std::vector<std::string>& pieces);
// The pieces' paths (relative names resolved against the index's directory). Checks the index
// against what write_pvtu_index writes: PUnstructuredGrid, the P... declarations, the pieces.
Result<std::vector<std::string>> read_pvtu_index(const std::string& path);
// A piece with the arrays write_vtu_piece writes, in any encoding io/vtk_xml.hpp reads (Error::Parse
// when one is missing or holds values outside its type).
Result<VtuPiece> read_vtu_piece(const std::string& path);
// One mesh from the pieces: vertex v is GlobalNodeIds v (ids must be 0 .. V-1, every one used,
// one position per id), the tets in GlobalCellIds order, the boundary triangles in piece order.
// Fails when an id is missing or twice, or when a vertex has two positions.
Result<VolumeMesh> join_pieces(const std::vector<VtuPiece>& pieces);
// That the joined pieces fit: no facet of more than two tets, a facet of two tets is no boundary
// triangle, and (when the mesh has boundary triangles) a facet of one tet is one. InvalidMesh names
// the first facet that does not.
Status check_joined(const VolumeMesh& mesh);

}  // namespace anitet

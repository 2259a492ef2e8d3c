// Binary Medit files: the Gamma Mesh Format (GMF) of libMeshb, as refine, Feflo.a, Mmg and the
// UGAWG data write them: .meshb (meshes) and .solb (per-vertex solutions).
//
// Layout (every word in the file's byte order, told by its first int32: 1):
//   int32 1, int32 version, then keywords; each keyword is int32 code, the position of the next
//   keyword (0 for none), then its data: a line count, for solutions the field count and types,
//   then the lines.
//   version | reals   | integers (counts, indices, refs) | positions
//   1       | float32 | int32                            | int32
//   2       | float64 | int32                            | int32
//   3       | float64 | int32                            | int64
//   4       | float64 | int64                            | int64
//   The dimension, the solution field count and types are int32 in every version.
// Keywords read: Dimension (3; 3D only), Vertices (x y z ref), Edges (a b ref), Triangles
// (a b c ref), Quadrilaterals (a b c d ref), Tetrahedra (a b c d ref), SolAtVertices (fields of
// type 1 scalar, 2 vector, 3 symmetric tensor xx xy yy xz yz zz), End. Any other keyword is
// skipped by its next-keyword position (and listed in GmfFileInfo::skipped).
//
// Readers never crash on bad bytes: Error::Parse "name: byte offset N: expected ..." for malformed
// or truncated data, Error::BadIndex for an index that is not a vertex, Error::UnsupportedFormat
// for other dimensions or field types, Error::EmptyInput when the wanted keywords are missing.
// Writers write little-endian files whose keywords come in the order Dimension, Vertices, Edges,
// Triangles, Quadrilaterals, Tetrahedra (or SolAtVertices), End, as libMeshb writes them: a file
// holding only these keywords in this order, read and written again in the version read (and
// little-endian), gives the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/vertex_fields.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

// What a reader learnt about the file besides its data.
struct GmfFileInfo {
  int version = 0;               // 1 to 4
  bool big_endian = false;
  std::vector<int32_t> skipped;  // codes of the keywords skipped, in file order
};

// The keywords of a .meshb that anitet keeps, indices 0-based, refs as stored (the reader fills
// every ref array; for the writer an empty one means all 0).
struct GmfMesh {
  std::vector<double> xyz;  // 3 per vertex
  std::vector<int32_t> vertex_ref;
  std::vector<uint32_t> edge, tri, quad, tet;  // 2, 3, 4, 4 per element
  std::vector<int32_t> edge_ref, tri_ref, quad_ref, tet_ref;
};

// The GMF keyword codes anitet reads and writes (libMeshb's numbering).
namespace gmf {
constexpr int32_t kDimension = 3, kVertices = 4, kEdges = 5, kTriangles = 6, kQuadrilaterals = 7,
                  kTetrahedra = 8, kEnd = 54, kSolAtVertices = 62;
}  // namespace gmf

Result<GmfMesh> read_gmf_mesh(std::string_view data, const std::string& name, GmfFileInfo* info = nullptr);
// The file's bytes in `version` 1 to 4, or 0: the smallest of 2, 3 and 4 that can hold it
// (version 2 and 1 files stay below 2 GiB, version 3 counts and indices below 2^31).
// Error::InvalidArgument for inconsistent arrays, another version or data the version cannot
// hold; Error::BadIndex for an index that is not a vertex.
Result<std::string> to_gmf_mesh(const GmfMesh& mesh, int version = 0);

// A .meshb as a volume mesh (tets with their refs as regions, triangles as the boundary with
// their refs as patches; vertex refs and edges are dropped): Error::EmptyInput without tets.
Result<VolumeMesh> read_meshb_volume(std::string_view data, const std::string& name, GmfFileInfo* info = nullptr);
// A .meshb as a surface (triangles, quadrilaterals split in two): Error::EmptyInput without any.
Result<SurfaceMesh> read_meshb_surface(std::string_view data, const std::string& name,
                                       GmfFileInfo* info = nullptr);
// Vertices (ref 0), Triangles (bnd_patch), Tetrahedra (region, 0 when empty); the version as in
// to_gmf_mesh. The vertex metric is not part of a .meshb (write_sol writes it).
Result<std::string> to_meshb(const VolumeMesh& mesh, int version = 0);
// Vertices (ref 0) and Triangles (patch).
Result<std::string> to_meshb(const SurfaceMesh& mesh, int version = 0);

// The SolAtVertices of a .solb (Error::EmptyInput when it has none).
Result<VertexFields> read_solb(std::string_view data, const std::string& name, GmfFileInfo* info = nullptr);
// Dimension 3, SolAtVertices, End; the version as in to_gmf_mesh. Error::InvalidArgument for a
// field without kinds or values that are not a whole number of records.
Result<std::string> to_solb(const VertexFields& fields, int version = 0);

}  // namespace anitet

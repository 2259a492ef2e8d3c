// Reading and writing tetrahedral meshes (see surface_io.hpp for the readers' error rules).
// Indices in VolumeMesh are 0-based; region holds one label per tet, bnd_patch one per
// boundary triangle.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {

enum class VolumeFormat { Medit, Gmsh, TetGen, Vtu };

// From the extension, case-insensitive: .mesh .msh .node/.ele .vtu.
Result<VolumeFormat> volume_format_from_path(const std::string& path);

// Reads a file chosen by extension. For TetGen give the .node or the .ele path: base.node and
// base.ele are read, and base.face (boundary triangles with markers) when it exists.
// Error::EmptyInput when the file has no tetrahedron.
Result<VolumeMesh> read_volume_mesh(const std::string& path);

// Medit .mesh (ASCII): Vertices, Tetrahedra (ref = region), Triangles (ref = patch).
Result<VolumeMesh> read_medit_volume(std::string_view data, const std::string& name);
// Gmsh .msh 4.1 (ASCII or binary) or 2.2 (ASCII): tets (type 4) and triangles (type 2). The label
// is the entity's first physical tag when it has one, else the entity (elementary) tag.
Result<VolumeMesh> read_gmsh_volume(std::string_view data, const std::string& name);
// TetGen .node + .ele (+ optional .face, pass "" when absent); first index 0 or 1 as in the .node
// file. Region = the first tet attribute (0 when none), patch = the face marker.
Result<VolumeMesh> read_tetgen(std::string_view node, std::string_view ele, std::string_view face,
                               const std::string& name);
// VTK XML UnstructuredGrid with format="ascii" arrays (as to_vtu writes): tets (type 10) and
// triangles (type 5); cell data "region" and "patch" when present.
Result<VolumeMesh> read_vtu(std::string_view data, const std::string& name);

// One value per tet, written as VTU cell data (e.g. the quality tool's "quality").
struct TetScalar {
  std::string name;
  std::vector<double> values;
};

// Writes a file chosen by extension: .mesh (Medit), .msh (Gmsh 4.1), .vtu (VTK XML).
// `tet_scalars` are written by .vtu only. Error::InvalidArgument for inconsistent arrays.
Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path,
                         const std::vector<TetScalar>& tet_scalars = {});
// Writes mesh.vertex_metric as a Medit .sol: SolAtVertices of type 1 (1 value per vertex) or
// type 3 (6 values per vertex, Medit's order xx xy yy xz yz zz, the same as VolumeMesh's).
Status write_sol(const VolumeMesh& mesh, const std::string& path);

// The file contents.
// Medit: MeshVersionFormatted 2 (double precision), Triangles (patch refs), Tetrahedra (regions).
// Gmsh 4.1 ASCII: one volume entity per region and one surface entity per patch; entity tag =
//   physical tag = the label when all labels of that dimension are positive, else 1, 2, ... in
//   increasing label order.
// VTU: tets then boundary triangles as cells; cell data "region" (-1 on triangles), "patch" (-1
//   on tets) and each tet scalar (-1 on triangles: VTK's ASCII parser does not read "nan"); the
//   vertex metric, when present, as point data "size" (1 value) or "metric" (6 components).
Result<std::string> to_medit(const VolumeMesh& mesh);
Result<std::string> to_gmsh(const VolumeMesh& mesh);
Result<std::string> to_vtu(const VolumeMesh& mesh, const std::vector<TetScalar>& tet_scalars = {});
Result<std::string> to_sol(const VolumeMesh& mesh);

// Error::InvalidArgument unless the array sizes agree; Error::BadIndex for an index that is not
// a vertex. Writers run this first.
Status check_volume_arrays(const VolumeMesh& mesh);

}  // namespace anitet

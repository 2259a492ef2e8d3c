// Reading and writing tetrahedral meshes (see surface_io.hpp for the readers' error rules).
// Indices in VolumeMesh are 0-based; region holds one label per tet, bnd_patch one per
// boundary triangle.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "io/patch_names.hpp"

namespace anitet {

enum class VolumeFormat { Medit, MeditBinary, Gmsh, TetGen, Vtu, Su2, OpenFoam, Cgns, Exodus };

// From the extension, case-insensitive: .mesh .meshb .msh .node/.ele .vtu .su2 .cgns .exo/.e; a path
// whose last component is "polyMesh" (e.g. CASE/constant/polyMesh, a trailing '/' allowed) is an
// OpenFOAM polyMesh directory. Su2, OpenFoam, Cgns and Exodus are written only.
Result<VolumeFormat> volume_format_from_path(const std::string& path);
// Whether the format's writer writes VolumeMesh::prism and ::pyramid (prism and pyramid cells);
// the others refuse a mesh with either (Error::UnsupportedFormat). kPrismFormats names them for
// messages.
bool volume_format_writes_prisms(VolumeFormat f);
inline constexpr const char* kPrismFormats = ".vtu and .../polyMesh";
// Error::UnsupportedFormat unless the format of `path` can be written; Error::NotImplemented for
// .cgns or .exo/.e when anitet was built without CGNS or Exodus II, or its library cannot be
// opened.
Status check_writable_volume_path(const std::string& path);
// Whether this build has the CGNS / Exodus II writers (found by CMake at build time).
bool cgns_available();
bool exodus_available();
// Why the writer's library cannot be opened now (it is opened on first use): empty when it can.
std::string cgns_load_error();
std::string exodus_load_error();

// Reads a file chosen by extension. For TetGen give the .node or the .ele path: base.node and
// base.ele are read, and base.face (boundary triangles with markers) when it exists.
// Error::EmptyInput when the file has no tetrahedron.
Result<VolumeMesh> read_volume_mesh(const std::string& path);

// Medit .mesh (ASCII): Vertices, Tetrahedra (ref = region), Triangles (ref = patch).
Result<VolumeMesh> read_medit_volume(std::string_view data, const std::string& name);
// (Binary Medit .meshb: read_meshb_volume in gmf_format.hpp.)
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

// Writes a file chosen by volume_format_from_path, after check_boundary_elements (no file when it
// fails): .mesh (Medit), .meshb (binary Medit, GMF version 2, or 3 or 4 when the mesh needs them:
// see to_gmf_mesh), .msh (Gmsh 4.1), .vtu (VTK
// XML), .su2, an OpenFOAM polyMesh directory, .cgns, .exo/.e. `tet_scalars` are written by .vtu
// only. Error::InvalidArgument for inconsistent arrays. The boundary patches are named by
// `patch_names` (label -> name, see patch_names.hpp; unnamed labels get patch<label>) in every
// format that has names; Error::InvalidArgument for an invalid name, a named label that no
// boundary triangle has, or two labels with one name. Error::NotImplemented for .cgns or .exo
// when anitet was built without that library.
Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path,
                         const std::vector<TetScalar>& tet_scalars = {});
Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                         const std::vector<TetScalar>& tet_scalars = {});
// The same with the patches' kinds given (patch_names.hpp: the kind a name implies otherwise),
// for the formats that type their patches: OpenFOAM, CGNS, Exodus II.
Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                         const PatchTypes& patch_types, const std::vector<TetScalar>& tet_scalars = {});
// Writes mesh.vertex_metric as a Medit .sol (sol_io.hpp), or a binary .solb when the path ends
// in .solb (GMF version chosen as in to_gmf_mesh): SolAtVertices of type 1 (1 value per vertex)
// or type 3 (6 values per vertex, Medit's order xx xy yy xz yz zz, the same as VolumeMesh's).
Status write_sol(const VolumeMesh& mesh, const std::string& path);

// The file contents.
// Medit: MeshVersionFormatted 2 (double precision), Triangles (patch refs), Tetrahedra (regions);
//   the patch names as comment lines "# patch LABEL NAME" after the header (Medit has no names).
// Gmsh 4.1 ASCII: one volume entity per region and one surface entity per patch; entity tag =
//   physical tag = the label when all labels of that dimension are positive, else 1, 2, ... in
//   increasing label order; $PhysicalNames gives each surface its patch name and each volume
//   region<label>.
// VTU: tets then boundary triangles as cells; cell data "region" (-1 on triangles), "patch" (-1
//   on tets) and each tet scalar (-1 on triangles: VTK's ASCII parser does not read "nan"); the
//   vertex metric, when present, as point data "size" (1 value) or "metric" (6 components).
Result<std::string> to_medit(const VolumeMesh& mesh, const PatchNames& patch_names = {});
// The same text streamed to a file (write_file_with: PATH.part-PID, then renamed into place).
Status write_medit_volume(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names = {});
Result<std::string> to_gmsh(const VolumeMesh& mesh, const PatchNames& patch_names = {});
Result<std::string> to_vtu(const VolumeMesh& mesh, const std::vector<TetScalar>& tet_scalars = {});
Result<std::string> to_sol(const VolumeMesh& mesh);

// The solver formats (solver_formats.cpp, cgns_format.cpp, exodus_format.cpp). Each boundary
// patch is one named group, in increasing label order; a boundary triangle that is a face of
// exactly one tet is written oriented out of the mesh (right-hand normal), others as given.
// SU2 native (ASCII, 0-based): NDIME= 3, NELEM= tets (VTK type 10, element index appended),
//   NPOIN= points (index appended), NMARK= patches, each MARKER_TAG= name and MARKER_ELEMS= its
//   triangles (type 5). One zone: regions are not written.
Result<std::string> to_su2(const VolumeMesh& mesh, const PatchNames& patch_names = {});

// OpenFOAM polyMesh (ASCII, the layout of OpenFOAM's own writers): cells = tets in order, then
// prisms, then pyramids (their quads as quad faces, a boundary quad given by its two triangles); faces
// in OpenFOAM's order: internal faces first, in upper-triangular order (by owner, then
// neighbour; owner < neighbour), oriented from owner to neighbour; then the boundary faces patch
// by patch (increasing label), oriented out of the domain. Every boundary face of the tets must
// be a boundary triangle and no boundary triangle an internal face (Error::InvalidArgument
// otherwise). Patch type from the patch's kind (patch_names.hpp): wall, patch (inlet, outlet, farfield,
// patch) or symmetryPlane (symmetry when its faces are not coplanar). cellZones: one
// zone region<label> per region when mesh.region is not empty.
struct PolyMeshPatch {
  std::string name;
  std::string type;  // "wall", "patch", "symmetryPlane" or "symmetry"
  size_t start = 0, size = 0;
};
struct PolyMesh {
  std::vector<uint32_t> face;       // the faces' vertices one after another (3 per tet face)
  std::vector<uint8_t> face_size;   // 1 per face: 3, or 4 for a prism's or pyramid's quad
  std::vector<uint32_t> owner;      // 1 per face
  std::vector<uint32_t> neighbour;  // 1 per internal face
  std::vector<PolyMeshPatch> patches;
  std::vector<std::pair<std::string, std::vector<uint32_t>>> cell_zones;
  size_t num_internal_faces() const { return neighbour.size(); }
};
Result<PolyMesh> to_polymesh(const VolumeMesh& mesh, const PatchNames& patch_names = {},
                             const PatchTypes& patch_types = {});
// Writes DIR/points, faces, owner, neighbour, boundary (and cellZones, or removes a stale one),
// creating DIR and its parents. OpenFOAM's tools want DIR = CASE/constant/polyMesh and a
// CASE/system/controlDict, which this does not write.
Status write_openfoam(const VolumeMesh& mesh, const std::string& dir, const PatchNames& patch_names = {},
                      const PatchTypes& patch_types = {});

// CGNS (HDF5 through the CGNS mid-level library): base "Base" (3, 3), one unstructured zone
// "Zone1"; coordinates; section "GridElements" of TETRA_4 (elements 1..tets); one TRI_3 section
// per patch named after it (the following element ids); one boundary condition per patch with
// the same name, type from the patch's kind (BCWall, BCInflow, BCOutflow, BCFarfield,
// BCSymmetryPlane, BCGeneral), PointRange over
// its section's element ids, GridLocation FaceCenter. Error::NotImplemented when built without
// CGNS.
Status write_cgns(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names = {},
                  const PatchTypes& patch_types = {});

// Exodus II: one TETRA element block (4 nodes per element) per region (id = the label when all are positive, else
// 1, 2, ..., named region<label>), elements numbered block by block; one side set per patch
// (id by the same rule, named after the patch) listing element and Exodus side number (1 = nodes
// 1 2 4, 2 = 2 3 4, 3 = 1 4 3, 4 = 1 3 2). Every boundary triangle must be a face of a tet
// (Error::InvalidArgument otherwise). The patches' kinds (patch_names.hpp) as side-set properties
// named WALL, INLET, OUTLET, FARFIELD, SYMMETRY, PATCH (those present): 1 on the side sets of
// that kind, 0 on the others. Error::NotImplemented when built without Exodus II.
Status write_exodus(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names = {},
                    const PatchTypes& patch_types = {});

// Error::InvalidArgument unless the array sizes agree; Error::BadIndex for an index that is not
// a vertex. Writers run this first.
Status check_volume_arrays(const VolumeMesh& mesh);

// What write_volume_mesh checks before it writes anything, so that no file it writes puts a
// solver's boundary conditions on the wrong faces: check_volume_arrays; no face shared by more
// than two tets; every boundary triangle a face of the tets (an interface between two tets
// allowed) and no face given twice; with `cover`, every boundary face of the tets (a face of one
// tet) a boundary triangle. Error::InvalidMesh naming the first problem, 1-based as in the files.
// write_volume_mesh asks for `cover` when the mesh has boundary triangles, and always for the
// formats whose markers are a solver's boundary conditions (SU2, OpenFOAM, CGNS, Exodus II).
Status check_boundary_elements(const VolumeMesh& mesh, bool cover);
// The same on a tet mesh's arrays (4 vertex indices per tet, 3 per boundary triangle, every index
// below num_vertices: the caller checks that).
Status check_boundary_elements(const std::vector<uint32_t>& tet, size_t num_vertices, const std::vector<uint32_t>& bnd_tri,
                               bool cover);

}  // namespace anitet

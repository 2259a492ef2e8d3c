// Reading and writing triangulated surfaces.
//
// Every reader parses bytes held in memory (`data`), using `name` (usually the path) in messages,
// and never crashes on bad input: it returns Error::Parse naming the line (text) or byte offset
// (binary) and what was expected, Error::BadIndex naming the triangle for an index out of range,
// Error::EmptyInput when there is no triangle, Error::UnsupportedFormat for variants not handled.
// Polygons are fan-triangulated. Non-finite coordinates are read as they are (validation reports
// them). Indices in SurfaceMesh are 0-based.
#pragma once

#include <string>
#include <string_view>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "io/patch_names.hpp"

namespace anitet {

enum class SurfaceFormat { Off, Obj, Stl, Ply, Medit, MeditBinary, Gmsh, Su2, Vtu, TetGen };

// From the extension, case-insensitive: .off .obj .stl .ply .mesh .meshb .msh .su2 .vtu .node/.ele.
Result<SurfaceFormat> surface_format_from_path(const std::string& path);

// Reads a file, choosing the format from its extension. `names`, when given, receives the patch
// names the file carries for the labels its triangles have (SU2 markers, Gmsh physical names,
// anitet's "# patch" comments in Medit files, STL `solid` names; other formats: none); a name
// that is no valid patch name (patch_names.hpp) is Error::InvalidArgument, except in STL files,
// whose free-text names are made valid (read_stl). A volume mesh (.mesh, .msh, .vtu, .su2, TetGen .node/.ele)
// gives its surface: its boundary triangles with their patch labels, else (.mesh .msh .vtu
// .node/.ele without any) the boundary faces of its tets, outward, patch 0; every vertex of the
// file is kept in file order, so the tets' interior vertices are vertices of no triangle.
Result<SurfaceMesh> read_surface(const std::string& path, PatchNames* names = nullptr);
// The same from bytes (TetGen, which has two files, only from its path).
Result<SurfaceMesh> read_surface(std::string_view data, SurfaceFormat format,
                                 const std::string& name, PatchNames* names = nullptr);
// The surface of a volume mesh, as read_surface gives it.
Result<SurfaceMesh> surface_of_volume(const VolumeMesh& mesh);

// OFF (also COFF/NOFF/STOFF: extra per-vertex values are skipped); patches 0.
Result<SurfaceMesh> read_off(std::string_view data, const std::string& name);
// OBJ `v` and `f` (v, v/vt, v//vn, v/vt/vn, negative indices). Each distinct `g`/`o` name gets a
// patch label 1, 2, ... in order of first appearance; faces before any group get 0.
Result<SurfaceMesh> read_obj(std::string_view data, const std::string& name);
// STL ASCII or binary (detected by content, also when a binary header starts with "solid").
// Corners with bit-equal coordinates are merged into one vertex. Patches: 0, or, in an ASCII
// file whose triangles are in several `solid` blocks, 1, 2, ... per block in file order (blocks
// of the same name share one label). `names`, when given, then receives each label's `solid`
// name made a valid, unique patch name (patch_names_from_text: "wall 1" becomes "wall_1"); an
// unnamed block's label, a single patch, and binary files get none.
Result<SurfaceMesh> read_stl(std::string_view data, const std::string& name, PatchNames* names = nullptr);
// PLY ascii, binary_little_endian or binary_big_endian: `vertex` x y z and the `face` index list.
Result<SurfaceMesh> read_ply(std::string_view data, const std::string& name);
// Medit .mesh (ASCII): Vertices and Triangles (refs become patches; Quadrilaterals are split).
// anitet's writer puts the patch names in comment lines "# patch LABEL NAME".
Result<SurfaceMesh> read_medit_surface(std::string_view data, const std::string& name);
// (Binary Medit .meshb: read_meshb_surface in gmf_format.hpp, the same content.)
// The names in those comments (any label; unchecked lines are comments only).
PatchNames medit_patch_names(std::string_view data);
// Gmsh .msh 4.1 (ASCII or binary) or 2.2 (ASCII): triangles (type 2); patch = the first physical
// tag of the surface the triangle is on, else its entity (elementary) tag (the same rule as
// read_gmsh_volume).
Result<SurfaceMesh> read_gmsh_surface(std::string_view data, const std::string& name);
// The names of its physical groups of dimension 2 ($PhysicalNames), by physical tag, unchecked.
Result<PatchNames> gmsh_surface_names(std::string_view data, const std::string& name);

// SU2 native mesh: the triangles (and split quadrilaterals) of its boundary markers, marker i in
// file order as patch label i + 1, its MARKER_TAG in `names` (a tag that is no valid patch
// name, see patch_names.hpp, is an error when names are asked for). Volume elements are
// skipped; 2D and multi-zone files are UnsupportedFormat.
Result<SurfaceMesh> read_su2_surface(std::string_view data, const std::string& name, PatchNames* names = nullptr);

// Writes a file, choosing the format from its extension: .off .obj .stl (binary) .mesh .meshb.
Status write_surface(const SurfaceMesh& mesh, const std::string& path);

// The file contents. OBJ writes a group `patch<label>` for each patch run when some label is not 0.
// STL binary stores coordinates as float, so it is the one lossy format here.
Result<std::string> to_off(const SurfaceMesh& mesh);
Result<std::string> to_obj(const SurfaceMesh& mesh);
Result<std::string> to_stl_binary(const SurfaceMesh& mesh);
Result<std::string> to_medit(const SurfaceMesh& mesh);

// Error::InvalidArgument unless xyz, tri and patch sizes agree; Error::BadIndex for an index that
// is not a vertex. Writers run this first.
Status check_surface_arrays(const SurfaceMesh& mesh);

}  // namespace anitet

// Writers of the 2D mesher's meshes (every file written beside its name and renamed into place,
// io/file_bytes.hpp), by extension:
//  - .mesh: Medit, Dimension 2: Vertices (ref 1 for the input's points, 0 for the others), Edges
//    (the input segments' pieces, ref = the segment's label), Triangles (ref = the region's
//    attribute, rounded);
//  - .msh: Gmsh 4.1 ASCII, one curve entity per label and one surface entity per attribute
//    (physical names label<L> and region<A>), z = 0;
//  - .vtu: VTK XML, triangles and lines (cell data "region" and "label"), z = 0, with the
//    per-vertex metric when there is one;
//  - .14 or a name fort.14: ADCIRC's grid (see write_fort14).
// Coordinates in the shortest form that reads back to the same bits.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "mesh2d/mesher2.hpp"

namespace anitet::mesh2d {

// The kind of file a path names: "mesh", "msh", "vtu", "fort14", or "" when unknown.
std::string mesh2d_format(const std::string& path);

struct Fort14Options {
  std::string title = "anitet mesh2d";
  std::set<int32_t> open_labels;     // labels of the open (ocean) boundaries; others are land
  std::vector<double> depth;         // per vertex (empty: 0 everywhere)
  int mainland_type = 20;            // IBTYPE of land boundaries on the outer boundary
  int island_type = 21;              // IBTYPE of closed land boundaries around holes
};

// ADCIRC fort.14: title; NE NP; nodes "i x y depth"; elements "i 3 a b c"; then the open
// boundaries (NOPE, NETA, each "NVDLL 0" and its nodes) and the land boundaries (NBOU, NVEL, each
// "NVELL IBTYPE" and its nodes). Each boundary loop of the mesh (the domain on its left: outer
// loops counter-clockwise, islands clockwise) is cut into runs of open and of land edges; a run
// of open edges is an open boundary, a run of land edges a land boundary of mainland_type, and a
// loop of land edges only around a hole an island boundary of island_type, closed by repeating
// its first node (as is a loop of land edges around the whole domain). Boundaries on outer loops
// come first. Interface segments (the domain on both sides) are not boundaries.
Status write_fort14(const std::string& path, const TriMesh2& mesh, const Fort14Options& options);

// Writes by extension (.mesh .msh .vtu .14/fort.14); Error::UnsupportedFormat naming the
// extension otherwise.
Status write_mesh2d(const std::string& path, const TriMesh2& mesh, const Fort14Options& fort14 = {});

// The per-vertex metric as a Medit .sol (Dimension 2): sizes when every tensor is isotropic,
// else xx xy yy tensors.
Status write_sol2d(const std::string& path, const TriMesh2& mesh);

}  // namespace anitet::mesh2d

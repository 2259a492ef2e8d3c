// Face topology of a VolumeMesh for the writers that need it (OpenFOAM faces/owner/neighbour,
// Exodus side sets, outward boundary triangles for SU2 and CGNS).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "io/patch_names.hpp"

namespace anitet {

// (kOutwardFace, kPrismFace and kPyramidFace, the cells' outward faces, are in core/volume_mesh.hpp.)

struct MeshFaces {
  static constexpr int64_t kNone = -1;
  // Cell faces are numbered 4t+f for tet t's face f (kOutwardFace), then 4 nt + 5p + f for prism
  // p's face f (kPrismFace: three quads, then the two triangles), then 4 nt + 5 (np + y) + f for
  // pyramid y's face f (kPyramidFace: the quad, then four triangles). For each cell face: the cell
  // face on the other side, or kNone on the mesh boundary.
  std::vector<int64_t> across;
  // For each boundary triangle i: the cell face with the same three vertices, or a prism's or
  // pyramid's quad whose diagonal split it is half of; kNone when there is none. When two cells share it
  // (an internal face) the one with the smaller number.
  std::vector<int64_t> bnd_face;
  // For each boundary triangle: true when the face it matched has a cell on both sides.
  std::vector<bool> bnd_internal;
};

// Error::InvalidMesh, naming the vertices, when three or more cell faces share their vertices.
Result<MeshFaces> build_mesh_faces(const VolumeMesh& mesh);

// The cell of cell face `face` (tets 0..nt-1, then prisms nt + p, then pyramids nt + np + y) and
// its vertices, outward from that cell; returns their count (3 or 4).
size_t cell_of_face(const VolumeMesh& mesh, int64_t face);
int face_vertices(const VolumeMesh& mesh, int64_t face, uint32_t out[4]);

// The boundary elements of the boundary triangles `tris` (e.g. a patch's), in that order: each
// triangle oriented as outward_triangle does, but the two triangles of a prism's or pyramid's quad
// as that quad, once (at the first of the two), outward from the cell.
struct BoundaryElements {
  std::vector<uint32_t> vertices;  // 3 or 4 per element
  std::vector<uint8_t> size;       // per element: 3 or 4
};
BoundaryElements boundary_elements(const VolumeMesh& mesh, const MeshFaces& faces, const std::vector<uint32_t>& tris);

// Boundary triangle b, oriented out of the mesh when it is a face of exactly one tet (the tet's
// outward face), else as given.
std::array<uint32_t, 3> outward_triangle(const VolumeMesh& mesh, const MeshFaces& faces, size_t b);

// The boundary triangles of each patch (named_patches(): checked names, increasing label), each
// patch's triangles in mesh order.
struct PatchTriangles {
  NamedPatch patch;
  std::vector<uint32_t> tris;
};
Result<std::vector<PatchTriangles>> patch_triangles(const VolumeMesh& mesh, const PatchNames& names,
                                                    const PatchTypes& types = {});

}  // namespace anitet

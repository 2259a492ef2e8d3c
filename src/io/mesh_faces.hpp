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

// Local face f of a positively oriented tet (v0 v1 v2 v3), listed so that its right-hand normal
// points OUT of the tet. The order is Exodus II's side numbering for TETRA (side f + 1):
// side 1 = nodes 1 2 4, side 2 = 2 3 4, side 3 = 1 4 3, side 4 = 1 3 2.
inline constexpr int kOutwardFace[4][3] = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};

struct MeshFaces {
  static constexpr int64_t kNone = -1;
  // For each tet face 4t+f: the tet face 4u+g on the other side, or kNone on the mesh boundary.
  std::vector<int64_t> across;
  // For each boundary triangle i: the tet face 4t+f with the same three vertices, kNone when no
  // tet has it. When two tets share it (an internal face) the one with the smaller t.
  std::vector<int64_t> bnd_face;
  // For each boundary triangle: true when the face it matched has a tet on both sides.
  std::vector<bool> bnd_internal;
};

// Error::InvalidMesh, naming the vertices, when three or more tet faces share three vertices.
Result<MeshFaces> build_mesh_faces(const VolumeMesh& mesh);

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

// A finished tetrahedral mesh as written to or read from files: compact flat arrays, 0-based.
// (The working structure that meshing stages edit is TetMesh, in tet_mesh.hpp.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

// Local face f of a positively oriented tet (v0 v1 v2 v3), listed so that its right-hand normal
// points OUT of the tet. The order is Exodus II's side numbering for TETRA (side f + 1):
// side 1 = nodes 1 2 4, side 2 = 2 3 4, side 3 = 1 4 3, side 4 = 1 3 2.
inline constexpr int kOutwardFace[4][3] = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};
// The same for a prism (VolumeMesh::prism's order): three quads, then the two triangles (-1
// pads them), in Exodus II's side numbering for WEDGE (side f + 1).
inline constexpr int kPrismFaceSize[5] = {4, 4, 4, 3, 3};
inline constexpr int kPrismFace[5][4] = {{0, 1, 4, 3}, {1, 2, 5, 4}, {0, 3, 5, 2}, {0, 2, 1, -1}, {3, 4, 5, -1}};
// The same for a pyramid (VolumeMesh::pyramid's order): the quad base, then the four triangles,
// each with the base edge it stands on (Exodus II's PYRAMID numbers the triangles first).
inline constexpr int kPyramidFaceSize[5] = {4, 3, 3, 3, 3};
inline constexpr int kPyramidFace[5][4] = {{0, 3, 2, 1}, {0, 1, 4, -1}, {1, 2, 4, -1}, {2, 3, 4, -1}, {3, 0, 4, -1}};

struct VolumeMesh {
  std::vector<double> xyz;            // 3 per vertex
  std::vector<uint32_t> tet;          // 4 per tet, positively oriented (orient3d > 0)
  std::vector<int32_t> region;        // 1 per tet (may be empty: all region 0)
  std::vector<uint32_t> bnd_tri;      // 3 per boundary triangle (may be empty)
  std::vector<int32_t> bnd_patch;     // 1 per boundary triangle
  std::vector<double> vertex_metric;  // empty, 1 (size h) or 6 (xx xy yy xz yz zz) per vertex
  // Prism cells beside the tets (boundary-layer prisms, merge_bl_prisms in bl_prisms.hpp; empty
  // for a tet mesh): 6 per prism, the triangle 0 1 2 and its copy 3 4 5 (edges 0-3, 1-4, 2-5), in
  // Gmsh/CGNS/Exodus order: 0 1 2 counter-clockwise seen from 3 4 5, so the tet 0 1 2 3 is
  // positive (VTK's wedge is 0 2 1 3 5 4). A prism's quad side on the boundary is two boundary
  // triangles of one patch split along one diagonal.
  std::vector<uint32_t> prism;
  std::vector<int32_t> prism_region;  // 1 per prism (empty when region is)
  // Pyramid cells (where a boundary-layer column stopped in its layer, beside the prisms; empty
  // for a tet mesh): 5 per pyramid, the quad base 0 1 2 3 and the apex 4, in VTK/Gmsh/CGNS order:
  // 0 1 2 3 counter-clockwise seen from the apex, so the tet 0 1 2 4 is positive. Its quad may be
  // warped (it is a prism's quad side too).
  std::vector<uint32_t> pyramid;
  std::vector<int32_t> pyramid_region;  // 1 per pyramid (empty when region is)

  size_t num_vertices() const { return xyz.size() / 3; }
  size_t num_tets() const { return tet.size() / 4; }
  size_t num_prisms() const { return prism.size() / 6; }
  size_t num_pyramids() const { return pyramid.size() / 5; }
  // Whether the mesh has cells other than tets (prisms or pyramids).
  bool has_mixed_cells() const { return !prism.empty() || !pyramid.empty(); }
  size_t num_boundary_triangles() const { return bnd_tri.size() / 3; }
  const double* point(size_t v) const { return &xyz[3 * v]; }
};

}  // namespace anitet

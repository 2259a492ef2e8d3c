// A finished tetrahedral mesh as written to or read from files: compact flat arrays, 0-based.
// (The working structure that meshing stages edit is TetMesh, in tet_mesh.hpp.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

struct VolumeMesh {
  std::vector<double> xyz;            // 3 per vertex
  std::vector<uint32_t> tet;          // 4 per tet, positively oriented (orient3d > 0)
  std::vector<int32_t> region;        // 1 per tet (may be empty: all region 0)
  std::vector<uint32_t> bnd_tri;      // 3 per boundary triangle (may be empty)
  std::vector<int32_t> bnd_patch;     // 1 per boundary triangle
  std::vector<double> vertex_metric;  // empty, 1 (size h) or 6 (xx xy yy xz yz zz) per vertex

  size_t num_vertices() const { return xyz.size() / 3; }
  size_t num_tets() const { return tet.size() / 4; }
  size_t num_boundary_triangles() const { return bnd_tri.size() / 3; }
  const double* point(size_t v) const { return &xyz[3 * v]; }
};

}  // namespace anitet

// A triangulated surface as read from a file: flat arrays, 0-based indices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace anitet {

struct SurfaceMesh {
  std::vector<double> xyz;      // 3 per vertex
  std::vector<uint32_t> tri;    // 3 per triangle, counter-clockwise seen from outside the domain
  std::vector<int32_t> patch;   // 1 per triangle: the input's surface/patch label (0 when none)
  // The line of its file each triangle was read from (text formats: OFF, OBJ, ASCII STL, Medit),
  // for messages that point into the file; empty when unknown.
  std::vector<uint32_t> line;

  size_t num_vertices() const { return xyz.size() / 3; }
  size_t num_triangles() const { return tri.size() / 3; }
  const double* point(size_t v) const { return &xyz[3 * v]; }

  void add_vertex(double x, double y, double z) {
    xyz.push_back(x);
    xyz.push_back(y);
    xyz.push_back(z);
  }
  void add_triangle(uint32_t a, uint32_t b, uint32_t c, int32_t label = 0) {
    tri.push_back(a);
    tri.push_back(b);
    tri.push_back(c);
    patch.push_back(label);
  }
};

}  // namespace anitet

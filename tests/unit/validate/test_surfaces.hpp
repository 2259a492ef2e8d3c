// Small surfaces built in code for the validation tests.
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/surface_mesh.hpp"

namespace anitet::test {

// Appends the box [lo, hi] (12 triangles, facing outward unless `inward`) with its own 8
// vertices. Returns the id of its first triangle.
inline uint32_t add_box(SurfaceMesh& s, const double lo[3], const double hi[3],
                        bool inward = false) {
  const auto base = static_cast<uint32_t>(s.num_vertices());
  for (uint32_t i = 0; i < 8; ++i) {
    s.add_vertex((i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]);
  }
  // Quads counter-clockwise seen from outside; vertex i = x + 2y + 4z.
  const uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  const auto first = static_cast<uint32_t>(s.num_triangles());
  for (const auto& q : quads) {
    if (inward) {
      s.add_triangle(base + q[0], base + q[2], base + q[1]);
      s.add_triangle(base + q[0], base + q[3], base + q[2]);
    } else {
      s.add_triangle(base + q[0], base + q[1], base + q[2]);
      s.add_triangle(base + q[0], base + q[2], base + q[3]);
    }
  }
  return first;
}

inline uint32_t add_cube(SurfaceMesh& s, double x, double y, double z, double size,
                         bool inward = false) {
  const double lo[3] = {x, y, z}, hi[3] = {x + size, y + size, z + size};
  return add_box(s, lo, hi, inward);
}

inline SurfaceMesh cube(double size = 1.0) {
  SurfaceMesh s;
  add_cube(s, 0, 0, 0, size);
  return s;
}

// A closed tetrahedron facing outward.
inline void add_tet(SurfaceMesh& s, const double a[3], const double b[3], const double c[3],
                    const double d[3]) {
  const auto base = static_cast<uint32_t>(s.num_vertices());
  for (const double* p : {a, b, c, d}) s.add_vertex(p[0], p[1], p[2]);
  // Outward when orient3d(a, b, c, d) > 0, i.e. d above abc: abc must face away from d.
  s.add_triangle(base + 0, base + 2, base + 1);
  s.add_triangle(base + 0, base + 1, base + 3);
  s.add_triangle(base + 1, base + 2, base + 3);
  s.add_triangle(base + 2, base + 0, base + 3);
}

// A triangular bipyramid: equator e0 e1 e2, apexes top (above) and bottom (below when given
// as such), outward when top is above the counter-clockwise equator.
inline SurfaceMesh bipyramid(const double top[3], const double bottom[3]) {
  SurfaceMesh s;
  s.add_vertex(0, 0, 0);
  s.add_vertex(4, 0, 0);
  s.add_vertex(0, 4, 0);
  s.add_vertex(top[0], top[1], top[2]);
  s.add_vertex(bottom[0], bottom[1], bottom[2]);
  for (uint32_t i = 0; i < 3; ++i) {
    const uint32_t j = (i + 1) % 3;
    s.add_triangle(i, j, 3);
    s.add_triangle(j, i, 4);
  }
  return s;
}

// Unit sphere: an octahedron subdivided `levels` times, vertices pushed to the sphere, outward.
inline SurfaceMesh sphere(int levels, double radius = 1.0, double cx = 0, double cy = 0,
                          double cz = 0) {
  std::vector<double> p = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  std::vector<uint32_t> t = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4,
                             2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    const auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const auto id = static_cast<uint32_t>(p.size() / 3);
      for (int k = 0; k < 3; ++k) p.push_back(0.5 * (p[3 * a + k] + p[3 * b + k]));
      mid[key] = id;
      return id;
    };
    std::vector<uint32_t> next;
    for (size_t i = 0; i < t.size(); i += 3) {
      const uint32_t a = t[i], b = t[i + 1], c = t[i + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    t = std::move(next);
  }
  SurfaceMesh s;
  for (size_t v = 0; v < p.size() / 3; ++v) {
    const double n = std::sqrt(p[3 * v] * p[3 * v] + p[3 * v + 1] * p[3 * v + 1] +
                               p[3 * v + 2] * p[3 * v + 2]);
    s.add_vertex(cx + radius * p[3 * v] / n, cy + radius * p[3 * v + 1] / n,
                 cz + radius * p[3 * v + 2] / n);
  }
  for (size_t i = 0; i < t.size(); i += 3) s.add_triangle(t[i], t[i + 1], t[i + 2]);
  return s;
}

// A closed "height-field box": the top is the grid xs x ys at heights top_z (row-major, x
// fastest), the bottom is the ring of the grid at height bottom_z plus one centre vertex
// (bottom_centre, at bottom_z), and vertical walls join the two rings. Outward when the top
// stays above the bottom.
inline SurfaceMesh heightfield_box(const std::vector<double>& xs, const std::vector<double>& ys,
                                   const std::vector<double>& top_z, double bottom_z,
                                   const double bottom_centre[2]) {
  SurfaceMesh s;
  const size_t nx = xs.size(), ny = ys.size();
  for (size_t j = 0; j < ny; ++j) {
    for (size_t i = 0; i < nx; ++i) s.add_vertex(xs[i], ys[j], top_z[j * nx + i]);
  }
  const auto top = [&](size_t i, size_t j) { return static_cast<uint32_t>(j * nx + i); };
  for (size_t j = 0; j + 1 < ny; ++j) {
    for (size_t i = 0; i + 1 < nx; ++i) {
      s.add_triangle(top(i, j), top(i + 1, j), top(i + 1, j + 1));
      s.add_triangle(top(i, j), top(i + 1, j + 1), top(i, j + 1));
    }
  }
  // The ring counter-clockwise seen from above.
  std::vector<uint32_t> ring;
  for (size_t i = 0; i + 1 < nx; ++i) ring.push_back(top(i, 0));
  for (size_t j = 0; j + 1 < ny; ++j) ring.push_back(top(nx - 1, j));
  for (size_t i = nx - 1; i > 0; --i) ring.push_back(top(i, ny - 1));
  for (size_t j = ny - 1; j > 0; --j) ring.push_back(top(0, j));
  const auto base = static_cast<uint32_t>(s.num_vertices());
  for (uint32_t v : ring) s.add_vertex(s.xyz[3 * v], s.xyz[3 * v + 1], bottom_z);
  const auto centre = static_cast<uint32_t>(s.num_vertices());
  s.add_vertex(bottom_centre[0], bottom_centre[1], bottom_z);
  const auto n = static_cast<uint32_t>(ring.size());
  for (uint32_t k = 0; k < n; ++k) {
    const uint32_t k1 = (k + 1) % n;
    // Wall quad: top ring k, k1 and their copies below; faces outward.
    s.add_triangle(ring[k], base + k, base + k1);
    s.add_triangle(ring[k], base + k1, ring[k1]);
    s.add_triangle(centre, base + k1, base + k);  // bottom faces down
  }
  return s;
}

}  // namespace anitet::test

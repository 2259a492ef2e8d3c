// Small meshes built in code for the quality tests.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <vector>

#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"

namespace anitet::test {

inline double orient_value(const VolumeMesh& m, const uint32_t* v) {
  const double* a = m.point(v[0]);
  double e[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) e[i][k] = m.point(v[i + 1])[k] - a[k];
  return e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
         e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
}

// Appends tet (a, b, c, d), swapping two vertices if needed so it is positive.
inline void add_positive_tet(VolumeMesh& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  uint32_t v[4] = {a, b, c, d};
  if (orient_value(m, v) < 0) std::swap(v[0], v[1]);
  m.tet.insert(m.tet.end(), v, v + 4);
}

// The n x n x n grid of unit cubes [0, n]^3 scaled by h, each cut into 6 tets around its main
// diagonal (Kuhn): conforming across cubes.
inline VolumeMesh kuhn_grid(int n, double h = 1.0) {
  VolumeMesh m;
  auto id = [n](int x, int y, int z) { return uint32_t(x + (n + 1) * (y + (n + 1) * z)); };
  for (int z = 0; z <= n; ++z)
    for (int y = 0; y <= n; ++y)
      for (int x = 0; x <= n; ++x) {
        m.xyz.push_back(h * x);
        m.xyz.push_back(h * y);
        m.xyz.push_back(h * z);
      }
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (const auto& p : perms) {
          int c[3] = {x, y, z};
          uint32_t v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int k = 0; k < 3; ++k) {
            ++c[p[k]];
            v[k + 1] = id(c[0], c[1], c[2]);
          }
          add_positive_tet(m, v[0], v[1], v[2], v[3]);
        }
  return m;
}

// The boundary faces of a tet mesh, oriented outward, as a surface on the mesh's vertices
// (a brute-force count, independent of the library's face matching).
inline SurfaceMesh boundary_surface(const VolumeMesh& m) {
  std::map<std::array<uint32_t, 3>, std::vector<std::array<uint32_t, 3>>> faces;
  // Facet i opposite vertex i, wound to point out of a positive tet.
  const int out[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  for (size_t t = 0; t < m.num_tets(); ++t) {
    for (const auto& f : out) {
      std::array<uint32_t, 3> tri{m.tet[4 * t + f[0]], m.tet[4 * t + f[1]], m.tet[4 * t + f[2]]};
      auto key = tri;
      std::sort(key.begin(), key.end());
      faces[key].push_back(tri);
    }
  }
  SurfaceMesh s;
  s.xyz = m.xyz;
  for (const auto& [key, list] : faces) {
    if (list.size() == 1) s.add_triangle(list[0][0], list[0][1], list[0][2]);
  }
  return s;
}

// Splits edge (a, b) at point p: every tet holding both becomes two. Returns p's id.
inline uint32_t split_edge(VolumeMesh& m, uint32_t a, uint32_t b, const double p[3]) {
  const uint32_t pid = uint32_t(m.num_vertices());
  m.xyz.insert(m.xyz.end(), p, p + 3);
  const size_t nt = m.num_tets();
  for (size_t t = 0; t < nt; ++t) {
    uint32_t* v = &m.tet[4 * t];
    const auto ia = std::find(v, v + 4, a) - v, ib = std::find(v, v + 4, b) - v;
    if (ia == 4 || ib == 4) continue;
    std::array<uint32_t, 4> second{v[0], v[1], v[2], v[3]};
    second[size_t(ib)] = pid;
    v[ia] = pid;
    m.tet.insert(m.tet.end(), second.begin(), second.end());
  }
  return pid;
}

}  // namespace anitet::test

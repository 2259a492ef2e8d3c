// Closed surfaces built in code for the stage 1 tests: grid-triangulated boxes (cubes, thin slabs,
// nested cavities) and subdivided icosahedra. All oriented with normals pointing out of the
// material (a cavity's box faces into the cavity).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/bvh.hpp"
#include "core/surface_mesh.hpp"

namespace anitet::test {

// Appends the box [lo, hi] with n[k] grid cells along axis k on its faces (2 triangles per cell,
// diagonals alternating), facing out of the box, or into it when `inward` (a cavity).
inline void add_grid_box(SurfaceMesh& s, const double lo[3], const double hi[3], const int n[3],
                         bool inward = false) {
  std::map<std::array<int, 3>, uint32_t> ids;
  auto vertex = [&](std::array<int, 3> g) {
    auto it = ids.find(g);
    if (it != ids.end()) return it->second;
    const auto id = static_cast<uint32_t>(s.num_vertices());
    s.add_vertex(lo[0] + (hi[0] - lo[0]) * g[0] / n[0], lo[1] + (hi[1] - lo[1]) * g[1] / n[1],
                 lo[2] + (hi[2] - lo[2]) * g[2] / n[2]);
    ids.emplace(g, id);
    return id;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      // (u, v) spans the face with u x v pointing out of the box.
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      const int u = side ? b : c, v = side ? c : b;
      for (int i = 0; i < n[u]; ++i) {
        for (int j = 0; j < n[v]; ++j) {
          std::array<int, 3> g00{}, g10{}, g11{}, g01{};
          for (auto* g : {&g00, &g10, &g11, &g01}) (*g)[axis] = side ? n[axis] : 0;
          g00[u] = i, g00[v] = j;
          g10[u] = i + 1, g10[v] = j;
          g11[u] = i + 1, g11[v] = j + 1;
          g01[u] = i, g01[v] = j + 1;
          uint32_t q[4] = {vertex(g00), vertex(g10), vertex(g11), vertex(g01)};
          if ((i + j) % 2) {
            const uint32_t r[4] = {q[1], q[2], q[3], q[0]};
            std::copy(r, r + 4, q);
          }
          if (inward) {
            s.add_triangle(q[0], q[2], q[1]);
            s.add_triangle(q[0], q[3], q[2]);
          } else {
            s.add_triangle(q[0], q[1], q[2]);
            s.add_triangle(q[0], q[2], q[3]);
          }
        }
      }
    }
  }
}

inline SurfaceMesh grid_box(const double lo[3], const double hi[3], const int n[3]) {
  SurfaceMesh s;
  add_grid_box(s, lo, hi, n);
  return s;
}

// The unit cube with its 12 triangles only (large triangles: pushes collide across the cube).
inline SurfaceMesh coarse_cube() {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const int n[3] = {1, 1, 1};
  return grid_box(lo, hi, n);
}

inline SurfaceMesh grid_cube(int cells) {
  const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  const int n[3] = {cells, cells, cells};
  return grid_box(lo, hi, n);
}

// A slab much thinner than its triangles are wide.
inline SurfaceMesh thin_slab() {
  const double lo[3] = {0, 0, 0}, hi[3] = {4, 4, 0.1};
  const int n[3] = {12, 12, 1};
  return grid_box(lo, hi, n);
}

// A cube [0, 3]^3 with a cubic cavity [1, 2]^3.
inline SurfaceMesh nested_cubes() {
  SurfaceMesh s;
  const double lo[3] = {0, 0, 0}, hi[3] = {3, 3, 3};
  const int n[3] = {6, 6, 6};
  add_grid_box(s, lo, hi, n);
  const double ilo[3] = {1, 1, 1}, ihi[3] = {2, 2, 2};
  const int m[3] = {3, 3, 3};
  add_grid_box(s, ilo, ihi, m, /*inward=*/true);
  return s;
}

// An icosahedron subdivided `levels` times, projected on the sphere of the given radius.
inline SurfaceMesh icosphere(int levels, double radius = 1.0) {
  SurfaceMesh s;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                           {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                           {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<double, 3>> pts;
  for (const auto& p : v) {
    const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    pts.push_back({p[0] / len, p[1] / len, p[2] / len});
  }
  std::vector<std::array<uint32_t, 3>> tris = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      std::array<double, 3> p;
      for (int k = 0; k < 3; ++k) p[k] = 0.5 * (pts[a][k] + pts[b][k]);
      const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      for (double& x : p) x /= len;
      pts.push_back(p);
      const auto id = static_cast<uint32_t>(pts.size() - 1);
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& tr : tris) {
      const uint32_t a = midpoint(tr[0], tr[1]), b = midpoint(tr[1], tr[2]),
                     c = midpoint(tr[2], tr[0]);
      next.push_back({tr[0], a, c});
      next.push_back({tr[1], b, a});
      next.push_back({tr[2], c, b});
      next.push_back({a, b, c});
    }
    tris = std::move(next);
  }
  for (const auto& p : pts) s.add_vertex(radius * p[0], radius * p[1], radius * p[2]);
  for (const auto& tr : tris) s.add_triangle(tr[0], tr[1], tr[2]);
  return s;
}

// Patch labels of body_in_box().
constexpr int32_t kBodyWall = 1, kBoxFarfield = 2;

// The body as a hole (its triangles reversed: normals into the body, out of the fluid) labelled
// kBodyWall, inside the box [c - half, c + half] (`cells` grid cells per edge) labelled
// kBoxFarfield: a boundary-layer case.
inline SurfaceMesh body_in_box(const SurfaceMesh& body, const double center[3], double half, int cells) {
  SurfaceMesh s;
  const double lo[3] = {center[0] - half, center[1] - half, center[2] - half};
  const double hi[3] = {center[0] + half, center[1] + half, center[2] + half};
  const int n[3] = {cells, cells, cells};
  add_grid_box(s, lo, hi, n);
  s.patch.assign(s.num_triangles(), kBoxFarfield);
  const auto offset = static_cast<uint32_t>(s.num_vertices());
  s.xyz.insert(s.xyz.end(), body.xyz.begin(), body.xyz.end());
  for (size_t t = 0; t < body.num_triangles(); ++t)
    s.add_triangle(offset + body.tri[3 * t], offset + body.tri[3 * t + 2], offset + body.tri[3 * t + 1], kBodyWall);
  return s;
}

// body_in_box() with a box 10x the body's size (its bounding box's largest extent, set in `size`)
// around the bounding box's centre, 3 cells per edge: issue 5's farfield case.
inline SurfaceMesh in_farfield_box(const SurfaceMesh& body, double& size) {
  const Box3 b = bounding_box(body.xyz.data(), body.num_vertices());
  size = std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
  const double center[3] = {0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2])};
  return body_in_box(body, center, 5.0 * size, 3);
}

}  // namespace anitet::test

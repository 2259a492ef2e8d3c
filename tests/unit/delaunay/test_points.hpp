// Point sets and brute-force oracles shared by the Delaunay tests.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/tet_mesh.hpp"
#include "predicates/predicates.hpp"

namespace anitet::test {

// Smaller workloads under AddressSanitizer, which is ~10x slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr size_t kScale = 10;
#else
constexpr size_t kScale = 1;
#endif

inline std::vector<double> random_cube(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> xyz(3 * n);
  for (double& c : xyz) c = u(rng);
  return xyz;
}

// Points on the unit sphere (rounded: nearly, not exactly, cospherical).
inline std::vector<double> random_sphere(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> xyz;
  xyz.reserve(3 * n);
  while (xyz.size() < 3 * n) {
    double p[3] = {g(rng), g(rng), g(rng)};
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (r < 1e-3) continue;
    for (double c : p) xyz.push_back(c / r);
  }
  return xyz;
}

// The k^3 integer grid: every cube's eight corners are cospherical, every face coplanar.
inline std::vector<double> grid(int k, double spacing = 1.0) {
  std::vector<double> xyz;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        xyz.push_back(spacing * i);
        xyz.push_back(spacing * j);
        xyz.push_back(spacing * l);
      }
  return xyz;
}

// Random points on `planes` parallel planes z = 0, 1, ..., with coordinates on a coarse lattice so
// that many are cocircular and collinear too.
inline std::vector<double> points_on_planes(size_t n, int planes, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> lattice(0, 40);
  std::uniform_int_distribution<int> plane(0, planes - 1);
  std::vector<double> xyz;
  for (size_t i = 0; i < n; ++i) {
    xyz.push_back(lattice(rng) / 8.0);
    xyz.push_back(lattice(rng) / 8.0);
    xyz.push_back(plane(rng));
  }
  return xyz;
}

inline double tet_volume6(const double* a, const double* b, const double* c, const double* d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[1] * v[2] - u[2] * v[1]) * w[0] + (u[2] * v[0] - u[0] * v[2]) * w[1] +
         (u[0] * v[1] - u[1] * v[0]) * w[2];
}

// Hull triangles of points in general position, by brute force: triples with every other point
// strictly on one side, oriented with the outward normal. O(n^4): small inputs only.
inline std::vector<std::array<uint32_t, 3>> brute_force_hull(const std::vector<double>& xyz) {
  const auto n = static_cast<uint32_t>(xyz.size() / 3);
  auto p = [&](uint32_t i) { return &xyz[3 * size_t(i)]; };
  std::vector<std::array<uint32_t, 3>> hull;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j)
      for (uint32_t k = j + 1; k < n; ++k) {
        int pos = 0, neg = 0;
        for (uint32_t q = 0; q < n; ++q) {
          if (q == i || q == j || q == k) continue;
          const int s = predicates::orient3d(p(i), p(j), p(k), p(q));
          pos += s > 0;
          neg += s < 0;
        }
        if (pos == 0) hull.push_back({i, j, k});  // others below: (i j k) faces out
        else if (neg == 0) hull.push_back({i, k, j});
      }
  return hull;
}

// Hull triangles as closed by the ghost tets, oriented outward (facet 3 of a ghost).
inline std::vector<std::array<uint32_t, 3>> ghost_hull(const TetMesh& m) {
  std::vector<std::array<uint32_t, 3>> hull;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (!m.is_deleted(t) && m.is_ghost(t)) hull.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2)});
  return hull;
}

// A triangle with its smallest index first (same cyclic order): comparable between lists.
inline std::array<uint32_t, 3> canonical(std::array<uint32_t, 3> f) {
  while (f[0] > f[1] || f[0] > f[2]) f = {f[1], f[2], f[0]};
  return f;
}

// Sum over the live non-ghost tets of 6 x volume.
inline double mesh_volume6(const TetMesh& m) {
  double sum = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t)
    if (!m.is_deleted(t) && !m.is_ghost(t))
      sum += tet_volume6(m.point(m.vertex(t, 0)), m.point(m.vertex(t, 1)), m.point(m.vertex(t, 2)),
                         m.point(m.vertex(t, 3)));
  return sum;
}

// 6 x the volume enclosed by outward hull triangles (divergence theorem about point o).
inline double hull_volume6(const std::vector<double>& xyz, const std::vector<std::array<uint32_t, 3>>& hull) {
  const double* o = xyz.data();
  double sum = 0;
  for (const auto& f : hull)
    sum -= tet_volume6(&xyz[3 * size_t(f[0])], &xyz[3 * size_t(f[1])], &xyz[3 * size_t(f[2])], o);
  return sum;
}

}  // namespace anitet::test

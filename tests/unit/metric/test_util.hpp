// Helpers shared by the metric tests: random SPD tensors and small checks.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>

#include "core/volume_mesh.hpp"
#include "metric/spd.hpp"

namespace anitet {
namespace metric {
namespace test {

// A random SPD tensor with sizes in [hmin, hmax] along random orthogonal directions.
inline void random_spd(std::mt19937_64& rng, double hmin, double hmax, double m[6]) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> lh(std::log(hmin), std::log(hmax));
  // A random symmetric log with eigenvalues -2 log h: rotate a diagonal by a random rotation,
  // obtained here by exponentiating a random symmetric matrix's eigenvectors.
  double s[6];
  for (double& x : s) x = u(rng);
  double val[3], vec[9];
  sym_eigen(s, val, vec);
  double l[3];
  for (double& x : l) x = 1.0 / std::pow(std::exp(lh(rng)), 2.0);
  const int idx[6][2] = {{0, 0}, {0, 1}, {1, 1}, {0, 2}, {1, 2}, {2, 2}};
  for (int c = 0; c < 6; ++c) {
    const int i = idx[c][0], j = idx[c][1];
    m[c] = 0.0;
    for (int k = 0; k < 3; ++k) m[c] += l[k] * vec[3 * k + i] * vec[3 * k + j];
  }
}

inline double frob(const double m[6]) {
  return std::sqrt(m[0] * m[0] + m[2] * m[2] + m[5] * m[5] +
                   2.0 * (m[1] * m[1] + m[3] * m[3] + m[4] * m[4]));
}

// Smallest eigenvalue of a - b, relative to |a|.
inline double min_eig_diff(const double a[6], const double b[6]) {
  double d[6];
  for (int i = 0; i < 6; ++i) d[i] = a[i] - b[i];
  return min_eigenvalue(d) / frob(a);
}

inline double max_rel_diff(const double a[6], const double b[6]) {
  double d[6];
  for (int i = 0; i < 6; ++i) d[i] = a[i] - b[i];
  return frob(d) / frob(b);
}

// n^3 unit cubes on [0, n]^3, each cut into the 6 tets of Kuhn's subdivision (positive).
inline VolumeMesh cube_mesh(int n) {
  VolumeMesh m;
  const int v = n + 1;
  for (int k = 0; k < v; ++k)
    for (int j = 0; j < v; ++j)
      for (int i = 0; i < v; ++i) {
        m.xyz.push_back(i);
        m.xyz.push_back(j);
        m.xyz.push_back(k);
      }
  auto id = [v](int i, int j, int k) { return uint32_t((k * v + j) * v + i); };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          uint32_t t[4];
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          // Odd permutations come out negative: swap two vertices.
          const bool odd = (p[0] == 0 && p[1] == 2) || (p[0] == 1 && p[1] == 0) || (p[0] == 2 && p[1] == 1);
          if (odd) std::swap(t[2], t[3]);
          m.tet.insert(m.tet.end(), t, t + 4);
          m.region.push_back(0);
        }
  return m;
}

}  // namespace test
}  // namespace metric
}  // namespace anitet

// Helpers shared by the metric tests: random SPD tensors and small checks.
#pragma once

#include <cmath>
#include <random>

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

}  // namespace test
}  // namespace metric
}  // namespace anitet

// A dense regular lattice of metric values: the working form in which metric fields are built,
// bounded (hmin/hmax) and graded before they are stored sparsely in OpenVDB (metric_field.hpp).
//
// Node (i, j, k) sits at origin + spacing * (i, j, k) (OpenVDB's voxel centres), x fastest in
// `values`. Each node holds either one size h (components == 1) or the 6 components of log(M)
// (components == 6, order xx xy yy xz yz zz).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"

namespace anitet {
namespace metric {

struct Lattice {
  double origin[3] = {0, 0, 0};
  double spacing = 1.0;
  int dims[3] = {0, 0, 0};
  int components = 1;          // 1: size h; 6: log-metric
  std::vector<double> values;  // components per node
  // Empty: every node is part of the field. Otherwise 1 per node, 0 for a node that is not
  // stored (its value is ignored; MetricField leaves the voxel inactive).
  std::vector<uint8_t> active;

  size_t num_nodes() const { return size_t(dims[0]) * size_t(dims[1]) * size_t(dims[2]); }
  size_t node(int i, int j, int k) const {
    return (size_t(k) * size_t(dims[1]) + size_t(j)) * size_t(dims[0]) + size_t(i);
  }
  void position(int i, int j, int k, double p[3]) const {
    p[0] = origin[0] + spacing * i;
    p[1] = origin[1] + spacing * j;
    p[2] = origin[2] + spacing * k;
  }
  // The metric M (not its log) at a node.
  void node_metric(size_t n, double m[6]) const;
};

// Error::InvalidArgument unless dims, spacing, components and values agree and every value is
// finite (and every size > 0).
Status check_lattice(const Lattice& lattice);

// Keeps every size in [hmin, hmax] (for tensors: each eigenvalue's size, eigenvectors kept).
// hmin <= 0 or hmax <= 0 means no bound on that side.
Status bound_sizes(Lattice& lattice, double hmin, double hmax);

struct GradationStats {
  int passes = 0;        // sweeps over the lattice
  size_t changed = 0;    // node updates
  bool converged = false;
};

// Bounded growth (Alauzet 2010, applied to the whole tensor): along a lattice step e from node a
// to its neighbour b, the metric may not shrink faster than M_b >= hgrad^(-2 l) M_a, where
// l = |e|_{M_a} is the step's length in a's metric; violating nodes get M_b <- M_b ∩ that.
// For sizes this is h_b <= h_a * hgrad^(spacing / h_a). Gauss-Seidel sweeps in alternating
// orders until nothing changes (at most max_passes). hgrad must be > 1.
Result<GradationStats> grade(Lattice& lattice, double hgrad, int max_passes = 1000);

}  // namespace metric
}  // namespace anitet

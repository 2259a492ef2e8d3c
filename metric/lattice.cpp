#include "lattice.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/sizing.hpp"
#include "spd.hpp"

namespace anitet {
namespace metric {

void Lattice::node_metric(size_t n, double m[6]) const {
  if (components == 1) isotropic_metric(values[n], m);
  else sym_exp(&values[6 * n], m);
}

Status check_lattice(const Lattice& lattice) {
  if (lattice.components != 1 && lattice.components != 6)
    return Status(Error::InvalidArgument, "a lattice holds 1 (size) or 6 (log-metric) values per node");
  if (!(lattice.spacing > 0.0) || !std::isfinite(lattice.spacing))
    return Status(Error::InvalidArgument, "lattice spacing must be positive");
  for (int a = 0; a < 3; ++a)
    if (lattice.dims[a] < 1) return Status(Error::InvalidArgument, "lattice dims must be >= 1");
  if (lattice.values.size() != lattice.num_nodes() * size_t(lattice.components))
    return Status(Error::InvalidArgument,
                  "lattice has " + std::to_string(lattice.values.size()) + " values for " +
                      std::to_string(lattice.num_nodes()) + " nodes");
  if (!lattice.active.empty() && lattice.active.size() != lattice.num_nodes())
    return Status(Error::InvalidArgument, "lattice active mask has the wrong size");
  for (size_t i = 0; i < lattice.values.size(); ++i) {
    const double v = lattice.values[i];
    if (!std::isfinite(v) || (lattice.components == 1 && !(v > 0.0)))
      return Status(Error::InvalidArgument,
                    "lattice value " + std::to_string(i) + " is not a finite positive size");
  }
  return Status::success();
}

Status bound_sizes(Lattice& lattice, double hmin, double hmax) {
  const double lo = hmin > 0.0 ? hmin : 0.0;
  const double hi = hmax > 0.0 ? hmax : HUGE_VAL;
  if (lo > hi) return Status(Error::InvalidArgument, "hmin is larger than hmax");
  if (lattice.components == 1) {
    for (double& h : lattice.values) h = std::min(std::max(h, lo), hi);
    return Status::success();
  }
  // Sizes 1e-150 .. 1e150 keep 1/h^2 a normal double: they stand for "no bound".
  const double h_lo = lo > 0.0 ? lo : 1e-150;
  const double h_hi = std::isinf(hi) ? 1e150 : hi;
  for (size_t n = 0; n < lattice.num_nodes(); ++n) {
    double m[6], c[6];
    sym_exp(&lattice.values[6 * n], m);
    if (!clamp_sizes(m, h_lo, h_hi, c) || !sym_log(c, &lattice.values[6 * n]))
      return Status(Error::InvalidArgument, "lattice node " + std::to_string(n) + " is not SPD");
  }
  return Status::success();
}

namespace {

// Sweeps the lattice in the order given by the signs of the three axes (dx, dy, dz = +1/-1):
// each node pulls the growth constraint from its 6 neighbours. Returns the number of updates.
template <class Relax>
size_t sweep(const Lattice& l, int sx, int sy, int sz, Relax&& relax) {
  size_t changed = 0;
  const int nx = l.dims[0], ny = l.dims[1], nz = l.dims[2];
  for (int kk = 0; kk < nz; ++kk) {
    const int k = sz > 0 ? kk : nz - 1 - kk;
    for (int jj = 0; jj < ny; ++jj) {
      const int j = sy > 0 ? jj : ny - 1 - jj;
      for (int ii = 0; ii < nx; ++ii) {
        const int i = sx > 0 ? ii : nx - 1 - ii;
        const size_t b = l.node(i, j, k);
        if (i > 0) changed += relax(l.node(i - 1, j, k), b, 0);
        if (i + 1 < nx) changed += relax(l.node(i + 1, j, k), b, 0);
        if (j > 0) changed += relax(l.node(i, j - 1, k), b, 1);
        if (j + 1 < ny) changed += relax(l.node(i, j + 1, k), b, 1);
        if (k > 0) changed += relax(l.node(i, j, k - 1), b, 2);
        if (k + 1 < nz) changed += relax(l.node(i, j, k + 1), b, 2);
      }
    }
  }
  return changed;
}

}  // namespace

Result<GradationStats> grade(Lattice& lattice, double hgrad, int max_passes) {
  Status st = check_lattice(lattice);
  if (!st.ok()) return st;
  if (!(hgrad > 1.0) || !std::isfinite(hgrad))
    return Status(Error::InvalidArgument, "hgrad must be a finite number > 1");
  const double log_g = std::log(hgrad);
  const double dx = lattice.spacing;
  GradationStats stats;
  static const int kOrders[8][3] = {{1, 1, 1},  {-1, -1, -1}, {1, -1, 1}, {-1, 1, -1},
                                    {1, 1, -1}, {-1, -1, 1},  {-1, 1, 1}, {1, -1, -1}};
  if (lattice.components == 1) {
    std::vector<double>& h = lattice.values;
    // Relative slack so that rounding cannot make the sweeps cycle.
    auto relax = [&](size_t a, size_t b, int) -> size_t {
      const double bound = h[a] * std::exp(log_g * dx / h[a]);
      if (h[b] > bound * (1.0 + 1e-13)) {
        h[b] = bound;
        return 1;
      }
      return 0;
    };
    for (; stats.passes < max_passes && !stats.converged; ++stats.passes) {
      const int* o = kOrders[stats.passes % 8];
      const size_t c = sweep(lattice, o[0], o[1], o[2], relax);
      stats.changed += c;
      stats.converged = c == 0;
    }
    return stats;
  }
  // Tensors: work on M itself, then store log(M) back.
  const size_t n = lattice.num_nodes();
  std::vector<double> m(6 * n);
  for (size_t v = 0; v < n; ++v) sym_exp(&lattice.values[6 * v], &m[6 * v]);
  auto relax = [&](size_t a, size_t b, int axis) -> size_t {
    const double* ma = &m[6 * a];
    double* mb = &m[6 * b];
    const double diag = axis == 0 ? ma[0] : axis == 1 ? ma[2] : ma[5];
    const double len = dx * std::sqrt(diag);  // |e|_{M_a} for e = dx along `axis`
    double grown[6];
    scale(ma, std::exp(-2.0 * log_g * len), grown);
    // Cheap rejection: b already contains the grown metric when b - grown is PSD.
    double diff[6];
    for (int i = 0; i < 6; ++i) diff[i] = mb[i] - grown[i];
    const double tol = 1e-12 * (mb[0] + mb[2] + mb[5]);
    if (min_eigenvalue(diff) >= -tol) return 0;
    double out[6];
    if (!intersect(mb, grown, out)) return 0;
    std::copy(out, out + 6, mb);
    return 1;
  };
  for (; stats.passes < max_passes && !stats.converged; ++stats.passes) {
    const int* o = kOrders[stats.passes % 8];
    const size_t c = sweep(lattice, o[0], o[1], o[2], relax);
    stats.changed += c;
    stats.converged = c == 0;
  }
  for (size_t v = 0; v < n; ++v)
    if (!sym_log(&m[6 * v], &lattice.values[6 * v]))
      return Status(Error::Internal, "gradation lost positive definiteness at node " + std::to_string(v));
  return stats;
}

}  // namespace metric
}  // namespace anitet

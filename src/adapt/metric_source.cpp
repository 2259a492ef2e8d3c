#include "adapt/metric_source.hpp"

#include <cmath>
#include <string>

#include "metric/spd.hpp"

namespace anitet::adapt {

Result<std::unique_ptr<VertexMetricSource>> VertexMetricSource::create(const VolumeMesh& mesh,
                                                                       const std::vector<double>& values) {
  const size_t nv = mesh.num_vertices();
  const int comps = nv > 0 && values.size() == nv ? 1 : nv > 0 && values.size() == 6 * nv ? 6 : 0;
  if (comps == 0)
    return Status(Error::InvalidArgument, "the metric has " + std::to_string(values.size()) +
                                              " values for a mesh of " + std::to_string(nv) +
                                              " vertices (1 size or 6 tensor components per vertex expected)");
  std::vector<double> tensor(6 * nv), logs(6 * nv);
  for (size_t v = 0; v < nv; ++v) {
    double* m = &tensor[6 * v];
    if (comps == 1) {
      const double h = values[v];
      if (!(h > 0.0) || !std::isfinite(h))
        return Status(Error::InvalidArgument, "the metric's size at vertex " + std::to_string(v + 1) + " is " +
                                                  std::to_string(h) + " (sizes must be > 0 and finite)");
      isotropic_metric(h, m);
    } else {
      for (int k = 0; k < 6; ++k) m[k] = values[6 * v + size_t(k)];
    }
    bool finite = true;
    for (int k = 0; k < 6; ++k) finite = finite && std::isfinite(m[k]);
    if (!finite || !metric::sym_log(m, &logs[6 * v]))
      return Status(Error::InvalidArgument, "the metric tensor at vertex " + std::to_string(v + 1) +
                                                " is not symmetric positive definite (" + std::to_string(m[0]) + " " +
                                                std::to_string(m[1]) + " " + std::to_string(m[2]) + " " +
                                                std::to_string(m[3]) + " " + std::to_string(m[4]) + " " +
                                                std::to_string(m[5]) + ")");
  }
  Result<metric::TetLocator> loc = metric::TetLocator::create(mesh);
  if (!loc.ok()) return loc.status();
  std::unique_ptr<VertexMetricSource> out(new VertexMetricSource(std::move(loc).value()));
  out->tensor_ = std::move(tensor);
  out->log_ = std::move(logs);
  return out;
}

void VertexMetricSource::at_vertex(uint32_t v, double m[6]) const {
  for (int k = 0; k < 6; ++k) m[k] = tensor_[6 * size_t(v) + size_t(k)];
}

void VertexMetricSource::eval(const double p[3], uint32_t& hint, double m[6]) const {
  const metric::TetLocator::Location loc = locator_.locate(p, hint);
  hint = loc.tet;
  const uint32_t* t = locator_.tet(loc.tet);
  double l[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    const double w = loc.weight[i];
    if (w == 0.0) continue;
    const double* lv = &log_[6 * size_t(t[i])];
    for (int k = 0; k < 6; ++k) l[k] += w * lv[k];
  }
  metric::sym_exp(l, m);
}

}  // namespace anitet::adapt

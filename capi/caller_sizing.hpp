// A caller's anitet_metric as the pipeline's SizingField: the one adapter the mesher, the metric
// writers and the sampling entry points use.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "core/sizing.hpp"
#include "handles.hpp"

namespace anitet::capi {

// Symmetric positive definite (leading minors > 0) and finite.
inline bool positive_definite(const double m[6]) {
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(m[i])) return false;
  const double d2 = m[0] * m[2] - m[1] * m[1];
  const double d3 = m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
                    m[3] * (m[1] * m[4] - m[2] * m[3]);
  return m[0] > 0.0 && d2 > 0.0 && d3 > 0.0;
}

// The caller's metric as the pipeline's sizing field. SizingField::metric cannot fail, so a
// failing analytic callback (or a tensor of it that is not positive definite) is recorded,
// answered with a coarse isotropic metric, and turned into an error at the next stage boundary.
class CallerSizing final : public anitet::SizingField {
 public:
  CallerSizing(const anitet_metric& m, double fallback_size) : m_(m), fallback_(fallback_size) {}

  void metric(const double p[3], double out[6]) const override {
    if (m_.kind == anitet_metric::Kind::Uniform) {
      anitet::isotropic_metric(m_.size, out);
      return;
    }
    if (m_.kind == anitet_metric::Kind::Field) {  // SPD by construction (checked when created)
      m_.field->metric(p, out);
      return;
    }
    const int rc = m_.fn(p[0], p[1], p[2], out, m_.user_data);
    if (rc == 0 && positive_definite(out)) return;
    if (!failed_.exchange(true)) {
      std::ostringstream why;
      why.precision(17);
      why << "the metric callback ";
      if (rc != 0) why << "returned " << rc;
      else why << "gave a tensor that is not positive definite";
      why << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
      const std::lock_guard<std::mutex> lock(mutex_);
      failure_ = why.str();
    }
    anitet::isotropic_metric(fallback_, out);
  }

  bool failed() const { return failed_.load(); }
  std::string failure() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
  }

 private:
  const anitet_metric& m_;
  double fallback_;
  mutable std::atomic<bool> failed_{false};
  mutable std::mutex mutex_;
  mutable std::string failure_;
};

// The diagonal of the bounding box of the points xyz (1 for a degenerate one): a size coarse
// enough to end a run quickly once its metric has failed.
inline double bounding_diagonal(const std::vector<double>& xyz) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  const double d = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                             (hi[2] - lo[2]) * (hi[2] - lo[2]));
  return std::isfinite(d) && d > 0.0 ? d : 1.0;
}

}  // namespace anitet::capi

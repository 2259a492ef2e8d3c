#include "combine.hpp"

#include <algorithm>

#include "spd.hpp"

namespace anitet {
namespace metric {

void IntersectionField::metric(const double p[3], double m[6]) const {
  if (fields_.empty()) {
    isotropic_metric(1.0, m);
    return;
  }
  fields_[0]->metric(p, m);
  for (size_t i = 1; i < fields_.size(); ++i) {
    double other[6], both[6];
    fields_[i]->metric(p, other);
    if (intersect(m, other, both)) std::copy(both, both + 6, m);
  }
}

void BoundedField::metric(const double p[3], double m[6]) const {
  double raw[6];
  field_.metric(p, raw);
  const double lo = hmin_ > 0.0 ? hmin_ : 1e-150, hi = hmax_ > 0.0 ? hmax_ : 1e150;
  if (!clamp_sizes(raw, lo, hi, m)) std::copy(raw, raw + 6, m);
}

}  // namespace metric
}  // namespace anitet

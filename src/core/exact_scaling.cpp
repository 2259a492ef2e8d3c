#include "core/exact_scaling.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace anitet {

Result<int> exact_power_of_two_scaling(std::initializer_list<PointArray> arrays) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  size_t n = 0;
  for (const PointArray& a : arrays)
    for (size_t i = 0; i < a.num_points; ++i, ++n)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], a.xyz[3 * i + size_t(d)]);
        hi[d] = std::max(hi[d], a.xyz[3 * i + size_t(d)]);
      }
  if (n == 0) return 0;
  double largest = 0, extent = 0;
  for (int d = 0; d < 3; ++d) {
    largest = std::max({largest, std::fabs(lo[d]), std::fabs(hi[d])});
    extent = std::max(extent, hi[d] - lo[d]);
  }
  if (largest <= kMaxCoordinate && extent >= kMinExtent) return 0;
  char msg[480];
  if (!(extent > 0.0) || !std::isfinite(extent)) {
    std::snprintf(msg, sizeof msg,
                  "coordinates up to %g in magnitude with an extent of %g fit the range computed in (coordinates "
                  "within %g, extent above %g) under no scaling by a power of two",
                  largest, extent, kMaxCoordinate, kMinExtent);
    return Status(Error::NotImplemented, msg);
  }
  const int k = -std::ilogb(extent);
  const double scaled_largest = std::ldexp(largest, k);
  bool exact = scaled_largest <= kMaxCoordinate && std::ldexp(extent, k) >= kMinExtent;
  for (const PointArray& a : arrays)
    for (size_t i = 0; exact && i < 3 * a.num_points; ++i) exact = std::ldexp(std::ldexp(a.xyz[i], k), -k) == a.xyz[i];
  if (!exact) {
    std::snprintf(msg, sizeof msg,
                  "coordinates up to %g in magnitude with an extent of %g fit the range computed in (within %g, "
                  "extent above %g) under no exact scaling by a power of two (2^%d would put them at up to %g, or "
                  "lose bits of the smallest): translate them nearer the origin",
                  largest, extent, kMaxCoordinate, kMinExtent, k, scaled_largest);
    return Status(Error::NotImplemented, msg);
  }
  return k;
}

}  // namespace anitet

// First-layer height from a target y+ (flat-plate skin-friction estimate).
#include <cmath>
#include <string>

#include "layers/layers.hpp"

namespace anitet {

Result<double> first_height_from_yplus(double yplus, double reynolds, double ref_length) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(yplus) || !positive(reynolds) || !positive(ref_length)) {
    return Status(Error::InvalidArgument, "y+ (" + std::to_string(yplus) + "), the Reynolds number (" +
                                              std::to_string(reynolds) + ") and the reference length (" +
                                              std::to_string(ref_length) + ") must all be positive");
  }
  const double cf = 0.026 * std::pow(reynolds, -1.0 / 7.0);
  const double h0 = yplus * ref_length / (reynolds * std::sqrt(cf / 2.0));
  if (!positive(h0)) return Status(Error::InvalidArgument, "the first height from y+ is not a positive number");
  return h0;
}

}  // namespace anitet

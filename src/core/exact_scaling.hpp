// Scaling by a power of two: exact while no result overflows or falls below the smallest normal
// double, and it leaves the sign of every geometric predicate as it was. The stages that compute
// in plain floating point (stage 1's tests, the quality measures) are measured to work for
// coordinates up to kMaxCoordinate in magnitude and boxes at least kMinExtent across; inputs
// outside that range are handled scaled into it, and the results scaled back.
#pragma once

#include <cstddef>
#include <initializer_list>

#include "core/status.hpp"

namespace anitet {

// Stage 1's floating-point tests overflow on a cube of half-side 1e100 and underflow on one of
// 1e-100; both mesh at 1e30 and 1e-30.
constexpr double kMaxCoordinate = 1e30;
constexpr double kMinExtent = 1e-30;

// The k for which 2^k brings the points (3 doubles each, several arrays) into that range: 0 when
// they are in it, else the k that makes their extent about 1. Error::NotImplemented, saying why,
// when no k does it exactly (a coordinate that would lose bits, a box no scaling fits, a
// non-finite or zero extent out of range).
struct PointArray {
  const double* xyz;
  size_t num_points;
};
Result<int> exact_power_of_two_scaling(std::initializer_list<PointArray> arrays);

}  // namespace anitet

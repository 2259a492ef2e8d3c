// first_height_from_yplus: the flat-plate estimate Cf = 0.026 Re^(-1/7), h0 = y+ nu / u_tau.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "layers/layers.hpp"

namespace anitet {
namespace {

TEST(YPlus, FlatPlateFirstHeight) {
  // Re = 1e6 on L = 1: Cf = 0.0036127, sqrt(Cf/2) = 0.042501, h0 = 1 / (1e6 * 0.042501).
  Result<double> h0 = first_height_from_yplus(1.0, 1e6, 1.0);
  ASSERT_TRUE(h0.ok()) << h0.status().message();
  EXPECT_NEAR(h0.value(), 2.352879860611332e-05, 1e-15);

  // The same in dimensional terms: U = 10 m/s, nu = 1.5e-5 m^2/s, L = 1.5 m (Re = 1e6), y+ = 30:
  // tau_w / rho = Cf U^2 / 2, u_tau = sqrt(tau_w / rho), h0 = y+ nu / u_tau = 1.0588 mm.
  const double u = 10.0, nu = 1.5e-5, length = 1.5, re = u * length / nu;
  const double u_tau = std::sqrt(0.026 * std::pow(re, -1.0 / 7.0) * u * u / 2.0);
  Result<double> h = first_height_from_yplus(30.0, re, length);
  ASSERT_TRUE(h.ok());
  EXPECT_NEAR(h.value(), 30.0 * nu / u_tau, 1e-15);
  EXPECT_NEAR(h.value(), 1.0587959372750993e-3, 1e-12);

  // Linear in y+ and in L at a fixed Re; decreasing in Re (as Re^(-13/14)).
  EXPECT_NEAR(first_height_from_yplus(5.0, 1e6, 2.0).value(), 10.0 * h0.value(), 1e-15);
  EXPECT_NEAR(first_height_from_yplus(1.0, 1e7, 1.0).value() / h0.value(), std::pow(10.0, -13.0 / 14.0), 1e-12);
}

TEST(YPlus, RefusesNonPositiveOrNonFiniteInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double bad : {0.0, -1.0, nan, inf}) {
    EXPECT_EQ(first_height_from_yplus(bad, 1e6, 1.0).status().code(), Error::InvalidArgument) << bad;
    EXPECT_EQ(first_height_from_yplus(1.0, bad, 1.0).status().code(), Error::InvalidArgument) << bad;
    EXPECT_EQ(first_height_from_yplus(1.0, 1e6, bad).status().code(), Error::InvalidArgument) << bad;
  }
}

}  // namespace
}  // namespace anitet

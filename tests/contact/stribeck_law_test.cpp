#include <stickslip/contact/stribeck_law.hpp>

#include "contact/contact_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace contact_stribeck_law_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::expect_invalid_argument;
using Law = stickslip::StribeckLaw<double>;

// mu(s) = mu_k + (mu_s - mu_k) exp(-(s/v_s)^delta) evaluated at points where the exponential
// has a known value. Tolerance: a few ulps of the coefficients (one exp and one pow).
TEST(StribeckLaw, DecaysFromStaticToKineticAsDefined) {
  const Law law(0.5, 0.3, 0.01);
  const double tol = 4 * std::numeric_limits<double>::epsilon();
  EXPECT_EQ(law.static_coefficient(), 0.5);
  EXPECT_NEAR(law.kinetic_coefficient(0.0), 0.5, tol);
  EXPECT_NEAR(law.kinetic_coefficient(0.01), 0.3 + 0.2 / std::exp(1.0), tol);
  EXPECT_NEAR(law.kinetic_coefficient(0.02), 0.3 + 0.2 * std::exp(-4.0), tol);
  EXPECT_NEAR(law.kinetic_coefficient(1.0), 0.3, tol);  // exp(-1e4) underflows to 0
}

TEST(StribeckLaw, ExponentShapesTheDecay) {
  const Law exponential(0.6, 0.2, 0.5, 1.0);
  const double tol = 4 * std::numeric_limits<double>::epsilon();
  EXPECT_NEAR(exponential.kinetic_coefficient(1.0), 0.2 + 0.4 * std::exp(-2.0), tol);
  const Law steep(0.6, 0.2, 0.5, 8.0);
  EXPECT_NEAR(steep.kinetic_coefficient(0.25), 0.2 + 0.4 * std::exp(-std::pow(0.5, 8.0)), tol);
  EXPECT_NEAR(steep.kinetic_coefficient(1.0), 0.2 + 0.4 * std::exp(-256.0), tol);
}

TEST(StribeckLaw, IsMonotoneNonIncreasingInSpeed) {
  const Law law(0.5, 0.3, 0.01, 1.5);
  double previous = law.kinetic_coefficient(0.0);
  for (int i = 1; i <= 1000; ++i) {
    const double mu = law.kinetic_coefficient(1e-4 * i);
    EXPECT_LE(mu, previous);
    EXPECT_GE(mu, 0.3);
    previous = mu;
  }
}

TEST(StribeckLaw, EqualCoefficientsGiveClassicalCoulomb) {
  const Law law(0.4, 0.4, 1e-3);
  for (double speed : {0.0, 1e-3, 1.0}) EXPECT_EQ(law.kinetic_coefficient(speed), 0.4);
}

TEST(StribeckLaw, RejectsBadParametersNamingThem) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument([] { Law(0.5, -0.3, 0.1); }, {"StribeckLaw", "mu_k"});
  expect_invalid_argument([] { Law(0.3, 0.5, 0.1); }, {"StribeckLaw", "mu_s"});
  expect_invalid_argument([] { Law(0.5, 0.3, 0.0); }, {"StribeckLaw", "v_s", "0"});
  expect_invalid_argument([] { Law(0.5, 0.3, -1.0); }, {"StribeckLaw", "v_s", "-1"});
  expect_invalid_argument([&] { Law(0.5, 0.3, nan); }, {"StribeckLaw", "v_s"});
  expect_invalid_argument([] { Law(0.5, 0.3, 0.1, 0.0); }, {"StribeckLaw", "exponent"});
  expect_invalid_argument([&] { Law(0.5, 0.3, 0.1, nan); }, {"StribeckLaw", "exponent"});
}

}  // namespace
}  // namespace contact_stribeck_law_test

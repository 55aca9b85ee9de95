#include <stickslip/contact/regularised_law.hpp>

#include "contact/contact_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace contact_regularised_law_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::expect_invalid_argument;
using Law = stickslip::RegularisedLaw<double>;
using stickslip::RegularisedShape;

TEST(RegularisedLaw, TanhShapeMatchesItsDefinitionAndIsOdd) {
  const Law law(0.4, 1e-3, RegularisedShape::Tanh);
  const double tol = 4 * std::numeric_limits<double>::epsilon();
  EXPECT_EQ(law.coefficient(0.0), 0.0);
  EXPECT_NEAR(law.coefficient(1e-3), 0.4 * std::tanh(1.0), tol);
  EXPECT_NEAR(law.coefficient(1.0), 0.4, tol);  // saturated: tanh(1000) = 1 in double
  for (double v : {1e-5, 3e-4, 2e-3, 0.5}) EXPECT_EQ(law.coefficient(-v), -law.coefficient(v));
}

TEST(RegularisedLaw, LinearSaturatedIsAClampedRamp) {
  const Law law(0.4, 1e-3, RegularisedShape::LinearSaturated);
  const double tol = 4 * std::numeric_limits<double>::epsilon();
  EXPECT_NEAR(law.coefficient(5e-4), 0.2, tol);
  EXPECT_NEAR(law.coefficient(-2.5e-4), -0.1, tol);
  EXPECT_EQ(law.coefficient(1e-3), 0.4);
  EXPECT_EQ(law.coefficient(7.0), 0.4);
  EXPECT_EQ(law.coefficient(-7.0), -0.4);
  EXPECT_NEAR(law.coefficient_derivative(1e-4), 400.0, 400.0 * tol);
  EXPECT_EQ(law.coefficient_derivative(2e-3), 0.0);
}

// The analytic derivative against central differences, whose error is O(h^2): halving h must
// divide the error by 4 (order 2 +- 0.3), which a wrong derivative cannot do.
TEST(RegularisedLaw, TanhDerivativeMatchesCentralDifferencesAtOrderTwo) {
  const Law law(0.4, 1e-3, RegularisedShape::Tanh);
  for (double v : {-1.5e-3, -2e-4, 3e-4, 8e-4}) {
    auto error = [&](double h) {
      const double fd = (law.coefficient(v + h) - law.coefficient(v - h)) / (2 * h);
      return std::abs(fd - law.coefficient_derivative(v));
    };
    const double h = 2e-5;
    EXPECT_NEAR(std::log2(error(h) / error(h / 2)), 2.0, 0.3) << "v = " << v;
  }
}

TEST(RegularisedLaw, RejectsBadParametersNamingThem) {
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid_argument([] { Law(-0.1, 1e-3); }, {"RegularisedLaw", "mu", "-0.1"});
  expect_invalid_argument([&] { Law(inf, 1e-3); }, {"RegularisedLaw", "mu"});
  expect_invalid_argument([] { Law(0.3, 0.0); }, {"RegularisedLaw", "v_eps"});
  expect_invalid_argument([] { Law(0.3, -1e-3); }, {"RegularisedLaw", "v_eps"});
  expect_invalid_argument([&] { Law(0.3, inf); }, {"RegularisedLaw", "v_eps", "inf"});
}

}  // namespace
}  // namespace contact_regularised_law_test

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

// RegularisedLaw(0.3, 1e-310).coefficient_derivative(0.01) was inf * 0 = NaN
// (mu / v_eps overflowed before the factor 1 - tanh^2 = 0). A v_eps whose slope mu / v_eps
// overflows is now rejected by name with its limit, and at the smallest admitted v_eps the
// derivative is finite everywhere: the closed form (mu / v_eps) sech^2(v / v_eps).
TEST(RegularisedLaw, TinyVEpsIsRejectedOrGivesAFiniteDerivative) {
  expect_invalid_argument([] { Law(0.3, 1e-310); }, {"RegularisedLaw", "v_eps", "slope"});
  expect_invalid_argument([] { Law(1e10, 1e-300); }, {"RegularisedLaw", "v_eps", "1e-300"});
  const double v_min = Law::min_v_eps(0.3);
  EXPECT_EQ(v_min, std::numeric_limits<double>::min());  // 0.3 / DBL_MAX is below it
  EXPECT_EQ(Law::min_v_eps(1e10), 1e10 / std::numeric_limits<double>::max());
  for (auto shape : {RegularisedShape::Tanh, RegularisedShape::LinearSaturated}) {
    const Law law(0.3, v_min, shape);
    // Far beyond v_eps the law is saturated: the derivative is exactly 0 (sech^2(1e305) = 0).
    EXPECT_EQ(law.coefficient_derivative(0.01), 0.0);
    EXPECT_EQ(law.coefficient_derivative(-1e300), 0.0);
    // At v = 0 it is the peak slope mu / v_eps, finite by the limit; computed as mu (1 - 0) /
    // v_eps: one rounding, hence the 1-ulp tolerance.
    EXPECT_NEAR(law.coefficient_derivative(0.0), 0.3 / v_min, 0.3 / v_min * 2.3e-16);
    EXPECT_TRUE(std::isfinite(law.coefficient_derivative(v_min)));
  }
  // Tanh at v = v_eps: (mu / v_eps) sech^2(1), a few roundings of tanh and the product (8 ulp).
  const Law law(0.3, 1e-300);
  const double sech = 1.0 / std::cosh(1.0);
  EXPECT_NEAR(law.coefficient_derivative(1e-300), 0.3e300 * sech * sech, 0.3e300 * sech * sech * 8 * 2.2e-16);
}

}  // namespace
}  // namespace contact_regularised_law_test

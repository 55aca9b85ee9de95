#include <stickslip/contact/coulomb_law.hpp>

#include "contact/contact_test_util.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace contact_coulomb_law_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::expect_invalid_argument;
using Law = stickslip::CoulombLaw<double>;

TEST(CoulombLaw, CoefficientsAreConstant) {
  const Law law(0.5, 0.3);
  EXPECT_EQ(law.static_coefficient(), 0.5);
  for (double speed : {0.0, 1e-12, 1.0, 1e9}) EXPECT_EQ(law.kinetic_coefficient(speed), 0.3);
  EXPECT_EQ(law.mu_s(), 0.5);
  EXPECT_EQ(law.mu_k(), 0.3);
}

TEST(CoulombLaw, AcceptsTheLimitsEqualCoefficientsAndZeroFriction) {
  EXPECT_NO_THROW(Law(0.4, 0.4));
  EXPECT_NO_THROW(Law(0.0, 0.0));
  EXPECT_NO_THROW(Law(0.2, 0.0));
}

TEST(CoulombLaw, RejectsBadCoefficientsNamingTheParameter) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid_argument([] { Law(0.5, -0.1); }, {"CoulombLaw", "mu_k", "-0.1"});
  expect_invalid_argument([] { Law(0.2, 0.3); }, {"CoulombLaw", "mu_s", ">= mu_k", "0.2"});
  expect_invalid_argument([&] { Law(nan, 0.3); }, {"CoulombLaw", "mu_s", "nan"});
  expect_invalid_argument([&] { Law(inf, 0.3); }, {"CoulombLaw", "mu_s", "inf"});
  expect_invalid_argument([&] { Law(0.5, nan); }, {"CoulombLaw", "mu_k"});
}

}  // namespace
}  // namespace contact_coulomb_law_test

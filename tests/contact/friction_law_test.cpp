#include <stickslip/contact/friction_law.hpp>

#include <stickslip/contact/coulomb_law.hpp>
#include <stickslip/contact/regularised_law.hpp>
#include <stickslip/contact/stribeck_law.hpp>

#include <gtest/gtest.h>

namespace contact_friction_law_test {  // named: the contact test files share one (unity) translation unit
namespace {

// A user law with the exact-law interface: mu_k rising linearly with speed (velocity
// strengthening), capped at mu_s.
struct LinearStrengtheningLaw {
  using Scalar = double;
  static constexpr bool has_stick_state = true;
  double static_coefficient() const { return 0.5; }
  double kinetic_coefficient(double speed) const { return speed > 1.0 ? 0.5 : 0.3 + 0.2 * speed; }
};

// A user law with the regularised interface.
struct AtanLaw {
  using Scalar = double;
  static constexpr bool has_stick_state = false;
  double coefficient(double v) const;
  double coefficient_derivative(double v) const;
};

struct MissingKinetic {
  using Scalar = double;
  static constexpr bool has_stick_state = true;
  double static_coefficient() const { return 0.5; }
};

// Exact interface but claims to have no stick state: inconsistent, rejected.
struct InconsistentFlag {
  using Scalar = double;
  static constexpr bool has_stick_state = false;
  double static_coefficient() const { return 0.5; }
  double kinetic_coefficient(double) const { return 0.3; }
};

struct NoScalar {
  static constexpr bool has_stick_state = false;
  double coefficient(double) const;
  double coefficient_derivative(double) const;
};

TEST(FrictionLawTrait, AcceptsTheLibraryLaws) {
  EXPECT_TRUE(stickslip::is_friction_law_v<stickslip::CoulombLaw<double>>);
  EXPECT_TRUE(stickslip::is_friction_law_v<stickslip::StribeckLaw<float>>);
  EXPECT_TRUE(stickslip::is_friction_law_v<stickslip::RegularisedLaw<long double>>);
}

TEST(FrictionLawTrait, AcceptsUserLawsWithEitherInterface) {
  EXPECT_TRUE(stickslip::is_friction_law_v<LinearStrengtheningLaw>);
  EXPECT_TRUE(stickslip::is_friction_law_v<AtanLaw>);
}

TEST(FrictionLawTrait, RejectsIncompleteOrInconsistentLaws) {
  EXPECT_FALSE(stickslip::is_friction_law_v<MissingKinetic>);
  EXPECT_FALSE(stickslip::is_friction_law_v<InconsistentFlag>);
  EXPECT_FALSE(stickslip::is_friction_law_v<NoScalar>);
  EXPECT_FALSE(stickslip::is_friction_law_v<double>);
}

}  // namespace
}  // namespace contact_friction_law_test

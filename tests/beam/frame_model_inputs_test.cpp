// Checked inputs of FrameModel: overflow and underflow in the section, the member
// geometry, the nodal masses and the assembly are named by their cause, and absurd sizes
// are refused against stated limits.

#include "beam/beam_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace frame_model_inputs_test {  // named: the beam test files share one (unity) translation unit
namespace {

using namespace stickslip;
using namespace stickslip_test;
using Index = Eigen::Index;

// E I = 1e200 * 1e200 overflows although both factors are finite: it was accepted and surfaced at
// the eigen-solve as "is M positive definite?". Likewise rho A and E A.
TEST(FrameModelInputs, OverflowingRigiditiesAndMassPerLengthAreNamed) {
  FrameModel<double> m;
  const auto a = m.add_node(0.0, 0.0), b = m.add_node(1.0, 0.0);
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{1e200, 7800.0, 1e-4, 1e200}), 2), "section.E * section.I");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{1e200, 7800.0, 1e200, 1e-9}), 2), "section.E * section.A");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{2e11, 1e300, 1e10, 1e-9}), 2), "section.rho * section.A");
  // Underflow to 0 is named as well (E A = 1e-200 * 1e-200 = 0).
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{1e-200, 7800.0, 1e-200, 1e-9}), 2), "section.E * section.A");
  EXPECT_EQ(m.num_members(), 0);
}

// Two point masses of 1e308 kg on one node summed to inf and gave NaN mode shapes with no error.
TEST(FrameModelInputs, OverflowingNodalSumsAreNamedAtTheCall) {
  FrameModel<double> m;
  const auto a = m.add_node(0.0, 0.0), b = m.add_node(1.0, 0.0);
  m.add_member(a, b, slender_steel(), 2);
  m.add_point_mass(b, 1e308);
  EXPECT_INVALID_ARGUMENT(m.add_point_mass(b, 1e308), "overflows");
  m.add_rotary_inertia(b, 1.5e308);
  EXPECT_INVALID_ARGUMENT(m.add_rotary_inertia(b, 1e308), "node 1");
  m.add_spring(a, Dof::Y, 1.5e308);
  EXPECT_INVALID_ARGUMENT(m.add_spring(a, Dof::Y, 1e308), "k: the sum on DOF Y of node 0 overflows");
  // Nothing was added by the refused calls: the model still assembles, with finite matrices.
  const auto f = m.assemble();
  EXPECT_TRUE(Eigen::MatrixXd(f.mass).allFinite());
  EXPECT_TRUE(Eigen::MatrixXd(f.stiffness).allFinite());
}

// A 1e-160 m member: |d|^2 = 1e-320 is subnormal, so the plain norm was off by ~1e-5 relative
// and the element rejected its direction as "cos^2 + sin^2 must be 1". The length is now exact
// (stableNorm) and the real cause, E I / L^3 = 4e480 overflowing, is named with the member.
TEST(FrameModelInputs, TinyMemberHasExactDirectionAndItsOverflowIsNamed) {
  for (double angle : {0.0, 0.7853981633974483}) {
    FrameModel<double> m;
    const double L = 1e-160;
    const auto a = m.add_node(0.0, 0.0), b = m.add_node(L * std::cos(angle), L * std::sin(angle));
    m.add_member(a, b, slender_steel(), 1);
    const auto& member = m.member(0);
    // cos and sin from the exact length: a unit vector to a few ulp (the subnormal-free
    // computation keeps full precision; cos^2 + sin^2 adds three roundings: 4 ulp).
    EXPECT_NEAR(member.cos * member.cos + member.sin * member.sin, 1.0, 9e-16) << angle;
    EXPECT_NEAR(member.length / L, 1.0, 4e-16) << angle;
    EXPECT_INVALID_ARGUMENT(m.assemble(), "member 0, element 0");
    EXPECT_INVALID_ARGUMENT(m.assemble(), "too short or too long");
  }
  // A 1e200 m member: rho A L^3 (the rotary terms of its mass) overflows. (Adding its second node
  // also overflowed the norm of the coincidence check: it was refused as coinciding with node 0.)
  FrameModel<double> m;
  const auto a = m.add_node(0.0, 0.0), b = m.add_node(1e200, 0.0);
  m.add_member(a, b, slender_steel(), 1);
  EXPECT_INVALID_ARGUMENT(m.assemble(), "rho A L^3 = inf");
}

// Each element's entries are finite (E A / L = 1.5e308) but two elements meet at the middle node,
// where the assembled stiffness sums to 3e308 = inf: named with the DOF and node.
TEST(FrameModelInputs, OverflowingAssembledSumIsNamedWithTheDof) {
  FrameModel<double> m;
  const auto a = m.add_node(0.0, 0.0), b = m.add_node(2.0, 0.0);
  m.add_member(a, b, (Section{1.5e300, 1e-300, 1e8, 1.0}), 2);  // interior node 2 at x = 1
  EXPECT_INVALID_ARGUMENT(m.assemble(), "assembled K has a non-finite entry (inf) in the row of DOF X of node 2");
}

// 2^62 elements threw std::length_error (or tried to allocate); now refused against the limit.
TEST(FrameModelInputs, AbsurdElementCountsAreRefusedAgainstTheStatedLimit) {
  FrameModel<double> m;
  const auto a = m.add_node(0.0, 0.0), b = m.add_node(1.0, 0.0);
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, slender_steel(), Index(1) << 62), "max_elements_per_member = 1048576");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, slender_steel(), FrameModel<double>::max_elements_per_member + 1),
                          "elements must be in [1, max_elements_per_member");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, slender_steel(), 0), "elements");
  EXPECT_EQ(m.num_nodes(), 2);
  EXPECT_EQ(m.num_members(), 0);
}

}  // namespace
}  // namespace frame_model_inputs_test

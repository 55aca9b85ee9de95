// Shooting on the belt-driven stick-slip oscillator (autonomous, tests/contact/belt_cycle.hpp):
// period and amplitude of the limit cycle in closed form; the stick phase collapses the state,
// so the nontrivial Floquet multiplier is 0 and the trivial one is 1.

#include "contact/belt_cycle.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace steady_state_belt_test {
namespace {

using contact_test::BeltCase;
using contact_test::BeltCycle;
using contact_test::SingleDofParameters;
using namespace steady_state_test;

SingleDofParameters belt_parameters(double belt_speed) {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 100.0;
  p.normal_force = 10.0;
  p.belt_speed = belt_speed;
  return p;
}

// Tolerances: runs at rtol 1e-10, Newton at 1e-9 max(1, |x|) on states of O(0.1): the period and
// the state are right to ~1e-9 (1e-8 allowed). The amplitude max |x| is taken from 256 samples
// per period plus steps and events; the peak x_k + A is in slip, between samples: the sampling
// error is below A (1 - cos(pi T_slip / (256 T))) < 1e-4 A.
TEST(SteadyStateBelt, StickSlipCycleIsTheClosedForm) {
  for (const BeltCase c : {BeltCase{0.5, 0.3, 0.2}, BeltCase{0.4, 0.1, 0.05}}) {
    SCOPED_TRACE(::testing::Message() << "mu_s " << c.mu_s << " mu_k " << c.mu_k << " v_b "
                                      << c.belt_speed);
    const SingleDofParameters p = belt_parameters(c.belt_speed);
    const BeltCycle ref(p.mass, p.stiffness, p.normal_force, c);
    const double w = std::sqrt(p.stiffness / p.mass), T = ref.t_stick + ref.t_slip;
    Oscillator sys(p, Contact(Law(c.mu_s, c.mu_k)));
    // Guess: the slip phase's midpoint x = x_k, x' = -A w, moved by a few per cent.
    const Eigen::Vector4d guess(ref.x_k + 0.05 * ref.A, -0.95 * ref.A * w, 0, 0);
    stickslip::Shooting<Oscillator> shooting(sys, oscillator_options());
    const auto orbit = shooting.autonomous(S::SlipNegative, guess, 1.05 * T);
    ASSERT_TRUE(orbit.ok()) << orbit.message;
    EXPECT_NEAR(orbit.period, T, 1e-8 * T);
    // x0 lies on the slip arc (x - x_k)^2 + (x'/w)^2 = A^2.
    EXPECT_NEAR(std::hypot(orbit.x0[0] - ref.x_k, orbit.x0[1] / w), ref.A, 1e-8);
    EXPECT_NEAR(orbit.amplitudes[0], ref.x_k + ref.A, 1e-4 * ref.A);
    ASSERT_EQ(orbit.events.size(), 2u);  // slip -> stick, stick -> slip
    ASSERT_TRUE(orbit.floquet.has_trivial);
    EXPECT_NEAR(std::abs(orbit.floquet.trivial - 1.0), 0.0, 1e-6);
    ASSERT_EQ(orbit.floquet.multipliers.size(), 1);
    EXPECT_LT(std::abs(orbit.floquet.multipliers[0]), 1e-8);
    EXPECT_TRUE(orbit.floquet.stable);

    // Saltation: variational vs finite-difference monodromy on the cycle (stick entry, stick
    // exit); 1e-6 as in the issue (the differences are exact to ~rtol / h = 1e-4 relative of
    // the run error 1e-10, i.e. ~1e-8 here).
    auto opt = oscillator_options();
    const auto var = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, orbit.period, opt, true);
    opt.monodromy = stickslip::MonodromyMethod::FiniteDifference;
    const auto fd = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, orbit.period, opt, true);
    ASSERT_TRUE(var.ok() && fd.ok()) << var.message << fd.message;
    expect_matrix_near(var.monodromy.topLeftCorner(2, 2), fd.monodromy.topLeftCorner(2, 2), 1e-6,
                       "variational vs finite-difference monodromy");
  }
}

}  // namespace
}  // namespace steady_state_belt_test

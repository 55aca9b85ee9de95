// A damper leaving a vibrating one-mode structure and landing again (tests/contact/impact_systems.hpp,
// DamperOnOneMode): the contact component used as the composed model would use it. Each impact is
// checked on the states recorded just before and after it, independently of frictional_impact:
// the generalised momentum q' + m (a y' + b x') that an internal impulse cannot change, Newton's
// law on the relative normal velocity, Coulomb's law on the impulses read back from the damper's
// velocity jumps, and the kinetic energy lost against the impact loss the system books. The
// energy balance of the whole run closes through those losses.

#include "contact/impact_systems.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace contact_one_mode_impact_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::DamperOnOneMode;
using stickslip::ContactState;
using State = DamperOnOneMode::State;

struct RunSummary {
  stickslip::HybridResult<double, State, ContactState> result;
  State x0;
};

RunSummary run(DamperOnOneMode& sys, double t_end) {
  stickslip::StepperOptions<double> o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.max_step = 1e-3;  // 1/100 of the mode's period: the stick guards move with the vibration
  stickslip::HybridStepper<DamperOnOneMode> stepper(sys, o);
  State x0 = State::Zero();  // at rest, in contact (y = a q = 0), stuck
  return {stepper.integrate(ContactState::Stick, 0.0, x0, t_end), x0};
}

// Checks of one impact on the recorded states (see the file comment).
void check_impact(const DamperOnOneMode& sys, const DamperOnOneMode::ImpactRecord& hit, double e,
                  double mu) {
  const auto& p = sys.parameters();
  const State& b = hit.before;
  const State& a = hit.after;
  SCOPED_TRACE("impact at t = " + std::to_string(hit.t));
  // Velocities ~ 1 m/s, masses ~ 0.1-1: round-off of a few operations, 1e-13.
  const double tol = 1e-13;
  EXPECT_NEAR(sys.contact_momentum(a), sys.contact_momentum(b), tol);
  EXPECT_EQ(a[0], b[0]);  // an impulse does not move anything
  EXPECT_EQ(a[2], b[2]);
  const double L_n = p.m * (a[5] - b[5]), L_t = p.m * (a[3] - b[3]);
  EXPECT_GT(L_n, 0.0);
  const double v_n = b[5] - p.a * b[1], v_n_after = a[5] - p.a * a[1];
  EXPECT_LT(v_n, 0.0);
  EXPECT_NEAR(v_n_after, hit.lands ? 0.0 : -e * v_n, tol);
  const double V = a[3] - p.b * a[1];
  if (std::abs(L_t) < mu * L_n * (1.0 - 1e-12)) {
    EXPECT_NEAR(V, 0.0, tol);  // inside the capacity: the impulse stopped the sliding
  } else {                     // on it: slides, friction opposing the sliding after
    EXPECT_NEAR(std::abs(L_t), mu * L_n, tol * L_n);
    EXPECT_LE(V * L_t, tol);
  }
  // Kinetic energy lost = the impact loss booked; the landing also puts y onto a q (a gap of the
  // event tolerance times |v_n|, 1e-12 m, times P = 1 N).
  EXPECT_NEAR(sys.energy(b) - sys.energy(a), a[6] - b[6], 1e-11);
  EXPECT_GE(a[6] - b[6], -1e-15);
}

TEST(DamperOnOneMode, LeavesTheVibratingModeAndLandsAgainWithMomentumNewtonCoulombAndEnergyAtEachImpact) {
  const double e = 0.5, mu = 0.3;
  DamperOnOneMode sys({}, DamperOnOneMode::Law(mu, mu), stickslip::NewtonImpact<double>(e, 1e-4));
  const auto r = run(sys, 1.0);
  ASSERT_TRUE(r.result.ok()) << r.result.message;
  // The forced mode (0.9 omega) accelerates the contact beyond P/m = 10 m/s^2 once it has built
  // up: the damper lifts off and, with e = 0.5, mostly bounces off the vibrating mode (as a ball
  // on a vibrating table); the run has lift-offs, bounces and at least one landing (measured: 2
  // lift-offs, 18 impacts; the first 9 a Zeno sequence ended by the landing rule at t = 0.158,
  // sliding impulses there, stopping ones later: both branches of Coulomb's law).
  EXPECT_GE(sys.lift_offs.size(), 2u);
  ASSERT_GE(sys.impacts.size(), 10u);
  const auto landings = std::count_if(sys.impacts.begin(), sys.impacts.end(),
                                      [](const auto& h) { return h.lands; });
  EXPECT_GE(landings, 1);
  EXPECT_GE(sys.impacts.size() - static_cast<std::size_t>(landings), 5u);  // bounces
  for (const auto& hit : sys.impacts) check_impact(sys, hit, e, mu);
  // Whole run: energy + impact, friction and viscous losses - external work, constant. Terms
  // ~ 0.1-1 J; the integration error of the work integrals at rtol 1e-10 over 1 s (measured
  // 3.9e-10).
  EXPECT_NEAR(sys.balance(r.result.x), sys.balance(r.x0), 1e-8);
  EXPECT_GT(r.result.x[6], 0.0);
}

TEST(DamperOnOneMode, PlasticImpactsAlwaysLandAndTheRunNeverChatters) {
  const double mu = 0.3;
  DamperOnOneMode sys({}, DamperOnOneMode::Law(mu, mu), stickslip::NewtonImpact<double>(0.0, 0.0));
  const auto r = run(sys, 1.0);
  ASSERT_TRUE(r.result.ok()) << r.result.message;
  // Every flight ends in a landing (measured: 9 lift-offs, 8 impacts in 1 s).
  EXPECT_GE(sys.lift_offs.size(), 5u);
  ASSERT_GE(sys.impacts.size(), 5u);
  for (const auto& hit : sys.impacts) {
    EXPECT_TRUE(hit.lands);
    check_impact(sys, hit, 0.0, mu);
  }
  EXPECT_NEAR(sys.balance(r.result.x), sys.balance(r.x0), 1e-8);  // measured 3.3e-10
}

}  // namespace
}  // namespace contact_one_mode_impact_test

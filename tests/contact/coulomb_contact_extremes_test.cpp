// Extremes of the contact parameters with the hybrid stepper: N -> 0, mu_s = mu_k, lift-off.
// (mu_k = 0 is in the belt test, N huge and the exact threshold in the held-mass test.)

#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace contact_coulomb_contact_extremes_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;
using Law = stickslip::CoulombLaw<double>;
using Sys = SingleDofOscillator<Law>;
constexpr double kPi = 3.14159265358979323846;

// N = 1e-300: the capacity is ~5e-301, so every v = 0 crossing is a reversal and the motion is
// the frictionless forced response from rest, x = P (cos(w t) - cos(wn t)), P = F0/(k - m w^2).
// Tolerance 1e-7 of P: DP54 at rtol 1e-11 over 10 s; friction contributes ~1e-300.
TEST(ContactExtremes, VanishingNormalForceGivesTheFrictionlessResponse) {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 9.0;
  p.force_amplitude = 2.0;
  p.force_frequency = 1.3;
  p.normal_force = 1e-300;
  Sys sys(p, stickslip::CoulombContact<Law>(Law(0.5, 0.3)));
  const Eigen::Vector4d x0 = Eigen::Vector4d::Zero();
  const S mode0 = sys.consistent_mode(0.0, x0);
  ASSERT_EQ(mode0, S::SlipPositive);  // f_required = -F0 exceeds the capacity
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-14;
  EventLog log;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const double t_end = 10.0;
  const auto r = stepper.integrate(mode0, 0.0, x0, t_end, log);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_GE(log.events.size(), 4u);
  for (const auto& e : log.events) EXPECT_NE(e.to, S::Stick) << "t = " << e.t;
  const double P = p.force_amplitude / (p.stiffness - p.mass * 1.3 * 1.3);
  const double x_ref = P * (std::cos(1.3 * t_end) - std::cos(3.0 * t_end));
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_NEAR(r.x[0], x_ref, 1e-7 * std::abs(P));
  EXPECT_LT(r.x[3], 1e-290);  // dissipation ~ mu_k N * distance
}

// mu_s = mu_k on the belt: d = 0, so slip starts at the centre of the slip oscillation with
// x' = v_b, and x' returns to v_b (tangentially, a grazing contact) after a full period 2 pi/w.
// Whether or not the grazing is detected as an event, the motion must stay the harmonic cycle
// of amplitude v_b / w about x_k = mu N / k: sqrt((x - x_k)^2 + (x'/w)^2) = v_b / w always
// after the first slip, finite, never below x_k - v_b/w. Tolerance 1e-6 relative: an early stick
// (v within v_tol of 0 near the grazing point) perturbs it by at most ~v_tol / v_b = 1.5e-7.
TEST(ContactExtremes, EqualCoefficientsOnTheBeltGiveTheHarmonicCycle) {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 100.0;
  p.normal_force = 10.0;
  p.belt_speed = 0.1;
  const double mu = 0.4, w = 10.0, x_k = mu * 10.0 / 100.0, A = 0.1 / w;
  Sys sys(p, stickslip::CoulombContact<Law>(Law(mu, mu)));
  struct Log : EventLog {
    double x_k = 0, w = 1, A = 1, max_error = 0;
    bool slipped = false;
    bool on_step(double, const Eigen::Vector4d& x, const S& m) {
      slipped = slipped || m != S::Stick;
      if (slipped)
        max_error = std::max(max_error, std::abs(std::hypot(x[0] - x_k, x[1] / w) / A - 1));
      return true;
    }
  } log;
  log.x_k = x_k;
  log.w = w;
  log.A = A;
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-14;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const Eigen::Vector4d x0(x_k - 0.01, 0.1, 0, 0);  // stuck, reaches mu N / k at t = 0.1 s
  const auto r = stepper.integrate(S::Stick, 0.0, x0, 0.1 + 10 * 2 * kPi / w, log);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_FALSE(log.events.empty());
  EXPECT_NEAR(log.events[0].t, 0.1, 1e-9);
  EXPECT_TRUE(log.slipped);
  EXPECT_LT(log.max_error, 1e-6);
}

// Lift-off is reported, never hidden: N(t) = N0 + N1 cos(wN t) with N1 > N0 reaches 0 at
// t_L = acos(-N0/N1)/wN. The run stops there with Status::StoppedBySystem, mode LiftOff and a
// message naming lift-off: from stick without load (the capacity guards and N reach 0 together),
// from stick under load (the capacity is exceeded first at mu_s N = |f_required|, the mass slips,
// then N reaches 0) and from sliding (it sticks first at v = 0, then as before). Event time to 1e-9 s (event tolerance 1e-12 s).
TEST(ContactExtremes, LiftOffIsReportedAtTheTimeTheNormalForceVanishes) {
  struct Start {
    double load, v0;
    S first_event_to;
  };
  for (const Start& start : {Start{0.0, 0.0, S::LiftOff}, Start{0.3, 0.0, S::SlipPositive},
                             Start{0.0, 1.0, S::Stick}}) {
    SCOPED_TRACE("load " + std::to_string(start.load) + ", v0 " + std::to_string(start.v0));
    SingleDofParameters p;
    p.stiffness = 4.0;
    p.force_bias = start.load;
    p.normal_force = 2.0;
    p.normal_amplitude = 3.0;
    p.normal_frequency = 1.1;
    p.watch_lift_off = true;
    Sys sys(p, stickslip::CoulombContact<Law>(Law(0.5, 0.3)));
    const Eigen::Vector4d x0(0.0, start.v0, 0.0, 0.0);
    EventLog log;
    stickslip::StepperOptions<double> opt;
    opt.rtol = 1e-11;
    opt.atol = 1e-14;
    // While stuck the state is frozen (zero error estimate, so the step grows 5x per step) but
    // the guards move with N(t): the step must stay below the time scale of N, or a dip of the
    // capacity can fall between two step ends unseen.
    opt.max_step = 0.05;
    stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
    const auto r = stepper.integrate(sys.consistent_mode(0.0, x0), 0.0, x0, 10.0, log);
    EXPECT_EQ(r.status, stickslip::Status::StoppedBySystem);
    EXPECT_EQ(r.mode, S::LiftOff);
    EXPECT_NE(r.message.find("lift-off"), std::string::npos) << r.message;
    EXPECT_NEAR(r.t, std::acos(-2.0 / 3.0) / 1.1, 1e-9);
    ASSERT_FALSE(log.events.empty());
    EXPECT_EQ(log.events.front().to, start.first_event_to);
  }
}

}  // namespace
}  // namespace contact_coulomb_contact_extremes_test

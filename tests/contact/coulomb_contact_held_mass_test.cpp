// A mass held by static friction under a load below mu_s N: no drift at all while stuck (the
// exact laws), against the creep of a regularised law (closed form).

#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace contact_coulomb_contact_held_mass_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;

// Spring preloaded at x0, oscillating load and normal force: |f_required| = |k x0 - F(t)| stays
// <= 0.7 N while mu_s N(t) >= 0.5 * 6 = 3 N, so the mass must stay stuck forever.
SingleDofParameters held_mass() {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 40.0;
  p.force_bias = 0.2;
  p.force_amplitude = 0.5;
  p.force_frequency = 2.3;
  p.normal_force = 10.0;
  p.normal_amplitude = 4.0;
  p.normal_frequency = 1.7;
  return p;
}

// Checks at every accepted step that the state is bit-identical to the start.
struct NoDriftLog : EventLog {
  Eigen::Vector4d x0;
  long steps = 0, moved = 0;
  bool on_step(double, const Eigen::Vector4d& x, const S& m) {
    ++steps;
    if (m != S::Stick || x[0] != x0[0] || x[1] != 0.0 || x[2] != 0.0 || x[3] != 0.0) ++moved;
    return true;
  }
};

template <class Law, class Method>
void check_no_drift(const Law& law, const stickslip::StepperOptions<double>& opt, double t_end,
                    long min_steps) {
  using Sys = SingleDofOscillator<Law>;
  Sys sys(held_mass(), stickslip::CoulombContact<Law>(law));
  NoDriftLog log;
  log.x0 = Eigen::Vector4d(0.01, 0.0, 0.0, 0.0);
  ASSERT_EQ(sys.consistent_mode(0.0, log.x0), S::Stick);
  stickslip::HybridStepper<Sys, Method> stepper(sys, opt);
  const auto r = stepper.integrate(S::Stick, 0.0, log.x0, t_end, log);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.mode, S::Stick);
  EXPECT_TRUE(log.events.empty());
  EXPECT_GE(log.steps, min_steps);
  // Exact: not "small", zero. A creep of even one ulp per step would show here.
  EXPECT_EQ(log.moved, 0);
  EXPECT_EQ(r.x[0], log.x0[0]);
  EXPECT_EQ(r.x[1], 0.0);
}

TEST(HeldMass, NoDriftOverAMillionRungeKuttaSteps) {
  stickslip::StepperOptions<double> opt;
  opt.fixed_step = 1e-3;
  check_no_drift<stickslip::CoulombLaw<double>, stickslip::RungeKutta4>(
      stickslip::CoulombLaw<double>(0.5, 0.3), opt, 1000.0, 999'000);
}

TEST(HeldMass, NoDriftWithStribeckLawAndAdaptiveSteps) {
  stickslip::StepperOptions<double> opt;
  opt.max_step = 1e-2;  // many steps, so that creep per step would accumulate
  check_no_drift<stickslip::StribeckLaw<double>, stickslip::DormandPrince54>(
      stickslip::StribeckLaw<double>(0.5, 0.3, 1e-3), opt, 1000.0, 99'000);
}

// Extreme: a huge normal force holds against a large oscillating load; still exactly no motion.
TEST(HeldMass, HugeNormalForceNeverSlips) {
  using Law = stickslip::CoulombLaw<double>;
  using Sys = SingleDofOscillator<Law>;
  SingleDofParameters p = held_mass();
  p.force_amplitude = 1e6;
  p.normal_force = 1e12;
  p.normal_amplitude = 0.0;
  Sys sys(p, stickslip::CoulombContact<Law>(Law(0.5, 0.3)));
  EventLog log;
  const Eigen::Vector4d x0(0.01, 0.0, 0.0, 0.0);
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys);
  const auto r = stepper.integrate(S::Stick, 0.0, x0, 100.0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_TRUE(log.events.empty());
  EXPECT_EQ(r.x, x0);
}

// Extreme: a load exactly at the slip threshold, f_required = mu_s N (bit for bit), keeps the
// mass stuck: the capacity is a closed set (eq. 1: |f| <= mu_s N). No event, no motion.
TEST(HeldMass, LoadExactlyAtThresholdStaysStuck) {
  using Law = stickslip::CoulombLaw<double>;
  using Sys = SingleDofOscillator<Law>;
  SingleDofParameters p;
  p.stiffness = 0.0;
  p.normal_force = 10.0;
  p.force_bias = -0.5 * 10.0;  // f_required = -F = mu_s N exactly
  Sys sys(p, stickslip::CoulombContact<Law>(Law(0.5, 0.3)));
  const Eigen::Vector4d x0(0.25, 0.0, 0.0, 0.0);
  Eigen::VectorXd g(sys.num_guards(S::Stick));
  sys.guards(S::Stick, 0.0, x0, g);
  ASSERT_EQ(g[0], 0.0);
  ASSERT_EQ(sys.consistent_mode(0.0, x0), S::Stick);
  EventLog log;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys);
  const auto r = stepper.integrate(S::Stick, 0.0, x0, 50.0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_TRUE(log.events.empty());
  EXPECT_EQ(r.x, x0);
}

// Excitation crossing the threshold: F = -r t reaches -mu_s N at t* = mu_s N / r exactly; the
// mass then slips backward with m x'' = -r t + mu_k N, so
//   x(t) = x0 + [mu_k N (t - t*)^2 / 2 - r ((t^3 - t*^3)/6 - t*^2 (t - t*)/2)] / m.
// Tolerances: event time to the stepper's event tolerance (1e-12 s, checked at 1e-9 s); the
// position after slip to DP54's rtol = 1e-11 (checked at 1e-8 relative).
TEST(HeldMass, RampingLoadSlipsExactlyAtTheThreshold) {
  using Law = stickslip::CoulombLaw<double>;
  using Sys = SingleDofOscillator<Law>;
  SingleDofParameters p;
  p.mass = 2.0;
  p.stiffness = 0.0;
  p.normal_force = 10.0;
  p.force_rate = -0.7;
  const double mus = 0.5, muk = 0.3, N = 10.0, r_ = 0.7, m = 2.0;
  Sys sys(p, stickslip::CoulombContact<Law>(Law(mus, muk)));
  const Eigen::Vector4d x0(0.25, 0.0, 0.0, 0.0);
  EventLog log;
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-14;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const double t_star = mus * N / r_, t_end = t_star + 0.5;
  const auto r = stepper.integrate(S::Stick, 0.0, x0, t_end, log);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(log.events.size(), 1u);
  EXPECT_EQ(log.events[0].to, S::SlipNegative);
  EXPECT_NEAR(log.events[0].t, t_star, 1e-9);
  const double tau = t_end - t_star;
  const double x_ref =
      x0[0] + (muk * N * tau * tau / 2 -
               r_ * ((t_end * t_end * t_end - t_star * t_star * t_star) / 6 -
                     t_star * t_star * tau / 2)) / m;
  EXPECT_NEAR(r.x[0], x_ref, 1e-8 * std::abs(x_ref - x0[0]));
}

// The regularised law has no stick state: under a constant load F below mu N the mass creeps at
// the speed where mu N tanh(v / v_eps) = F, v = v_eps atanh(F / (mu N)) (the documented price).
// Tolerance 1e-8 relative: after 2e4 time constants m v_eps / (mu N) the transient is gone, and
// DP54 at rtol 1e-11 holds the steady speed far below that.
TEST(HeldMass, RegularisedLawCreepsAtTheClosedFormSpeed) {
  using Law = stickslip::RegularisedLaw<double>;
  using Sys = SingleDofOscillator<Law>;
  SingleDofParameters p;
  p.stiffness = 0.0;
  p.normal_force = 10.0;
  p.force_bias = 1.0;
  const double mu = 0.5, v_eps = 1e-4;
  Sys sys(p, stickslip::CoulombContact<Law>(Law(mu, v_eps)));
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-16;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const auto r = stepper.integrate(S::Stick, 0.0, Eigen::Vector4d::Zero(), 0.5);
  ASSERT_TRUE(r.ok()) << r.message;
  const double v_creep = v_eps * std::atanh(1.0 / (mu * 10.0));
  EXPECT_NEAR(r.x[1] / v_creep, 1.0, 1e-8);
  EXPECT_GT(r.x[0], 0.4 * v_creep);  // it moved: no true stick
}

}  // namespace
}  // namespace contact_coulomb_contact_held_mass_test

// ExactLinearStepper on the one-degree-of-freedom friction oscillators of the contact tests
// (piecewise linear with CoulombLaw), event by event against their piecewise closed forms:
// the belt-driven stick-slip cycle and Den Hartog's continuous sliding.

#include <stickslip/ode/exact_linear_stepper.hpp>

#include "contact/belt_cycle.hpp"
#include "contact/den_hartog_orbit.hpp"
#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ode_exact_friction_oscillators_test {  // named: the exact-stepper tests share a TU
namespace {

using contact_test::BeltCase;
using contact_test::BeltCycle;
using contact_test::DenHartogOrbit;
using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;
using Law = stickslip::CoulombLaw<double>;
using Oscillator = SingleDofOscillator<Law>;
constexpr double kPi = 3.14159265358979323846;

// Belt cycle (tests/contact/belt_cycle.hpp): stick for t_stick = 2 d / v_b from x_k - d to
// x_k + d, slip for t_slip back to x_k - d. Tolerances: event times are located to 1e-12 s on
// the exact solution; the closed form of t_slip itself is evaluated to ~1e-15; the guard in
// slip, v = x', has slope ~ w A at the stop, so the located time is off the closed form by
// < 1e-11 s after 2 x 8 events. Positions: on the guards up to the event-time bracket (1e-12 s)
// times the speed (<= w A = 10 A): 1e-11 A.
TEST(ExactLinearStepperFriction, BeltStickSlipCycleEventByEvent) {
  // (Not mu_k = 0: the cycle then re-sticks exactly on the stick boundary |k x| = mu_s N, and
  // stick or slip there is decided by round-off; both continue the same motion.)
  for (const BeltCase c : {BeltCase{0.5, 0.3, 0.1}, BeltCase{0.8, 0.2, 0.01},
                           BeltCase{0.4, 0.05, 0.3}}) {
    SingleDofParameters p;
    p.mass = 1.0;
    p.stiffness = 100.0;
    p.normal_force = 10.0;
    p.belt_speed = c.belt_speed;
    const BeltCycle ref(p.mass, p.stiffness, p.normal_force, c);
    Oscillator sys(p, stickslip::CoulombContact<Law>(Law(c.mu_s, c.mu_k)));
    const Eigen::Vector4d x0(ref.x_k - ref.d, c.belt_speed, 0, 0);
    EventLog log;
    const int cycles = 8;
    const double period = ref.t_stick + ref.t_slip;
    stickslip::ExactLinearStepper<Oscillator> stepper(sys);
    const auto r =
        stepper.integrate(S::Stick, 0.0, x0, cycles * period + ref.t_stick + 0.5 * ref.t_slip, log);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(log.events.size(), static_cast<std::size_t>(2 * cycles + 1));
    for (std::size_t i = 0; i < log.events.size(); ++i) {
      const auto& e = log.events[i];
      const double t_ref = static_cast<double>(i / 2) * period + ref.t_stick +
                           (i % 2 == 1 ? ref.t_slip : 0.0);
      EXPECT_NEAR(e.t, t_ref, 1e-11) << "event " << i << ", mu_s " << c.mu_s;
      if (i % 2 == 0) {
        ASSERT_EQ(e.to, S::SlipNegative);
        EXPECT_NEAR(e.x[0], ref.x_k + ref.d, 1e-11 * ref.A);
      } else {
        ASSERT_EQ(e.to, S::Stick);
        EXPECT_NEAR(e.x[0], ref.x_k - ref.d, 1e-11 * ref.A);
        EXPECT_EQ(e.x[1], c.belt_speed);
      }
    }
  }
}

// Den Hartog (tests/contact/den_hartog_orbit.hpp), started on the orbit: stops at t1 + k T/2 at
// x = +-X. Tolerances: the orbit's t1 and X come from closed-form trigonometry (~1e-15
// relative); event times are located to 1e-12 s and the slope of the guard v at a stop is
// |x''| ~ (k X - F) / m, not small; 1e-10 (relative to T and X) leaves a margin for the
// accumulation over 24 events, and a wrong force, phase or reversal is off by >= 1e-3.
TEST(ExactLinearStepperFriction, DenHartogContinuousSlidingEventByEvent) {
  const double m = 2.0, k = 50.0, F0 = 10.0, muk = 0.25;
  const double wn = std::sqrt(k / m);
  for (const double beta : {0.7, 1.3, 3.0}) {
    const double w = beta * wn, N = 0.3 * F0 / muk;
    const DenHartogOrbit ref(m, k, F0, w, muk * N, 1.1 * muk * N);
    ASSERT_TRUE(ref.valid) << "beta " << beta;
    SingleDofParameters p;
    p.mass = m;
    p.stiffness = k;
    p.force_amplitude = F0;
    p.force_frequency = w;
    p.normal_force = N;
    Oscillator sys(p, stickslip::CoulombContact<Law>(Law(1.1 * muk, muk)));
    const double t0 = ref.t1 + ref.T / 4;
    Eigen::Vector4d x0;
    ref.state(t0, x0[0], x0[1]);
    x0[2] = x0[3] = 0;
    struct Log : EventLog {
      const DenHartogOrbit* ref = nullptr;
      double max_error = 0;
      bool on_sample(double t, const Eigen::Vector4d& x, const S&) {
        double xr, vr;
        ref->state(t, xr, vr);
        max_error = std::max(max_error, std::abs(x[0] - xr) / ref->X);
        return true;
      }
    } log;
    log.ref = &ref;
    stickslip::StepperOptions<double> opt;
    opt.output_interval = ref.T / 64;
    const int periods = 12;
    stickslip::ExactLinearStepper<Oscillator> stepper(sys, opt);
    const auto r = stepper.integrate(S::SlipPositive, t0, x0, t0 + periods * ref.T, log);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(log.events.size(), static_cast<std::size_t>(2 * periods));
    const double first = ref.t1 + ref.T / 2;  // the first stop after t0: x = +X
    for (std::size_t i = 0; i < log.events.size(); ++i) {
      const auto& e = log.events[i];
      EXPECT_NEAR((e.t - first - static_cast<double>(i) * ref.T / 2) / ref.T, 0.0, 1e-10)
          << "beta " << beta << " event " << i;
      EXPECT_NEAR(e.x[0] / ref.X, i % 2 == 0 ? 1.0 : -1.0, 1e-10);
      EXPECT_EQ(e.to, i % 2 == 0 ? S::SlipNegative : S::SlipPositive);
    }
    EXPECT_LT(log.max_error, 1e-10) << "beta " << beta;
    std::printf("Den Hartog beta %.1f: waveform error %.2e, steps %ld, events %ld, rhs %ld\n",
                beta, log.max_error, r.stats.accepted_steps, r.stats.events,
                r.stats.rhs_evaluations);
  }
  static_cast<void>(kPi);
}

}  // namespace
}  // namespace ode_exact_friction_oscillators_test

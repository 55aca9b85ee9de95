// Mass on a spring dragged by a belt (mu_s > mu_k): the closed-form stick-slip limit cycle
// against CoulombContact + HybridStepper.
//
// m x'' + k x = f, v = x' - v_b. Stick: x' = v_b, f = k x, until k x = mu_s N (guard g0 falls:
// the belt cannot pull harder, the body slides backward, slip negative). Slip negative:
// f = +mu_k N, so x oscillates harmonically about x_k = mu_k N / k with w = sqrt(k/m), starting at
// x - x_k = d = (mu_s - mu_k) N / k with x' = v_b: amplitude A = sqrt(d^2 + (v_b/w)^2).
// Writing x - x_k = A cos(w tau + alpha) with cos(alpha) = d/A, sin(alpha) = -v_b/(w A),
// x' = v_b again at w tau = pi - 2 alpha, i.e.
//   t_slip = (pi + 2 atan(v_b / (w d))) / w,  at x = x_k - d (|k x| <= mu_s N: it sticks),
// then the belt carries it back from x_k - d to x_k + d:
//   t_stick = 2 d / v_b,   period T = t_stick + t_slip.
// (mu_k = 0 is included: x_k = 0, d = mu_s N / k.)

#include "contact/belt_cycle.hpp"
#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace contact_coulomb_contact_belt_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::BeltCase;
using contact_test::BeltCycle;
using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;
using Law = stickslip::CoulombLaw<double>;
using Belt = SingleDofOscillator<Law>;
constexpr double kPi = 3.14159265358979323846;


// Records events and the slip amplitude invariant sqrt((x - x_k)^2 + (x'/w)^2) at every step.
struct BeltLog : EventLog {
  double x_k = 0, w = 1, A = 1, max_amplitude_error = 0;
  long slip_steps = 0;
  bool on_step(double, const Eigen::Vector4d& x, const S& m) {
    if (m == S::SlipNegative) {
      const double a = std::hypot(x[0] - x_k, x[1] / w);
      max_amplitude_error = std::max(max_amplitude_error, std::abs(a / A - 1));
      ++slip_steps;
    }
    return true;
  }
};

// m = 1 kg, k = 100 N/m, N = 10 N (w = 10 rad/s), the belt speed of the case.
SingleDofParameters belt_parameters(const BeltCase& c) {
  SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 100.0;
  p.normal_force = 10.0;
  p.belt_speed = c.belt_speed;
  return p;
}

template <class Method>
void check_belt_cycle(const BeltCase& c, stickslip::StepperOptions<double> opt) {
  const SingleDofParameters p = belt_parameters(c);
  const BeltCycle ref(p.mass, p.stiffness, p.normal_force, c);
  Belt sys(p, stickslip::CoulombContact<Law>(Law(c.mu_s, c.mu_k)));

  // Start where the cycle re-sticks: x = x_k - d, moving with the belt.
  const Eigen::Vector4d x0(ref.x_k - ref.d, c.belt_speed, 0, 0);
  ASSERT_EQ(sys.consistent_mode(0.0, x0), S::Stick);
  BeltLog log;
  log.x_k = ref.x_k;
  log.w = std::sqrt(p.stiffness / p.mass);
  log.A = ref.A;
  const int cycles = 8;
  const double period = ref.t_stick + ref.t_slip;
  stickslip::HybridStepper<Belt, Method> stepper(sys, opt);
  const auto r = stepper.integrate(S::Stick, 0.0, x0, cycles * period + ref.t_stick + 0.5 * ref.t_slip, log);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(log.events.size(), static_cast<std::size_t>(2 * cycles + 1));

  // Tolerance 1e-6 relative (the issue's): the integration and event location errors are
  // ~1e-10 here (rtol 1e-11 / RK4 with w h = 0.01), so 1e-6 is met with margin, while a wrong
  // stick capacity, wrong kinetic force or a missed projection onto v = 0 is off by O(1).
  const double tol = 1e-6;
  double stick_start = 0.0;
  for (std::size_t i = 0; i < log.events.size(); ++i) {
    const auto& e = log.events[i];
    if (i % 2 == 0) {  // stick -> slip negative at x = x_k + d = mu_s N / k
      ASSERT_EQ(e.from, S::Stick);
      ASSERT_EQ(e.to, S::SlipNegative);
      EXPECT_NEAR((e.t - stick_start) / ref.t_stick, 1.0, tol) << "stick duration, event " << i;
      EXPECT_NEAR(e.x[0] / (ref.x_k + ref.d), 1.0, tol);
      if (i >= 2) {
        EXPECT_NEAR((e.t - log.events[i - 2].t) / period, 1.0, tol) << "period, event " << i;
      }
    } else {  // slip negative -> stick at x = x_k - d
      ASSERT_EQ(e.from, S::SlipNegative);
      ASSERT_EQ(e.to, S::Stick);
      EXPECT_NEAR((e.t - log.events[i - 1].t) / ref.t_slip, 1.0, tol) << "slip, event " << i;
      EXPECT_NEAR(e.x[0] - (ref.x_k - ref.d), 0.0, tol * ref.A);
      EXPECT_EQ(e.x[1], c.belt_speed);  // projected exactly onto v = 0
      stick_start = e.t;
    }
  }
  EXPECT_GT(log.slip_steps, 10 * cycles);
  EXPECT_LT(log.max_amplitude_error, tol);
}

stickslip::StepperOptions<double> tight_dp54() {
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-14;
  return opt;
}

TEST(BeltStickSlip, LimitCycleMatchesClosedFormDormandPrince) {
  check_belt_cycle<stickslip::DormandPrince54>({0.5, 0.3, 0.1}, tight_dp54());
}

TEST(BeltStickSlip, LimitCycleMatchesClosedFormSlowBeltLargeStaticExcess) {
  check_belt_cycle<stickslip::DormandPrince54>({0.8, 0.2, 0.01}, tight_dp54());
}

// Extreme mu_k = 0: the slip phase is a free oscillation about x = 0.
TEST(BeltStickSlip, LimitCycleMatchesClosedFormWithZeroKineticFriction) {
  check_belt_cycle<stickslip::DormandPrince54>({0.4, 0.0, 0.3}, tight_dp54());
}

// The paper's method: fixed-step RK4 with bisection event location.
TEST(BeltStickSlip, LimitCycleMatchesClosedFormRungeKutta4Bisection) {
  stickslip::StepperOptions<double> opt;
  opt.fixed_step = 1e-3;
  opt.event_location = stickslip::EventLocation::Bisection;
  check_belt_cycle<stickslip::RungeKutta4>({0.5, 0.3, 0.1}, opt);
}

// "A stop read as a velocity reversal": with large RK4 steps the state handed to
// the transition at the end of a slip was past v = 0 by the dense-output error (3e-8 ... 1.7e-7),
// above the contact's velocity tolerance sqrt(eps), and decide() read it as a reversal (slip
// positive) where the body sticks: every second event was wrong. Now the stepper hands over a
// state on v = 0 to |v'| event_time_tolerance, and the oscillator decides a slip whose velocity
// guard fired at rest (decide_at_rest). The event sequence must be the closed form's:
// stick -> slip negative -> stick ..., as many switches as the closed form has in [0, t_end].
template <class Method>
void check_belt_sequence(const BeltCase& c, stickslip::StepperOptions<double> opt,
                         const std::string& what) {
  const SingleDofParameters p = belt_parameters(c);
  const BeltCycle ref(p.mass, p.stiffness, p.normal_force, c);
  Belt sys(p, stickslip::CoulombContact<Law>(Law(c.mu_s, c.mu_k)));
  const Eigen::Vector4d x0(ref.x_k - ref.d, c.belt_speed, 0, 0);
  EventLog log;
  stickslip::HybridStepper<Belt, Method> stepper(sys, opt);
  // 6.5 periods: the end falls inside a slip, far (0.5 t_slip) from any switch.
  const double period = ref.t_stick + ref.t_slip;
  const auto r = stepper.integrate(S::Stick, 0.0, x0, 6 * period + ref.t_stick + 0.5 * ref.t_slip, log);
  ASSERT_TRUE(r.ok()) << what << ": " << r.message;
  ASSERT_EQ(log.events.size(), 13u) << what;
  for (std::size_t i = 0; i < log.events.size(); ++i) {
    const bool from_stick = i % 2 == 0;
    EXPECT_EQ(log.events[i].from, from_stick ? S::Stick : S::SlipNegative) << what << ", event " << i;
    EXPECT_EQ(log.events[i].to, from_stick ? S::SlipNegative : S::Stick) << what << ", event " << i;
  }
}

TEST(BeltStickSlip, StopIsNotReadAsAReversalAtLargeSteps) {
  for (const BeltCase c : {BeltCase{0.6, 0.3, 0.1}, BeltCase{0.4, 0.3, 0.1}}) {
    for (double h : {0.05, 0.02, 0.01}) {  // w h = 0.5, 0.2, 0.1
      stickslip::StepperOptions<double> opt;
      opt.fixed_step = h;
      check_belt_sequence<stickslip::RungeKutta4>(c, opt, "RK4 h = " + std::to_string(h));
    }
    for (double rtol : {1e-3, 1e-4}) {
      stickslip::StepperOptions<double> opt;
      opt.rtol = rtol;
      opt.atol = rtol * 1e-2;
      check_belt_sequence<stickslip::DormandPrince54>(c, opt,
                                                      "DOPRI rtol = " + std::to_string(rtol));
    }
  }
}

}  // namespace
}  // namespace contact_coulomb_contact_belt_test

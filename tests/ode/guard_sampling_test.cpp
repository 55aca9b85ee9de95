// StepperOptions::guard_samples: a guard that crosses and crosses back inside one step is seen
// when an interior sample of the dense output falls inside the excursion, and the event is then
// located as at a step end. Without samples the step-end sign test misses it (docs/ode.md, "Event
// semantics"); the references below are closed forms, not the stepper's own output.

#include <stickslip/ode.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace ode_guard_sampling_test {  // named: the ode test files share one (unity) translation unit
namespace {

using stickslip::CrossingDirection;
using stickslip::DormandPrince54;
using stickslip::EventLocation;
using stickslip::HybridStepper;
using stickslip::RungeKutta4;
using stickslip::StepperOptions;
using stickslip::TransitionAction;
using stickslip::TriggeredGuards;

/// x' = 1 from x(0) = 0 with the guard g = (x - c)^2 - d^2 (Falling): an excursion below zero
/// over x in (c - d, c + d), entered at t = c - d. The transition stops the run there. Every
/// method integrates x' = 1 exactly, so the event time is c - d to the event time tolerance.
struct Excursion {
  using Scalar = double;
  using State = Eigen::Matrix<double, 1, 1>;
  using Mode = int;
  double c = 0.5, d = 0.1;
  void rhs(const Mode&, double, const State&, State& dxdt) const { dxdt[0] = 1.0; }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
    g[0] = (x[0] - c) * (x[0] - c) - d * d;
  }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const { return CrossingDirection::Falling; }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State&) const {
    ++m;
    return TransitionAction::halt("entered the excursion");
  }
};

template <class Method>
stickslip::HybridResult<double, Excursion::State, int> run_excursion(long samples, EventLocation where,
                                                                     double step) {
  Excursion sys;
  StepperOptions<double> opt;
  opt.fixed_step = step;        // RK4
  opt.initial_step = step;      // Dormand-Prince: the first step spans the excursion ...
  opt.rtol = 1e-3;              // ... and is accepted (its error is zero on x' = 1)
  opt.guard_samples = samples;
  opt.event_location = where;
  HybridStepper<Excursion, Method> stepper(sys, opt);
  return stepper.integrate(0, 0.0, Excursion::State::Zero(), 2.0);
}

TEST(GuardSampling, StepEndSignTestAloneMissesAnExcursionInsideOneStep) {
  // The documented limit that the option lifts: one step of 1 over (0.4, 0.6), g > 0 at both ends.
  const auto r = run_excursion<RungeKutta4>(0, EventLocation::DenseRootFinding, 1.0);
  EXPECT_EQ(r.status, stickslip::Status::Success);
  EXPECT_EQ(r.stats.events, 0);
}

TEST(GuardSampling, InteriorSampleFindsTheExcursionAndLocatesItsEntry) {
  // Three samples per step (at 1/4, 1/2, 3/4 of a step of 1): the one at x = 0.5 is inside the
  // excursion. The entry c - d = 0.4 is located to the event time tolerance (1e-12) plus the
  // round-off of g near its root (|g'| = 2 d = 0.2): bound 1e-11.
  for (EventLocation where : {EventLocation::DenseRootFinding, EventLocation::Bisection}) {
    SCOPED_TRACE(stickslip::to_string(where));
    const auto rk = run_excursion<RungeKutta4>(3, where, 1.0);
    EXPECT_EQ(rk.status, stickslip::Status::StoppedBySystem) << rk.message;
    EXPECT_NEAR(rk.t, 0.4, 1e-11);
    EXPECT_EQ(rk.stats.guard_sample_cuts, 1);
    const auto dp = run_excursion<DormandPrince54>(3, where, 1.0);
    EXPECT_EQ(dp.status, stickslip::Status::StoppedBySystem) << dp.message;
    EXPECT_NEAR(dp.t, 0.4, 1e-11);
    EXPECT_EQ(dp.stats.guard_sample_cuts, 1);
  }
  // Samples that all fall outside the excursion (one sample per step at 1/2 of a step of 1.6:
  // x = 0.8) cannot see it: the option narrows the blind spot to the sample spacing, no more.
  const auto coarse = run_excursion<RungeKutta4>(1, EventLocation::DenseRootFinding, 1.6);
  EXPECT_EQ(coarse.stats.events, 0);
}

/// The harmonic oscillator x = sin t (x'' = -x, x(0) = 0, x'(0) = 1) with the guard 0.98 - x
/// (Falling): x exceeds 0.98 for t in (asin 0.98, pi - asin 0.98), a window of 0.40 around pi / 2.
struct Peak {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double level = 0.98;
  void rhs(const Mode&, double, const State& x, State& dxdt) const { dxdt << x[1], -x[0]; }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = level - x[0]; }
  CrossingDirection guard_direction(const Mode&, Eigen::Index) const { return CrossingDirection::Falling; }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double, State&) const {
    ++m;
    return TransitionAction::halt("peak");
  }
};

/// One classical RK4 step of size tau on x' = A x (A = [0 1; -1 0]) is the matrix polynomial
/// I + tau A + (tau A)^2 / 2 + (tau A)^3 / 6 + (tau A)^4 / 24 applied to x: the method's own
/// solution in closed form, independent of the stepper's code.
Eigen::Vector2d rk4_step(const Eigen::Vector2d& x, double tau) {
  Eigen::Matrix2d A;
  A << 0, 1, -1, 0;
  const Eigen::Matrix2d B = tau * A;
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() + B + B * B / 2 + B * B * B / 6 + B * B * B * B / 24;
  return P * x;
}

TEST(GuardSampling, RungeKutta4LargeStepsSeeThePeakOfAnOscillator) {
  // Fixed steps of 0.9: the grid points 0.9 and 1.8 both lie below the level (sin 0.9 = 0.78,
  // sin 1.8 = 0.97), so the step-end test misses the peak; four samples per step (spacing 0.18
  // < 0.40) see it.
  StepperOptions<double> opt;
  opt.fixed_step = 0.9;
  Peak sys;
  HybridStepper<Peak, RungeKutta4> blind(sys, opt);
  EXPECT_EQ(blind.integrate(0, 0.0, Eigen::Vector2d(0, 1), 1.8).stats.events, 0);

  opt.guard_samples = 4;
  HybridStepper<Peak, RungeKutta4> sampled(sys, opt);
  const auto r = sampled.integrate(0, 0.0, Eigen::Vector2d(0, 1), 1.8);
  ASSERT_EQ(r.status, stickslip::Status::StoppedBySystem) << r.message;
  // Reference: the root of 0.98 - x(tau) on the RK4 step from the grid point 0.9 (the event
  // state is re-integrated with the method from the step start), found here by bisection on the
  // closed-form step to 1e-14. The stepper brackets it to 1e-12 (event_time_tolerance).
  const Eigen::Vector2d x09 = rk4_step(Eigen::Vector2d(0, 1), 0.9);
  double lo = 0.0, hi = 0.9;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (sys.level - rk4_step(x09, mid)[0] < 0 ? hi : lo) = mid;
  }
  EXPECT_NEAR(r.t, 0.9 + hi, 1e-11);
  // and the method's root lies near the exact one, asin 0.98 (RK4's error at steps of 0.9 and
  // 0.47, a few 1e-3 in x, divided by |x'| = cos(asin 0.98) = 0.2): within 0.05.
  EXPECT_NEAR(r.t, std::asin(0.98), 0.05);
}

TEST(GuardSampling, RejectsANegativeOrHugeSampleCount) {
  Peak sys;
  StepperOptions<double> opt;
  for (long bad : {-1L, 1001L}) {
    opt.guard_samples = bad;
    try {
      HybridStepper<Peak, RungeKutta4> s(sys, opt);
      FAIL() << "no exception for " << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("guard_samples"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace ode_guard_sampling_test

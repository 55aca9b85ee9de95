// Tests of HybridStepper against closed-form answers.

#include <stickslip/ode.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "ode/ode_test_systems.hpp"

namespace {

using stickslip::DormandPrince54;
using stickslip::EventLocation;
using stickslip::EventRecord;
using stickslip::HybridStepper;
using stickslip::RungeKutta4;
using stickslip::Status;
using stickslip::StepperOptions;
using stickslip::test::BouncingBall;

struct ImpactRecorder : stickslip::NullObserver {
  std::vector<double> times;
  void on_event(const EventRecord<double, int>& e) { times.push_back(e.t); }
};

template <class Method>
void check_ball_impacts(EventLocation location, double fixed_step) {
  BouncingBall ball;
  StepperOptions<double> opt;
  opt.event_location = location;
  opt.fixed_step = fixed_step;
  opt.event_time_tolerance = 1e-12;
  HybridStepper<BouncingBall, Method> stepper(ball, opt);
  ImpactRecorder rec;
  const double h0 = 1.0;
  const double t_end = ball.impact_time(10, h0) + 0.01;
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(h0, 0.0), t_end, rec);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  ASSERT_EQ(rec.times.size(), 10u);
  EXPECT_EQ(r.mode, 10);
  EXPECT_EQ(r.stats.events, 10);
  // y(t) is quadratic: RK4, Dormand-Prince and both dense outputs reproduce it exactly, so the
  // impact times are limited by the 1e-12 location tolerance plus round-off of a few hundred
  // steps; 1e-10 is the requirement.
  for (int k = 1; k <= 10; ++k)
    EXPECT_NEAR(rec.times[static_cast<std::size_t>(k - 1)], ball.impact_time(k, h0), 1e-10)
        << "impact " << k;
}

TEST(HybridStepperBall, DormandPrinceRootFindingHitsClosedFormImpactTimes) {
  check_ball_impacts<DormandPrince54>(EventLocation::DenseRootFinding, 1e-4);
}
TEST(HybridStepperBall, DormandPrinceBisectionHitsClosedFormImpactTimes) {
  check_ball_impacts<DormandPrince54>(EventLocation::Bisection, 1e-4);
}
TEST(HybridStepperBall, RungeKutta4RootFindingHitsClosedFormImpactTimes) {
  check_ball_impacts<RungeKutta4>(EventLocation::DenseRootFinding, 1e-2);
}
TEST(HybridStepperBall, RungeKutta4BisectionHitsClosedFormImpactTimes) {
  check_ball_impacts<RungeKutta4>(EventLocation::Bisection, 1e-2);
}

}  // namespace

namespace {

using stickslip::test::Oscillator;

TEST(HybridStepperEvents, OscillatorZerosMatchClosedFormWithTightTolerances) {
  Oscillator osc;
  StepperOptions<double> opt;
  opt.rtol = 1e-12;
  opt.atol = 1e-14;
  HybridStepper<Oscillator> stepper(osc, opt);
  ImpactRecorder rec;
  const double pi = std::acos(-1.0);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 10.0, rec);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  const auto expected = static_cast<std::size_t>(std::floor(10.0 * osc.omega / pi + 0.5));
  ASSERT_EQ(rec.times.size(), expected);
  // rtol 1e-12 gives a global error of about 1e-12 in x over ten periods; the zero of
  // cos(omega t) moves by error / omega, so 1e-10 leaves a margin of 100.
  for (std::size_t k = 0; k < rec.times.size(); ++k)
    EXPECT_NEAR(rec.times[k], (static_cast<double>(k) + 0.5) * pi / osc.omega, 1e-10);
  EXPECT_NEAR(r.x[0], std::cos(osc.omega * 10.0), 1e-10);
}

TEST(HybridStepperStatus, NonFiniteRightHandSideStopsAtTheRightTime) {
  Oscillator osc;
  osc.nan_after = 0.5;
  HybridStepper<Oscillator> dp(osc);
  const auto r = dp.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 2.0);
  EXPECT_EQ(r.status, Status::NonFiniteState);
  // The step halves towards the first non-finite evaluation until it is below
  // min_step = 1e-14 (relative to max(1, |t|)), so the reported time is within a few min_step.
  EXPECT_NEAR(r.t, 0.5, 1e-12) << r.message;
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_NE(r.message.find("non-finite at t = 0.49999999999"), std::string::npos) << r.message;

  StepperOptions<double> opt;
  opt.fixed_step = 1e-3;
  HybridStepper<Oscillator, RungeKutta4> rk4(osc, opt);
  const auto r4 = rk4.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 2.0);
  EXPECT_EQ(r4.status, Status::NonFiniteState);
  EXPECT_NEAR(r4.t, 0.5, 1e-12) << r4.message;
}

// Without guards nothing but the stepper's finiteness check of the step's state and derivative
// sees a NaN: RK4 has no error estimate (it returns 0), so a non-finite step would otherwise be
// accepted and the run would end "successfully" with a NaN state.
TEST(HybridStepperStatus, NonFiniteStepOfAnUnguardedFixedStepRunIsReported) {
  Oscillator osc;
  osc.nan_after = 0.5;
  osc.guarded = false;
  StepperOptions<double> opt;
  opt.fixed_step = 1e-3;
  HybridStepper<Oscillator, RungeKutta4> rk4(osc, opt);
  const auto r = rk4.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 2.0);
  EXPECT_EQ(r.status, Status::NonFiniteState) << r.message;
  // (halving from the fixed step down to min_step, as in the guarded case above)
  EXPECT_NEAR(r.t, 0.5, 1e-12) << r.message;
  EXPECT_TRUE(r.x.allFinite());
  // The state it returns is the exact flow's to RK4 accuracy: (h omega)^4 / 120 per unit time
  // with h = 1e-3, omega = 3 is ~1e-12; 1e-9 leaves room for the halved last steps.
  EXPECT_NEAR(r.x[0], std::cos(osc.omega * r.t), 1e-9);
}

TEST(HybridStepperStatus, MaxStepsEndsTheRunWithItsStatus) {
  Oscillator osc;
  StepperOptions<double> opt;
  opt.fixed_step = 1e-3;
  opt.max_steps = 100;
  HybridStepper<Oscillator, RungeKutta4> rk4(osc, opt);
  const auto r = rk4.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 1.0);
  EXPECT_EQ(r.status, Status::MaxSteps);
  // 100 fixed steps of 1e-3 from t = 0 (no event before t = pi/6).
  EXPECT_NEAR(r.t, 0.1, 1e-12);
  EXPECT_EQ(r.stats.accepted_steps, 100);
}

}  // namespace

namespace {

struct HaltAfter {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  BouncingBall ball;
  int max_bounces = 3;
  void rhs(const Mode& m, double t, const State& x, State& d) const { ball.rhs(m, t, x, d); }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    ball.guards(m, t, x, g);
  }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return ball.guard_direction(m, i);
  }
  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards& w, double t,
                                         State& x) const {
    ball.transition(m, w, t, x);
    if (m >= max_bounces) return stickslip::TransitionAction::halt("enough bounces");
    return stickslip::TransitionAction::proceed();
  }
};

TEST(HybridStepperStatus, SystemCanHaltTheRunWithAReason) {
  HaltAfter sys;
  HybridStepper<HaltAfter> stepper(sys);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 100.0);
  EXPECT_EQ(r.status, Status::StoppedBySystem);
  EXPECT_EQ(r.mode, 3);
  EXPECT_NEAR(r.t, sys.ball.impact_time(3, 1.0), 1e-10);  // closed form, as in the ball tests
  EXPECT_NE(r.message.find("enough bounces"), std::string::npos) << r.message;
  EXPECT_STREQ(to_string(r.status), "stopped_by_system");
}

TEST(HybridStepperStatus, ObserverCanStopTheRun) {
  struct StopAfter : stickslip::NullObserver {
    int steps = 0;
    bool on_step(double, const Eigen::Vector2d&, const int&) { return ++steps < 5; }
  } obs;
  Oscillator osc;
  StepperOptions<double> opt;
  opt.fixed_step = 0.01;
  HybridStepper<Oscillator, RungeKutta4> stepper(osc, opt);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 1.0, obs);
  EXPECT_EQ(r.status, Status::StoppedByObserver);
  EXPECT_NEAR(r.t, 0.05, 1e-15);
  EXPECT_EQ(obs.steps, 5);
}

TEST(HybridStepperStatus, StepSizeUnderflowAtAFiniteTimeBlowUp) {
  // x' = x^2 from x(0) = 1 blows up at t = 1: the error control shrinks the step below
  // min_step * max(1, |t|) = 1e-14 before the state overflows.
  using Riccati = stickslip::test::Riccati;
  struct BlowUp : Riccati {
    void rhs(const Mode&, double, const State& x, State& d) const { d[0] = x[0] * x[0]; }
  } sys;
  HybridStepper<BlowUp> stepper(sys);
  const auto r = stepper.integrate(0, 0.0, BlowUp::State(1.0), 2.0);
  ASSERT_EQ(r.status, Status::StepSizeUnderflow) << r.message;
  // The numerical solution blows up where 1/x reaches 0; its relative error, accumulated under
  // rtol = 1e-6, shifts that time by O(rtol) (measured 3e-7).
  EXPECT_NEAR(r.t, 1.0, 1e-5);
  EXPECT_NE(r.message.find("fell below min_step"), std::string::npos) << r.message;
  EXPECT_GT(r.stats.rejected_steps, 0);
}

TEST(HybridStepperStatus, InvalidOptionsAndArgumentsThrowNamingTheParameter) {
  Oscillator osc;
  StepperOptions<double> opt;
  opt.rtol = -1.0;
  try {
    HybridStepper<Oscillator> stepper(osc, opt);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("HybridStepper: options.rtol"), std::string::npos);
  }
  HybridStepper<Oscillator> stepper(osc);
  EXPECT_THROW(stepper.integrate(0, 1.0, Eigen::Vector2d(1.0, 0.0), 0.5), std::invalid_argument);
  EXPECT_THROW(stepper.integrate(0, 0.0, Eigen::Vector2d(NAN, 0.0), 1.0), std::invalid_argument);
}

TEST(HybridStepperObservers, SamplesAtAFixedRateThroughTheDenseOutput) {
  // Samples at t = 0, 0.1, ..., 2 (21 of them) on cos(3 t), across events (x = 0 crossings,
  // transition leaves the state alone) and independent of the steps taken.
  struct Samples : stickslip::NullObserver {
    std::vector<double> t, x;
    long steps = 0;
    bool on_sample(double ts, const Eigen::Vector2d& xs, const int&) {
      t.push_back(ts);
      x.push_back(xs[0]);
      return true;
    }
    bool on_step(double, const Eigen::Vector2d&, const int&) { return ++steps > 0; }
  } obs;
  Oscillator osc;
  StepperOptions<double> opt;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.output_interval = 0.1;
  HybridStepper<Oscillator> stepper(osc, opt);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 2.0, obs);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  ASSERT_EQ(obs.t.size(), 21u);
  for (std::size_t k = 0; k < obs.t.size(); ++k) {
    EXPECT_NEAR(obs.t[k], 0.1 * static_cast<double>(k), 1e-15);
    // Dense-output error ~ rtol; 1e-8 leaves room for the global error over 2 s.
    EXPECT_NEAR(obs.x[k], std::cos(3.0 * obs.t[k]), 1e-8) << "t = " << obs.t[k];
  }
  EXPECT_EQ(obs.steps, r.stats.accepted_steps);
  EXPECT_GT(r.stats.events, 0);
}

}  // namespace

namespace {

template <int N>
using Linear = stickslip::test::LinearSystem<N>;

// Samples of x[0] at the output times, for any state type.
struct FirstComponentSamples : stickslip::NullObserver {
  std::vector<double> t, x;
  template <class State>
  bool on_sample(double ts, const State& xs, const int&) {
    t.push_back(ts);
    x.push_back(xs[0]);
    return true;
  }
};

template <int N>
stickslip::HybridResult<double, typename Linear<N>::State, int> run_oscillator(
    FirstComponentSamples& obs) {
  Linear<N> sys;
  sys.a = Linear<N>::Matrix::Zero(2, 2);
  sys.a(0, 1) = 1.0;
  sys.a(1, 0) = -9.0;
  StepperOptions<double> opt;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  opt.output_interval = 0.1;
  HybridStepper<Linear<N>, DormandPrince54> stepper(sys, opt);
  typename Linear<N>::State x0 = Linear<N>::State::Zero(2);
  x0[0] = 1.0;
  return stepper.integrate(0, 0.0, x0, 2.0, obs);
}

TEST(HybridStepperSteps, SmallFixedAndDynamicStatesTakeTheSameStepsAndDenseOutput) {
  // x'' = -9 x, x = cos(3 t). A small fixed-size state keeps the Dormand-Prince stages in locals
  // and a dynamic one in the method's workspace; the arithmetic is the same, so both must take
  // the same steps, and both dense outputs must follow the closed form.
  FirstComponentSamples fixed_obs, dynamic_obs;
  const auto rf = run_oscillator<2>(fixed_obs);
  const auto rd = run_oscillator<Eigen::Dynamic>(dynamic_obs);
  ASSERT_EQ(rf.status, Status::Success) << rf.message;
  ASSERT_EQ(rd.status, Status::Success) << rd.message;
  EXPECT_EQ(rf.stats.accepted_steps, rd.stats.accepted_steps);
  EXPECT_EQ(rf.stats.rejected_steps, rd.stats.rejected_steps);
  EXPECT_EQ(rf.stats.rhs_evaluations, rd.stats.rhs_evaluations);
  ASSERT_EQ(fixed_obs.x.size(), 21u);
  ASSERT_EQ(dynamic_obs.x.size(), 21u);
  for (std::size_t k = 0; k < fixed_obs.x.size(); ++k) {
    // Dense-output error ~ rtol; 1e-8 leaves room for the global error over 2 s.
    EXPECT_NEAR(fixed_obs.x[k], std::cos(3.0 * fixed_obs.t[k]), 1e-8) << "t = " << fixed_obs.t[k];
    // Same operations on the same numbers (vectorised differently): equal to a few ulp.
    EXPECT_NEAR(fixed_obs.x[k], dynamic_obs.x[k], 1e-14) << "t = " << fixed_obs.t[k];
  }
}

TEST(HybridStepperTolerances, PureRelativeControlWithAnExactlyZeroComponent) {
  // x' = -x, y' = 0 from (1, 0) with atol = 0: y stays exactly 0 and its error weight is 0. An
  // exactly zero error there counts 0 (not 0/0), so the run succeeds on the x error alone.
  Linear<2> sys;
  sys.a << -1.0, 0.0, 0.0, 0.0;
  StepperOptions<double> opt;
  opt.rtol = 1e-10;
  opt.atol = 0.0;
  HybridStepper<Linear<2>, DormandPrince54> stepper(sys, opt);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 1.0);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  // Local relative error <= rtol per step over a few dozen steps: 1e-8 is a wide margin.
  EXPECT_NEAR(r.x[0], std::exp(-1.0), 1e-8);
  EXPECT_EQ(r.x[1], 0.0);
}

}  // namespace

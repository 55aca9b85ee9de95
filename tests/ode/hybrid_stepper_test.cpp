// Tests of HybridStepper against closed-form answers.

#include <stickslip/ode.hpp>

#include <gtest/gtest.h>

#include <cmath>
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

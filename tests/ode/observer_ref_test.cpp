// ObserverRef: the same run seen through a reference as through the observer itself (the
// bouncing ball's closed-form impact times), both on_event forms, and a false from on_sample
// stopping the run at that sample.

#include <stickslip/ode.hpp>
#include <stickslip/ode/observer_ref.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ode/ode_test_systems.hpp"

namespace observer_ref_test {

using stickslip::EventRecord;
using stickslip::test::BouncingBall;
using Ref = stickslip::ObserverRef<double, BouncingBall::State, int>;

struct RecordOnly : stickslip::NullObserver {  // on_event(record) only
  std::vector<double> times;
  void on_event(const EventRecord<double, int>& e) { times.push_back(e.t); }
};

struct WithState : stickslip::NullObserver {  // on_event(record, x_after) and samples
  std::vector<double> rebound_speeds, samples;
  double stop_after = 1e300;
  void on_event(const EventRecord<double, int>&, const BouncingBall::State& x) {
    rebound_speeds.push_back(x[1]);
  }
  bool on_sample(double t, const BouncingBall::State&, const int&) {
    samples.push_back(t);
    return t < stop_after;
  }
};

TEST(ObserverRef, ForwardsEventsOfBothFormsAsTheObserverItselfSeesThem) {
  BouncingBall ball;
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  const BouncingBall::State x0(1.0, 0.0);
  RecordOnly direct, referred;
  stickslip::HybridStepper<BouncingBall> stepper(ball, opt);
  stepper.integrate(0, 0.0, x0, 2.0, direct);
  Ref ref(referred);
  stepper.integrate(0, 0.0, x0, 2.0, ref);
  ASSERT_GE(direct.times.size(), 3u);
  ASSERT_EQ(referred.times, direct.times);  // the same run: bitwise the same event times
  // Located to the event tolerance of the dense output: 1e-9 s is far above it and far below the
  // spacing of the impacts (0.36 s).
  for (std::size_t k = 0; k < referred.times.size(); ++k)
    EXPECT_NEAR(referred.times[k], ball.impact_time(static_cast<int>(k) + 1, 1.0), 1e-9);

  WithState with_state;
  Ref ref2(with_state);
  stepper.integrate(0, 0.0, x0, 2.0, ref2);
  ASSERT_EQ(with_state.rebound_speeds.size(), direct.times.size());
  // After impact k the ball leaves at e^k sqrt(2 g h0) (restitution e, energy of a fall from h0).
  const double v1 = std::sqrt(2.0 * ball.gravity);
  for (std::size_t k = 0; k < with_state.rebound_speeds.size(); ++k)
    EXPECT_NEAR(with_state.rebound_speeds[k], std::pow(ball.restitution, double(k + 1)) * v1, 1e-8);
}

TEST(ObserverRef, FalseFromOnSampleStopsTheRunAtThatSample) {
  BouncingBall ball;
  stickslip::StepperOptions<double> opt;
  opt.output_interval = 0.1;
  WithState obs;
  obs.stop_after = 0.25;
  Ref ref(obs);
  stickslip::HybridStepper<BouncingBall> stepper(ball, opt);
  const auto r = stepper.integrate(0, 0.0, BouncingBall::State(1.0, 0.0), 2.0, ref);
  EXPECT_EQ(r.status, stickslip::Status::StoppedByObserver);
  ASSERT_EQ(obs.samples.size(), 4u);  // 0, 0.1, 0.2, 0.3: the first sample past 0.25 says stop
  // The run ends with the step that produced that sample (HybridStepper reports the step's end).
  EXPECT_GE(r.t, 0.3);
  EXPECT_LT(r.t, 0.4);
}

}  // namespace observer_ref_test

// Event semantics of HybridStepper: step-boundary events, several crossings in one step, guards at
// zero when a mode starts, grazing, Zeno, and the Illinois root finder itself.

#include <stickslip/ode.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "ode/ode_test_systems.hpp"

namespace {

using stickslip::CrossingDirection;
using stickslip::DormandPrince54;
using stickslip::EventLocation;
using stickslip::EventRecord;
using stickslip::HybridStepper;
using stickslip::RungeKutta4;
using stickslip::Status;
using stickslip::StepperOptions;
using stickslip::TriggeredGuards;
using stickslip::test::BouncingBall;
using stickslip::test::Ramp;

struct EventLog : stickslip::NullObserver {
  std::vector<double> times;
  std::vector<TriggeredGuards> guards;
  template <class Mode>
  void on_event(const EventRecord<double, Mode>& e) {
    times.push_back(e.t);
    guards.push_back(*e.triggered);
  }
};

const EventLocation kLocations[] = {EventLocation::DenseRootFinding, EventLocation::Bisection};

TEST(IllinoisRoot, ClosesTheBracketAroundTheRootOfACubic) {
  // Root of t^3 - 2 t - 5 (Newton's classic): 2.0945514815423265...
  const double root = 2.0945514815423265;
  auto phi = [](double t) { return -(t * t * t - 2.0 * t - 5.0); };
  const auto br = stickslip::detail::illinois_root(phi, 2.0, phi(2.0), 3.0, phi(3.0), 1e-13);
  EXPECT_LE(br.hi - br.lo, 1e-13);
  EXPECT_LE(br.lo, root + 1e-15);
  EXPECT_GE(br.hi, root - 1e-15);
  EXPECT_GE(phi(br.lo), 0.0);
  EXPECT_LT(phi(br.hi), 0.0);
  // Superlinear: far fewer evaluations than the 44 halvings of bisection to 1e-13.
  EXPECT_LT(br.evaluations, 15);
}

// newton_root on the same cubic with its exact slope: the same bracket contract, in far fewer
// evaluations than Illinois (quadratic convergence from the Hermite start, then one point to
// close the bracket). The bound 6 leaves room for two Newton steps beyond the usual three.
TEST(NewtonRoot, ClosesTheBracketAroundTheRootOfACubicInFewerEvaluationsThanIllinois) {
  const double root = 2.0945514815423265;
  auto f = [](double t) { return -(t * t * t - 2.0 * t - 5.0); };
  auto fs = [](double t, double& slope) {
    slope = -(3.0 * t * t - 2.0);
    return -(t * t * t - 2.0 * t - 5.0);
  };
  const auto illinois = stickslip::detail::illinois_root(f, 2.0, f(2.0), 3.0, f(3.0), 1e-13);
  for (bool end_slopes : {true, false}) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double slo = end_slopes ? -(3.0 * 4.0 - 2.0) : nan;
    const double shi = end_slopes ? -(3.0 * 9.0 - 2.0) : nan;
    const auto br = stickslip::detail::newton_root(fs, 2.0, f(2.0), slo, 3.0, f(3.0), shi, 1e-13);
    EXPECT_LE(br.hi - br.lo, 1e-13);
    EXPECT_LE(br.lo, root + 1e-15);
    EXPECT_GE(br.hi, root - 1e-15);
    EXPECT_GE(f(br.lo), 0.0);
    EXPECT_LT(f(br.hi), 0.0);
    EXPECT_LE(br.evaluations, 6) << "end slopes " << end_slopes;
    EXPECT_LT(br.evaluations, illinois.evaluations) << "end slopes " << end_slopes;
  }
}

// The slope only steers: with a slope of the wrong sign, none at all (NaN), or at a triple root
// (phi = -(t - r)^3, where Newton converges only linearly and |phi| falls by 8/27 per step) the
// iteration falls back to bisection and still closes a valid bracket.
TEST(NewtonRoot, BadSlopesAndATripleRootStillCloseAValidBracket) {
  const double r = 0.3141592653589793;
  struct Case {
    const char* name;
    double (*value)(double);
    double (*slope)(double);
  };
  const Case cases[] = {
      {"wrong sign", [](double t) { return std::cos(t) - 0.2; },
       [](double t) { return std::sin(t); }},
      {"no slope", [](double t) { return std::cos(t) - 0.2; },
       [](double) { return std::numeric_limits<double>::quiet_NaN(); }},
      {"triple root", [](double t) { return -std::pow(t - 0.3141592653589793, 3); },
       [](double t) { return -3.0 * std::pow(t - 0.3141592653589793, 2); }},
  };
  for (const Case& c : cases) {
    auto fs = [&](double t, double& s) {
      s = c.slope(t);
      return c.value(t);
    };
    const double lo = c.value(0.0) > 0 && c.value(2.0) < 0 ? 0.0 : -1.0;
    const double hi = 2.0;
    ASSERT_GE(c.value(lo), 0.0) << c.name;
    ASSERT_LT(c.value(hi), 0.0) << c.name;
    const auto br = stickslip::detail::newton_root(fs, lo, c.value(lo), c.slope(lo), hi,
                                                   c.value(hi), c.slope(hi), 1e-12);
    EXPECT_LE(br.hi - br.lo, 1e-12) << c.name;
    EXPECT_GE(c.value(br.lo), 0.0) << c.name;
    EXPECT_LT(c.value(br.hi), 0.0) << c.name;
    // Bisection alone takes ceil(log2(3 / 1e-12)) = 42 evaluations; where Newton is rejected
    // every second evaluation bisects, so at most about twice that (the triple root: 63).
    EXPECT_LE(br.evaluations, 2 * 42 + 4) << c.name;
    const double expected = std::string(c.name) == "triple root" ? r : std::acos(0.2);
    // The bracket holds the root: t - r is exact near r (Sterbenz), so the cube's sign is exact;
    // cos is within an ulp, i.e. ~1e-16 in t at slope ~1.
    EXPECT_NEAR(0.5 * (br.lo + br.hi), expected, 1e-12) << c.name;
  }
}

TEST(EventSemantics, EventExactlyOnAStepBoundaryIsReportedOnceJustAfterIt) {
  // RK4 with h = 1/8 lands exactly on t = 0.5 where g = x - 0.5 is exactly zero. Zero is not past
  // the crossing: the next step sees g > 0 and places the event within the tolerance after 0.5.
  for (EventLocation loc : kLocations) {
    Ramp ramp{{1.0}, {0.5}, {CrossingDirection::Rising}};
    StepperOptions<double> opt;
    opt.fixed_step = 0.125;
    opt.event_location = loc;
    HybridStepper<Ramp, RungeKutta4> stepper(ramp, opt);
    EventLog log;
    const auto r = stepper.integrate(0u, 0.0, Ramp::State(0.0), 1.0, log);
    ASSERT_EQ(r.status, Status::Success) << r.message;
    ASSERT_EQ(log.times.size(), 1u) << to_string(loc);
    EXPECT_GE(log.times[0], 0.5);
    EXPECT_LE(log.times[0], 0.5 + opt.event_time_tolerance);
  }
}

TEST(EventSemantics, TwoCrossingsInOneStepAreTakenEarliestFirst) {
  // One RK4 step of 1 covers crossings at 0.3 (guard 1) and 0.6 (guard 0): two events, in time
  // order, each reporting only its guard. RK4 and its Hermite output are exact for x = t.
  for (EventLocation loc : kLocations) {
    Ramp ramp{{1.0, 1.0}, {0.6, 0.3}, {CrossingDirection::Rising, CrossingDirection::Rising}};
    StepperOptions<double> opt;
    opt.fixed_step = 1.0;
    opt.event_location = loc;
    HybridStepper<Ramp, RungeKutta4> stepper(ramp, opt);
    EventLog log;
    const auto r = stepper.integrate(0u, 0.0, Ramp::State(0.0), 1.0, log);
    ASSERT_EQ(r.status, Status::Success) << r.message;
    ASSERT_EQ(log.times.size(), 2u) << to_string(loc);
    EXPECT_NEAR(log.times[0], 0.3, 2e-12);
    EXPECT_NEAR(log.times[1], 0.6, 2e-12);
    EXPECT_EQ(log.guards[0], TriggeredGuards{1});
    EXPECT_EQ(log.guards[1], TriggeredGuards{0});
    EXPECT_EQ(r.mode, 3u);
    EXPECT_DOUBLE_EQ(r.x[0], 1.0);
  }
}

TEST(EventSemantics, SimultaneousCrossingsAreReportedTogether) {
  // g0 = x - 0.4 and g1 = 2 x - 0.8 cross at the same instant; g2 = x - 0.4 + 1e-9 a
  // nanosecond later (not within the 1e-12 tolerance): one event {0, 1}, then one {2}.
  for (EventLocation loc : kLocations) {
    Ramp ramp{{1.0, 2.0, 1.0},
              {0.4, 0.8, 0.4 + 1e-9},
              {CrossingDirection::Rising, CrossingDirection::Rising, CrossingDirection::Either}};
    StepperOptions<double> opt;
    opt.event_location = loc;
    HybridStepper<Ramp> stepper(ramp, opt);
    EventLog log;
    const auto r = stepper.integrate(0u, 0.0, Ramp::State(0.0), 1.0, log);
    ASSERT_EQ(r.status, Status::Success) << r.message;
    ASSERT_EQ(log.times.size(), 2u) << to_string(loc);
    EXPECT_EQ(log.guards[0], (TriggeredGuards{0, 1}));
    EXPECT_EQ(log.guards[1], TriggeredGuards{2});
    EXPECT_NEAR(log.times[0], 0.4, 2e-12);
    EXPECT_NEAR(log.times[1], 0.4 + 1e-9, 2e-12);
  }
}

TEST(EventSemantics, GuardAtZeroLeavingIntoItsSafeSideDoesNotRetrigger) {
  // Ball on the floor (y = 0 exactly) thrown up with v = 5: no event at t0, the first impact at
  // t = 2 v / g (closed form; y is quadratic, integrated exactly).
  BouncingBall ball;
  HybridStepper<BouncingBall> stepper(ball);
  EventLog log;
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(0.0, 5.0), 1.1, log);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  ASSERT_EQ(log.times.size(), 1u);
  EXPECT_NEAR(log.times[0], 2.0 * 5.0 / ball.gravity, 1e-11);
}

TEST(EventSemantics, GuardAtZeroLeavingIntoItsTriggeringSideIsAnImmediateEvent) {
  // Ball on the floor moving down (v = -5): the guard y = 0 leaves zero into its triggering
  // direction; the event fires when y passes -guard_zero_tolerance, i.e. at t = 1e-12 / 5.
  BouncingBall ball;
  HybridStepper<BouncingBall> stepper(ball);
  EventLog log;
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(0.0, -5.0), 1.0, log);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  ASSERT_GE(log.times.size(), 1u);
  const double z = stepper.options().guard_zero_tolerance;
  EXPECT_NEAR(log.times[0], z / 5.0, stepper.options().event_time_tolerance);
  // After the bounce (v = +4) the next impact is 2 * 4 / g later.
  ASSERT_EQ(log.times.size(), 2u);
  EXPECT_NEAR(log.times[1] - log.times[0], 2.0 * 4.0 / ball.gravity, 1e-11);
}

TEST(EventSemantics, GrazingGuardIsNotAnEvent) {
  // g = (x - 1)^2 touches zero at t = 1 without changing sign: no event, whatever the direction.
  for (CrossingDirection d : {CrossingDirection::Falling, CrossingDirection::Either}) {
    struct Touch : Ramp {
      void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
        g[0] = (x[0] - 1.0) * (x[0] - 1.0);
      }
    };
    Touch touch;
    touch.weight = {1.0};
    touch.level = {0.0};
    touch.direction = {d};
    HybridStepper<Touch> stepper(touch);
    EventLog log;
    const auto r = stepper.integrate(0u, 0.0, Touch::State(0.0), 2.0, log);
    ASSERT_EQ(r.status, Status::Success) << r.message;
    EXPECT_EQ(log.times.size(), 0u);
  }
}

TEST(EventSemantics, CrossAndReturnWithinOneStepIsMissedAsDocumented) {
  // g = (x - 1.05)^2 - 1e-6 is negative only on (1.049, 1.051). RK4 steps of 0.1 see g > 0 at
  // both ends and miss it (every step-end sign test does); steps below the dip width find both
  // crossings (Falling at 1.049, then Rising at 1.051 as Ramp toggles the direction).
  struct Dip : Ramp {
    void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
      g[0] = (x[0] - 1.05) * (x[0] - 1.05) - 1e-6;
    }
  };
  Dip dip;
  dip.weight = {1.0};
  dip.level = {0.0};
  dip.direction = {CrossingDirection::Falling};
  StepperOptions<double> opt;
  opt.fixed_step = 0.1;
  HybridStepper<Dip, RungeKutta4> coarse(dip, opt);
  EventLog missed;
  coarse.integrate(0u, 0.0, Dip::State(0.0), 1.55, missed);
  EXPECT_EQ(missed.times.size(), 0u);
  opt.fixed_step = 1e-3;
  HybridStepper<Dip, RungeKutta4> fine(dip, opt);
  EventLog found;
  fine.integrate(0u, 0.0, Dip::State(0.0), 1.55, found);
  ASSERT_EQ(found.times.size(), 2u);
  // x = t exactly; the roots 1.05 -+ 1e-3 carry the round-off of evaluating g near them.
  EXPECT_NEAR(found.times[0], 1.049, 1e-11);
  EXPECT_NEAR(found.times[1], 1.051, 1e-11);
}

TEST(ZenoGuard, BallWithRestitutionBelowOneEndsNearTheAccumulationPoint) {
  // e = 0.5 from 1 m: impacts accumulate at t_inf = t1 + (2 v1 / g) e / (1 - e). Once the bounce
  // height falls below guard_zero_tolerance, every impact is an immediate event and the run ends
  // with ZenoGuard instead of stepping forever.
  BouncingBall ball;
  ball.restitution = 0.5;
  const double t1 = std::sqrt(2.0 / ball.gravity), v1 = ball.gravity * t1;
  const double t_inf = t1 + 2.0 * v1 / ball.gravity * 0.5 / (1.0 - 0.5);
  for (EventLocation loc : kLocations) {
    StepperOptions<double> opt;
    opt.event_location = loc;
    HybridStepper<BouncingBall> stepper(ball, opt);
    const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 10.0);
    EXPECT_EQ(r.status, Status::ZenoGuard) << r.message;
    // The geometric series of flight times reaches t_inf to within the last flight times
    // (1e-6 s for heights of 1e-12 m) plus 100 immediate events of about that duration.
    EXPECT_GT(r.t, t_inf - 1e-5);
    EXPECT_LT(r.t, t_inf + 1e-3);
    EXPECT_NE(r.message.find("Zeno"), std::string::npos);
    EXPECT_LT(r.stats.events, 500);
  }
}

TEST(ZenoGuard, EventRateCapEndsTheRun) {
  // Elastic ball (e = 1) bouncing from 1 m: impacts at 0.452 s, then every 2 v1 / g = 0.903 s.
  // Allowing at most 3 events within 3 s stops it at the 4th impact (3.16 - 0.45 < 3).
  BouncingBall ball;
  ball.restitution = 1.0;
  StepperOptions<double> opt;
  opt.zeno_max_events = 3;
  opt.zeno_window = 3.0;
  HybridStepper<BouncingBall> stepper(ball, opt);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 10.0);
  EXPECT_EQ(r.status, Status::ZenoGuard) << r.message;
  EXPECT_EQ(r.stats.events, 4);
  EXPECT_NEAR(r.t, ball.impact_time(4, 1.0), 1e-10);
}

TEST(ZenoGuard, GuardThatRetriggersAfterATransitionEndsTheRun) {
  // The transition leaves the mode and state unchanged although the guard has crossed: the guard
  // keeps leaving zero in its triggering direction - a chain of immediate events.
  stickslip::test::Oscillator osc;
  osc.direction = CrossingDirection::Falling;
  HybridStepper<stickslip::test::Oscillator> stepper(osc);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 10.0);
  EXPECT_EQ(r.status, Status::ZenoGuard) << r.message;
  const double pi = std::acos(-1.0);
  // rtol = 1e-6 (default) on x = cos(3 t) shifts the zero by about 1e-7 / 3.
  EXPECT_NEAR(r.t, pi / (2.0 * osc.omega), 1e-6);
  // The first (regular) event, then the chain of immediate ones up to the cap.
  EXPECT_EQ(r.stats.events, stepper.options().zeno_max_immediate_events + 2);
}

}  // namespace

// ExactLinearStepper in a mode with a nonlinear remainder: the dense output of the Lawson
// Dormand-Prince step (samples and event location inside a step), against a closed-form solution.

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

namespace ode_exact_dense_output_test {  // named: the exact-stepper tests share a TU
namespace {

// q'' = -w2^2 q and p' = -p^2 with the linear part of a *detuned* oscillator, A = [[0, 1, 0],
// [-w^2, 0, 0], [0, 0, 0]], w != w2: the remainder (0, (w^2 - w2^2) q, -p^2) is of the size of
// the linear part and nonlinear in p. Closed form from (1, 0, p0): q = cos(w2 t),
// q' = -w2 sin(w2 t), p = p0 / (1 + p0 t). Optional guard g = q (Falling) that stops the run, at
// t* = pi / (2 w2).
class Detuned {
 public:
  using Scalar = double;
  using State = Eigen::Vector3d;
  using Mode = int;

  Detuned(double w, double w2, bool guarded) : w_(w), w2_(w2), guarded_(guarded) {}

  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w2_ * w2_ * x[0], -x[2] * x[2];
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.setZero(3, 3);
    lp.A(0, 1) = 1;
    lp.A(1, 0) = -w_ * w_;
    lp.b0.setZero(3);
    lp.omega.clear();
    lp.exact = false;
    lp.version = 1;
    return true;
  }
  Eigen::Index num_guards(const Mode&) const { return guarded_ ? 1 : 0; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const {
    if (guarded_) g[0] = x[0];
  }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Falling;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::halt("q reached 0");
  }

  State exact(double t, double p0) const {
    return State(std::cos(w2_ * t), -w2_ * std::sin(w2_ * t), p0 / (1 + p0 * t));
  }

 private:
  double w_, w2_;
  bool guarded_;
};

// Largest error against the closed form at the samples and at the step ends.
struct Errors : stickslip::NullObserver {
  const Detuned* sys = nullptr;
  double p0 = 0;
  std::vector<double> sample_t, sample_err;
  double step_err = 0;
  bool on_sample(double t, const Eigen::Vector3d& x, const int&) {
    sample_t.push_back(t);
    sample_err.push_back((x - sys->exact(t, p0)).lpNorm<Eigen::Infinity>());
    return true;
  }
  bool on_step(double t, const Eigen::Vector3d& x, const int&) {
    step_err = std::max(step_err, (x - sys->exact(t, p0)).lpNorm<Eigen::Infinity>());
    return true;
  }
};

constexpr double kW = 2.0, kW2 = 2.5, kP0 = 0.5;

// Steps of length h, all accepted (tolerances 1e6), samples every `interval` (0: none).
stickslip::StepperOptions<double> steps_of_length(double h, double interval) {
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e6;
  opt.atol = 1e6;
  opt.initial_step = h;
  opt.max_step = h;
  opt.output_interval = interval;
  return opt;
}

// One step of length h from the exact initial state, samples at theta = 1/3 and 2/3: their error
// is the local error of the continuous extension alone. Dormand-Prince's extension has order 4,
// i.e. local error O(h^5) (the step end's is O(h^6)); in the frame of Â it keeps that order
// (exp(theta h Â) carries w's error unchanged in size). Measured orders 4.9-5.0 for h = 0.4 ..
// 0.05 (errors 1.6e-5 .. 5e-10, far above round-off); asserted in [4.5, 5.5]: a wrong
// coefficient, a stage in the wrong frame or exp(Â h) instead of exp(theta h Â) gives <= 2, and
// re-taken trial steps (order 5, local O(h^6)) would measure ~6.
TEST(ExactLinearStepperDenseOutput, ContinuousExtensionHasLocalErrorOrderFive) {
  Detuned sys(kW, kW2, false);
  std::vector<double> err;
  for (double h : {0.4, 0.2, 0.1, 0.05}) {
    stickslip::ExactLinearStepper<Detuned> stepper(sys, steps_of_length(h, h / 3));
    Errors log;
    log.sys = &sys;
    log.p0 = kP0;
    const auto r = stepper.integrate(0, 0.0, sys.exact(0.0, kP0), h, log);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.stats.accepted_steps, 1);
    ASSERT_GE(log.sample_err.size(), 3u);
    EXPECT_EQ(stepper.work().dense_outputs, 2) << "h " << h;
    EXPECT_EQ(r.stats.rhs_evaluations, 1 + 6) << "h " << h << ": the samples re-took steps";
    err.push_back(std::max(log.sample_err[1], log.sample_err[2]));
  }
  for (std::size_t i = 0; i + 1 < err.size(); ++i) {
    const double order = std::log2(err[i] / err[i + 1]);
    std::printf("dense output, one step: errors %.3e -> %.3e: order %.2f\n", err[i], err[i + 1],
                order);
    EXPECT_GT(order, 4.5);
    EXPECT_LT(order, 5.5);
  }
}

// A run under error control (rtol 1e-9) with samples every 0.01 (about 4 per step): every sample
// comes from the dense output (no right-hand-side evaluation beyond the steps': 1 + 6 per step
// attempt), and the samples are accurate to the tolerance: the extension's local error is
// O(h^5) like the embedded estimate that the step control holds below atol + rtol |x| (~2.5e-9
// here), so the sample errors are of that size (measured 8.2e-9 against the closed form over 6 s,
// 2.4 periods; the step ends, with local extrapolation, 7.2e-10). Asserted below 10x the
// tolerance, 2.5e-8: an extension of order 2 would leave ~h^3 ~ 1e-4 at these steps (~0.04).
TEST(ExactLinearStepperDenseOutput, SamplesInsideStepsCostNoRightHandSideAndKeepTheAccuracy) {
  Detuned sys(kW, kW2, false);
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-9;
  opt.atol = 1e-12;
  opt.output_interval = 0.01;
  stickslip::ExactLinearStepper<Detuned> stepper(sys, opt);
  Errors log;
  log.sys = &sys;
  log.p0 = kP0;
  const auto r = stepper.integrate(0, 0.0, sys.exact(0.0, kP0), 6.0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  const double max_sample = *std::max_element(log.sample_err.begin(), log.sample_err.end());
  std::printf("%ld steps (%ld rejected), %zu samples, %ld from the dense output; largest error "
              "at samples %.2e, at step ends %.2e\n",
              r.stats.accepted_steps, r.stats.rejected_steps, log.sample_err.size(),
              stepper.work().dense_outputs, max_sample, log.step_err);
  EXPECT_EQ(log.sample_err.size(), 601u);
  EXPECT_GT(stepper.work().dense_outputs, 500);
  EXPECT_EQ(r.stats.rhs_evaluations, 1 + 6 * (r.stats.accepted_steps + r.stats.rejected_steps));
  EXPECT_LT(log.step_err, 1e-8);  // the run itself is accurate (rtol 1e-9 over 2.4 periods)
  EXPECT_LT(max_sample, 10 * (opt.atol + opt.rtol * kW2));
}

// Event inside a Lawson step: g = q crosses zero at t* = pi / (2 w2). Located on the dense output;
// with EventState::Reintegrate the root is moved onto re-taken steps of the method (counted in
// event_reintegrations), with DenseOutput not. Either way the event time is within 1e-9 s of t*
// (rtol 1e-10: a state error ~1e-10 moves the root by ~1e-10 / |q'| = 4e-11 s; the bracket closes
// to 1e-12 s) and the handed state is past the guard.
TEST(ExactLinearStepperDenseOutput, EventInsideALawsonStepIsLocatedOnTheDenseOutput) {
  Detuned sys(kW, kW2, true);
  const double t_star = 3.14159265358979323846 / (2 * kW2);
  for (auto state : {stickslip::EventState::Reintegrate, stickslip::EventState::DenseOutput}) {
    stickslip::StepperOptions<double> opt;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.event_state = state;
    stickslip::ExactLinearStepper<Detuned> stepper(sys, opt);
    const auto r = stepper.integrate(0, 0.0, sys.exact(0.0, kP0), 2.0);
    const char* name = stickslip::to_string(state);
    ASSERT_EQ(r.status, stickslip::Status::StoppedBySystem) << name << ": " << r.message;
    EXPECT_NEAR(r.t, t_star, 1e-9) << name;
    EXPECT_LT(r.x[0], 0.0) << name;
    EXPECT_GT(stepper.work().dense_outputs, 0) << name;
    if (state == stickslip::EventState::Reintegrate)
      EXPECT_GT(stepper.work().event_reintegrations, 0);
    else
      EXPECT_EQ(stepper.work().event_reintegrations, 0);
    std::printf("%s: event at t* %+.2e s, %ld dense points, %ld re-taken steps\n", name,
                r.t - t_star, stepper.work().dense_outputs, stepper.work().event_reintegrations);
  }
}

// Regression (found on the blade runs): a step length whose propagator set was first created by
// the dense output (holding only exp(-h Â)) never got its five stage propagators, so every later
// step of that length carried its stages along the ladder instead. Fixed steps of one length h on
// one Â (all accepted, Â never refreshed), once without samples and once with a
// sample inside every step (interval 0.7 h, so the first falls in the first step, before the
// second step asks for the stage propagators). Reference: the run without samples, whose count
// of Padé exponentials is the mode's ladder plus the five stage propagators of h; the run with
// samples adds exactly one, exp(-h Â) of the dense output (before the fix it had the ladder and
// that one only: 3 against 8). With the stage propagators a carried vector costs one product:
// 5 + (1 + .. + 5) = 20 per step, plus the dense output's and the samples' (measured 45 products
// per step; 139 before the fix, where each of the 20 carried vectors walked the ladder). Asserted
// below 70 per step, between the two.
TEST(ExactLinearStepperDenseOutput, DenseOutputOnEveryStepKeepsTheStagePropagatorsOfItsLength) {
  Detuned sys(kW, kW2, false);
  const double h = 0.05, t_end = 2.0;
  const auto run = [&](double interval) {
    stickslip::ExactLinearStepper<Detuned> stepper(sys, steps_of_length(h, interval));
    Errors log;
    log.sys = &sys;
    log.p0 = kP0;
    const auto r = stepper.integrate(0, 0.0, sys.exact(0.0, kP0), t_end, log);
    EXPECT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.stats.accepted_steps, 40);
    EXPECT_EQ(stepper.work().linear_part_refreshes, 0);
    return std::make_pair(stepper.work(), r.stats.accepted_steps);
  };
  const auto bare = run(0.0);
  const auto sampled = run(0.7 * h);
  std::printf("Padé exponentials: %ld without samples, %ld with; products per step %.1f, %.1f; "
              "%ld dense outputs\n",
              bare.first.propagator_exponentials, sampled.first.propagator_exponentials,
              static_cast<double>(bare.first.matvecs) / static_cast<double>(bare.second),
              static_cast<double>(sampled.first.matvecs) / static_cast<double>(sampled.second),
              sampled.first.dense_outputs);
  EXPECT_GT(sampled.first.dense_outputs, 30);
  EXPECT_EQ(sampled.first.propagator_exponentials, bare.first.propagator_exponentials + 1);
  EXPECT_LT(sampled.first.matvecs, 70 * sampled.second);
}

}  // namespace
}  // namespace ode_exact_dense_output_test

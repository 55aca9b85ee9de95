// ExactLinearStepper at the limits of its time axis (found by a probe of the exponential path):
// samples that cannot advance or are more than options.max_samples are refused at once, as by
// HybridStepper (before, the first looped on samples at t0 and the second ignored max_samples);
// a step that t + h cannot resolve ends the run with StepSizeUnderflow at once (before, the
// exact modes' grid step spun with a clock standing still until max_steps).

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ode_exact_run_limits_test {  // named: the exact-stepper tests share one unity TU
namespace {

// x'' = -w^2 x with a guard g = x + c (Falling) that an amplitude below c never fires. `exact`:
// the linear part is the whole right-hand side (an exact mode) or declared inexact (the Lawson
// method integrates it, with a zero remainder).
class QuietOscillator {
 public:
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;

  QuietOscillator(double w, bool exact) : w_(w), exact_(exact) {}
  void rhs(const Mode&, double, const State& x, State& dxdt) const { dxdt << x[1], -w_ * w_ * x[0]; }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0] + 10.0; }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Falling;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::halt("the guard fired");
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.resize(2, 2);
    lp.A << 0, 1, -w_ * w_, 0;
    lp.b0.setZero(2);
    lp.omega.clear();
    lp.exact = exact_;
    lp.Gx.resize(0, 0);
    return true;
  }

 private:
  double w_;
  bool exact_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string refusal(double t0, double t_end, const stickslip::StepperOptions<double>& opt) {
  QuietOscillator sys(1.0, true);
  stickslip::ExactLinearStepper<QuietOscillator> stepper(sys, opt);
  try {
    stepper.integrate(0, t0, Eigen::Vector2d(1.0, 0.0), t_end);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ExactLinearStepperRunLimits, TooManySamplesAreRefusedNamingMaxSamples) {
  stickslip::StepperOptions<double> opt;
  opt.output_interval = 1e-6;
  opt.max_samples = 1000;  // 1e6 + 1 samples asked over [0, 1]
  const auto start = std::chrono::steady_clock::now();
  const std::string what = refusal(0.0, 1.0, opt);
  EXPECT_NE(what.find("options.output_interval"), std::string::npos) << what;
  EXPECT_NE(what.find("options.max_samples"), std::string::npos) << what;
  opt.output_interval = 1e-13;  // 1e13 samples: refused before any is emitted
  opt.max_samples = 100000000;
  EXPECT_NE(refusal(0.0, 1.0, opt).find("options.max_samples"), std::string::npos);
  EXPECT_LT(seconds_since(start), 1.0);  // at once, not after emitting samples
}

TEST(ExactLinearStepperRunLimits, SampleIntervalBelowTheResolutionOfTIsRefused) {
  stickslip::StepperOptions<double> opt;
  opt.output_interval = 0.01;  // t0 + k dt == t0 for every k at |t| = 1e300
  const auto start = std::chrono::steady_clock::now();
  const std::string what = refusal(1e300, 1e300, opt);
  EXPECT_NE(what.find("options.output_interval"), std::string::npos) << what;
  EXPECT_NE(what.find("resolution"), std::string::npos) << what;
  EXPECT_LT(seconds_since(start), 1.0);
}

// w = 1e3: guard sampling step 2 pi / (8 w) = 7.9e-4 s. At t = 1e13 the smallest step t + h
// resolves (min_step * |t| = 0.1 s with the default min_step 1e-14) is far longer: the run must
// stop at its start with StepSizeUnderflow naming min_step, in the exact and in the Lawson
// branch alike. At t = 1e3 the same scene runs and matches cos(w (t - t0)): the exact modes'
// products and the Lawson steps (rtol 1e-10) hold ~1e-9 over 0.1 s there (1e-7 leaves a margin
// for the clock's resolution at t = 1e3, ~1e-13 s, times w per step).
TEST(ExactLinearStepperRunLimits, StepThatTheClockCannotResolveStopsWithStepSizeUnderflow) {
  for (bool exact : {true, false}) {
    SCOPED_TRACE(exact ? "exact mode" : "Lawson steps");
    const double w = 1e3;
    QuietOscillator sys(w, exact);
    stickslip::StepperOptions<double> opt;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    opt.max_steps = 100000;
    stickslip::ExactLinearStepper<QuietOscillator> stepper(sys, opt);
    const auto start = std::chrono::steady_clock::now();
    const auto r = stepper.integrate(0, 1e13, Eigen::Vector2d(1.0, 0.0), 1e13 + 1.0);
    EXPECT_LT(seconds_since(start), 1.0);
    EXPECT_EQ(r.status, stickslip::Status::StepSizeUnderflow) << r.message;
    EXPECT_EQ(r.t, 1e13);
    EXPECT_LE(r.stats.accepted_steps, 1);
    EXPECT_NE(r.message.find("min_step"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("at t = "), std::string::npos) << r.message;

    const double t0 = 1e3, t1 = t0 + 0.1;
    const auto ok = stepper.integrate(0, t0, Eigen::Vector2d(1.0, 0.0), t1);
    ASSERT_TRUE(ok.ok()) << ok.message;
    EXPECT_NEAR(ok.x[0], std::cos(w * (t1 - t0)), 1e-7);
    EXPECT_NEAR(ok.x[1], -w * std::sin(w * (t1 - t0)), 1e-7 * w);
  }
}

}  // namespace
}  // namespace ode_exact_run_limits_test

// ExactLinearStepper: a guard that dips below zero between two guard samples (grazing) is
// located, not missed; a guard that only comes close is not an event.

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace ode_exact_grazing_test {  // named: the exact-stepper tests share one unity TU
namespace {

// x'' = -w^2 x, x(0) = a cos(phi0), x'(0) = -a w sin(phi0); guard g = x + c (Falling), so
// g(t) = a cos(w t + phi0) + c. With c = a (1 - eps) the guard is below zero only for
// |w t + phi0 - pi| < acos(1 - eps) ~ sqrt(2 eps): 2.8e-3 rad for eps = 1e-6, while the guard
// samples are pi/4 rad apart (1/8 of the period) and, with phi0 = 0.3, none falls in the dip.
// The transition stops the run, so that the result holds the event.
/// One guard g = x[0] + c (Falling) whose event stops the run (the guard part of the systems below).
class GuardOnX {
 public:
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;

  explicit GuardOnX(double c) : c_(c) {}
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0] + c_; }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Falling;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::halt("reached");
  }

 protected:
  double c_;
};

class Grazer : public GuardOnX {
 public:
  Grazer(double w, double c, bool affine) : GuardOnX(c), w_(w), affine_(affine) {}

  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w_ * w_ * x[0];
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.resize(2, 2);
    lp.A << 0, 1, -w_ * w_, 0;
    lp.b0.setZero(2);
    lp.omega.clear();
    lp.exact = true;
    if (affine_) {
      lp.Gx.resize(1, 2);
      lp.Gx << 1, 0;
      lp.g0.setConstant(1, c_);
    } else {
      lp.Gx.resize(0, 0);
    }
    return true;
  }

 private:
  double w_;
  bool affine_;
};

// Guard values at the accepted steps (the last one is the event point itself).
struct GuardAtSteps : stickslip::NullObserver {
  double c = 0;
  std::vector<double> g;
  bool on_step(double, const Eigen::Vector2d& x, const int&) {
    g.push_back(x[0] + c);
    return true;
  }
};

// Reference: the first root of a cos(w t + phi0) + c, w t + phi0 = acos(-c / a). Event time
// tolerance 1e-10 s: the locator closes its bracket to 1e-12 s; near the dip the guard's slope
// is a w sqrt(2 eps), so the guard's round-off (1e-16) moves the root by < 1e-13 s.
TEST(ExactLinearStepper, GuardDippingBetweenSamplesIsLocated) {
  const double w = 5.0, a = 1.0, phi0 = 0.3;
  for (bool affine : {true, false})
    for (double eps : {1e-6, 1e-9}) {
      const double c = a * (1 - eps);
      Grazer sys(w, c, affine);
      stickslip::ExactLinearStepper<Grazer> stepper(sys);
      GuardAtSteps log;
      log.c = c;
      const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(a * std::cos(phi0), -a * w * std::sin(phi0)),
                                       10.0, log);
      ASSERT_EQ(r.status, stickslip::Status::StoppedBySystem)
          << "affine " << affine << " eps " << eps << ": " << r.message;
      const double t_ref = (std::acos(-c / a) - phi0) / w;
      EXPECT_NEAR(r.t, t_ref, 1e-10) << "affine " << affine << " eps " << eps;
      EXPECT_LT(r.x[0] + c, 0.0);  // the state handed to the transition is past the guard
      // The grid points themselves never saw the dip (else this would not test grazing).
      ASSERT_GE(log.g.size(), 4u);
      EXPECT_GT(*std::min_element(log.g.begin(), log.g.end() - 1), 0.1);
    }
}

// c = a (1 + eps): the guard comes within a eps of zero and leaves: no event over 10 periods.
TEST(ExactLinearStepper, GuardComingCloseWithoutCrossingIsNoEvent) {
  const double w = 5.0, a = 1.0, phi0 = 0.3;
  for (bool affine : {true, false}) {
    const double c = a * (1 + 1e-9);
    Grazer sys(w, c, affine);
    stickslip::ExactLinearStepper<Grazer> stepper(sys);
    const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(a * std::cos(phi0), -a * w * std::sin(phi0)),
                                     20 * 3.14159265358979 / w);
    EXPECT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.stats.events, 0);
  }
}

// x'' = -w^2 x + F cos(w t) from rest (resonance): x(t) = F t sin(w t) / (2 w), an oscillation
// whose amplitude grows linearly; guard g = x + c (Falling) first reaches zero after ~2 w c / F
// (thousands of periods). Long steps (several grid steps at once) are taken while the guard-rate
// bound shows the guard cannot reach zero; the root must still be the first one.
class Resonator : public GuardOnX {
 public:
  Resonator(double w, double F, double c) : GuardOnX(c), w_(w), F_(F) {}

  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    dxdt << x[1], -w_ * w_ * x[0] + F_ * std::cos(w_ * t);
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.resize(2, 2);
    lp.A << 0, 1, -w_ * w_, 0;
    lp.b0.setZero(2);
    lp.omega = {w_};
    lp.bc.resize(2, 1);
    lp.bc << 0, F_;
    lp.bs.setZero(2, 1);
    lp.exact = true;
    lp.Gx.resize(1, 2);
    lp.Gx << 1, 0;
    lp.g0.setConstant(1, c_);
    lp.gc.setZero(1, 1);
    lp.gs.setZero(1, 1);
    return true;
  }
  double x(double t) const { return F_ * t * std::sin(w_ * t) / (2 * w_); }

 private:
  double w_, F_;
};

// Reference: the first root of F t sin(w t) / (2 w) + c by a scan of the closed form at 1e-3 of
// a period and bisection to the last bit (a root the scan could step over would need the guard to dip
// for < 1e-3 period, but the guard's minima near the first root are ~c F / w deep per period).
// Tolerance 1e-8 s: the locator closes its bracket to event_time_tolerance (1e-12 s); the state
// after ~1000 products with exp(Â H) carries ~1e-13 relative round-off, which moves a root where
// the guard's slope is ~ amplitude w ~ c w by ~1e-13 / w.
TEST(ExactLinearStepper, LongRootFreeStretchIsCrossedInLongStepsAndTheFirstRootFound) {
  const double w = 5.0, F = 0.002, c = 1.0;
  Resonator sys(w, F, c);
  const double period = 2 * 3.14159265358979 / w, dt = 1e-3 * period;
  double lo = 0, hi = 0;
  for (double t = 0;; t += dt) {
    if (sys.x(t + dt) + c <= 0) {
      lo = t;
      hi = t + dt;
      break;
    }
  }
  for (int k = 0; k < 60; ++k) {  // to the last bit (the bracket starts at 1e-3 of a period)
    const double mid = 0.5 * (lo + hi);
    (sys.x(mid) + c > 0 ? lo : hi) = mid;
  }
  ASSERT_GT(hi, 3000 * period);  // a long root-free stretch
  stickslip::ExactLinearStepper<Resonator> stepper(sys);
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d::Zero(), 2 * hi);
  ASSERT_EQ(r.status, stickslip::Status::StoppedBySystem) << r.message;
  EXPECT_NEAR(r.t, hi, 1e-8);
  const long grid_steps = static_cast<long>(hi / (period / 8));
  std::printf("root at %.6f s: %ld accepted steps (%ld long), %ld grid steps to the root\n", hi,
              r.stats.accepted_steps, stepper.work().long_steps, grid_steps);
  // Long steps while the amplitude is small against c (the bound on |g'| is ~2 w |x|_max, so
  // they shorten as the oscillation grows); grid steps near the root.
  EXPECT_GT(stepper.work().long_steps, 100);
  EXPECT_LT(r.stats.accepted_steps, grid_steps);
}

}  // namespace
}  // namespace ode_exact_grazing_test

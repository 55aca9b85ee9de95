// ExactLinearStepper: a guard that dips below zero between two guard samples (grazing) is
// located, not missed; a guard that only comes close is not an event.

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace ode_exact_grazing_test {  // named: the exact-stepper tests share one unity TU
namespace {

// x'' = -w^2 x, x(0) = a cos(phi0), x'(0) = -a w sin(phi0); guard g = x + c (Falling), so
// g(t) = a cos(w t + phi0) + c. With c = a (1 - eps) the guard is below zero only for
// |w t + phi0 - pi| < acos(1 - eps) ~ sqrt(2 eps): 2.8e-3 rad for eps = 1e-6, while the guard
// samples are pi/4 rad apart (1/8 of the period) and, with phi0 = 0.3, none falls in the dip.
// The transition stops the run, so that the result holds the event.
class Grazer {
 public:
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;

  Grazer(double w, double c, bool affine) : w_(w), c_(c), affine_(affine) {}

  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w_ * w_ * x[0];
  }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[0] + c_; }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Falling;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::halt("touched");
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
  double w_, c_;
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

}  // namespace
}  // namespace ode_exact_grazing_test

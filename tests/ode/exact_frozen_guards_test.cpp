// ExactLinearStepper in inexact modes that give frozen affine guards (LinearPart::Gx with
// exact = false): Lawson steps longer than the guard sampling step delta where the guards' rate
// bound shows that no guard can reach its trigger, and a guard that dips below zero between two
// step points is still located, not missed.

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace ode_exact_frozen_guards_test {  // named: the exact-stepper tests share one unity TU
namespace {

// A fast oscillator x'' = -w^2 x and a slow coordinate z' = -k - kappa z; guard g = z + b x (Falling;
// the event stops the run): z drifts down and the oscillation's minima dip towards zero one
// after the other, the first root lies in a dip of depth ~ (a b) eps at the minimum m_root,
// g(t) = z(t) + a b cos(w t + phi0), z(t) = (z0 + k / kappa) exp(-kappa t) - k / kappa (z0 - k t
// for kappa = 0). The linear part is declared inexact and leaves kappa out (A = [[0, 1, 0],
// [-w^2, 0, 0], [0, 0, 0]], b0 = (0, 0, -k)), so that the remainder r = -kappa z (slow, as the
// remainder of a slipping contact whose A_m is refreshed) is what the Lawson method integrates;
// the guard rows Gx = (b, 0, 1), g0 = 0 are the guard itself.
class DriftingGrazer {
 public:
  using Scalar = double;
  using State = Eigen::Vector3d;
  using Mode = int;

  DriftingGrazer(double w, double k, double b, double kappa) : w_(w), k_(k), b_(b), kappa_(kappa) {}
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double, const State& x, Eigen::VectorXd& g) const { g[0] = x[2] + b_ * x[0]; }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Falling;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    return stickslip::TransitionAction::halt("reached");
  }
  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w_ * w_ * x[0], -k_ - kappa_ * x[2];
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.setZero(3, 3);
    lp.A(0, 1) = 1;
    lp.A(1, 0) = -w_ * w_;
    lp.b0 = Eigen::Vector3d(0, 0, -k_);
    lp.omega.clear();
    lp.exact = false;
    lp.version = 1;
    lp.Gx.resize(1, 3);
    lp.Gx << b_, 0, 1;
    lp.g0.setZero(1);
    return true;
  }

 private:
  double w_, k_, b_, kappa_;
};

struct StepLog : stickslip::NullObserver {
  std::vector<double> t, g;
  double b = 0;
  bool on_step(double ts, const Eigen::Vector3d& x, const int&) {
    t.push_back(ts);
    g.push_back(x[2] + b * x[0]);
    return true;
  }
};

constexpr double kPi = 3.14159265358979323846;

// The scene: w = 5 rad/s (delta = 2 pi / (8 w) = 0.157 s), a = 1, b = 0.1, k = 0.016 per s (the
// minima descend by k 2 pi / w = 0.02 = 0.2 a b per period); z0 puts the minimum m_root = 20 at
// depth -(a b) eps, so that the minima before it stay above zero by >= 0.02 - 0.1 eps, and starts
// the guard at ~5 a b: far from zero against the oscillation's share a b, where long steps clear.
// With kappa > 0, z0 is chosen so that z(t_min(m_root)) is the same.
struct Scene {
  double w = 5, a = 1, b = 0.1, k = 0.016, phi0 = 0.3, kappa = 0;
  int m_root = 20;
  double t_min(int m) const { return (kPi * (2 * m + 1) - phi0) / w; }
  double z0(double eps) const {
    const double zm = a * b * (1 - eps), tm = t_min(m_root);
    return kappa == 0 ? zm + k * tm : (zm + k / kappa) * std::exp(kappa * tm) - k / kappa;
  }
  double z(double t, double eps) const {
    return kappa == 0 ? z0(eps) - k * t : (z0(eps) + k / kappa) * std::exp(-kappa * t) - k / kappa;
  }
  double g(double t, double eps) const { return z(t, eps) + a * b * std::cos(w * t + phi0); }
  Eigen::Vector3d x0(double eps) const {
    return Eigen::Vector3d(a * std::cos(phi0), -a * w * std::sin(phi0), z0(eps));
  }
};

// Reference root: the first sign change of the closed form on a scan at 1e-4 of a period (the
// dip is sqrt(2 eps) / w wide: 3e-3 / w for eps = 5e-6, i.e. 5e-4 of a period), then bisection
// to the last bit.
double first_root(const Scene& sc, double eps) {
  const double dt = 1e-4 * 2 * kPi / sc.w;
  double lo = 0, hi = 0;
  for (double t = 0;; t += dt)
    if (sc.g(t + dt, eps) <= 0) {
      lo = t;
      hi = t + dt;
      break;
    }
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (sc.g(mid, eps) > 0 ? lo : hi) = mid;
  }
  return hi;
}

// Tolerance: with kappa = 0 the method is exact and the locator closes its bracket to
// event_time_tolerance (1e-12 s), and the guard's slope at the root is a b w sqrt(2 eps) ~ 1.6e-3,
// so round-off (1e-16) moves the root by < 1e-12 s: 1e-9 s. With kappa = 1e-3 per s the
// remainder is integrated to rtol 1e-10 over ~20 periods, which moves g by ~1e-9 a b and the
// root by ~1e-10 / 1.6e-3 s: 1e-6 s (a missed first dip would put the root a period, 1.26 s,
// later).
TEST(ExactLinearStepperFrozenGuards, GuardDippingBetweenLongSlippingStepsIsLocated) {
  for (double kappa : {0.0, 1e-3}) {
    Scene sc;
    sc.kappa = kappa;
    const double eps = 5e-6;
    const double t_ref = first_root(sc, eps);
    ASSERT_NEAR(t_ref, sc.t_min(sc.m_root), 1e-2 / sc.w);  // the root is in the dip of m_root
    DriftingGrazer sys(sc.w, sc.k, sc.b, kappa);
    stickslip::StepperOptions<double> opt;
    opt.rtol = 1e-10;
    opt.atol = 1e-12;
    stickslip::ExactLinearStepper<DriftingGrazer> stepper(sys, opt);
  stepper.set_long_slipping_steps(true);
    StepLog log;
    log.b = sc.b;
    const auto r = stepper.integrate(0, 0.0, sc.x0(eps), 2 * t_ref, log);
    ASSERT_EQ(r.status, stickslip::Status::StoppedBySystem) << "kappa " << kappa << ": " << r.message;
    EXPECT_NEAR(r.t, t_ref, kappa == 0 ? 1e-9 : 1e-6) << "kappa " << kappa;
    EXPECT_LT(r.x[2] + sc.b * r.x[0], 0.0);
    // Long steps were taken (else this would not test them), and no accepted step point saw
    // the dip (else it would not test grazing).
    EXPECT_GT(stepper.work().long_slip_steps, 10) << "kappa " << kappa;
    ASSERT_GE(log.g.size(), 3u);
    EXPECT_GT(*std::min_element(log.g.begin(), log.g.end() - 1), 0.0);
    std::printf("kappa %.0e: event at t - t_ref = %.2e s, %ld Lawson steps (%ld long, %ld re-taken), %ld grid steps to the root\n",
                kappa, r.t - t_ref, stepper.work().exponential_steps,
                stepper.work().long_slip_steps, stepper.work().slip_bound_rejections,
                static_cast<long>(t_ref / (2 * kPi / (8 * sc.w))));
  }
}

// The same scene (kappa = 0) with the minimum m_root at +(a b) eps, eps = 1e-3: the guard comes
// within ~5e-4 a b of zero (the drift moves the minimum's value down by k^2 / (2 a b w^2) = 5e-5)
// and leaves; no event up to half a period after it. Every minimum lies within one grid step delta
// of an accepted step point: no long step spans a close approach.
TEST(ExactLinearStepperFrozenGuards, LongSlippingStepsStopShortOfACloseApproach) {
  const Scene sc;
  const double eps = -1e-3;
  DriftingGrazer sys(sc.w, sc.k, sc.b, 0.0);
  stickslip::StepperOptions<double> opt;  // (exact: the remainder is zero; the tolerances
  opt.rtol = 1e-10;                       // bound the round-off of the steps, ~1e-16 a b)
  opt.atol = 1e-12;
  stickslip::ExactLinearStepper<DriftingGrazer> stepper(sys, opt);
  stepper.set_long_slipping_steps(true);
  StepLog log;
  log.b = sc.b;
  const double t_end = sc.t_min(sc.m_root) + kPi / sc.w;
  const auto r = stepper.integrate(0, 0.0, sc.x0(eps), t_end, log);
  EXPECT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.stats.events, 0);
  EXPECT_GT(stepper.work().long_slip_steps, 10);
  const double delta = 2 * kPi / (8 * sc.w);
  for (int m = 0; m <= sc.m_root; ++m) {
    double nearest = 1e9;
    for (double ts : log.t) nearest = std::min(nearest, std::abs(ts - sc.t_min(m)));
    EXPECT_LE(nearest, delta * (1 + 1e-9)) << "minimum " << m;
  }
}

}  // namespace
}  // namespace ode_exact_frozen_guards_test

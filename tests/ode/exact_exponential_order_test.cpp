// ExactLinearStepper in a mode with a nonlinear remainder (LinearPart::exact = false): the Lawson
// Dormand-Prince method's measured order of convergence, against a tight Dormand-Prince
// reference computed by HybridStepper (an independent method).

#include <stickslip/ode/exact_linear_stepper.hpp>

#include <gtest/gtest.h>

#include "ode/exact_test_systems.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

namespace ode_exact_exponential_order_test {  // named: the exact-stepper tests share a TU
namespace {

// Duffing oscillator x'' + w^2 x = -eps x^3, plus a slow component p' = c x - p^3 driven by it:
// linear part A = [[0, 1, 0], [-w^2, 0, 0], [c, 0, 0]], remainder (0, -eps x^3, -p^3).
class Duffing : public ode_exact_test::Unguarded<Eigen::Vector3d> {
 public:
  using Scalar = double;
  using State = Eigen::Vector3d;
  using Mode = int;

  Duffing(double w, double eps, double c) : w_(w), eps_(eps), c_(c) {}

  void rhs(const Mode&, double, const State& x, State& dxdt) const {
    dxdt << x[1], -w_ * w_ * x[0] - eps_ * x[0] * x[0] * x[0], c_ * x[0] - x[2] * x[2] * x[2];
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    lp.A.setZero(3, 3);
    lp.A(0, 1) = 1;
    lp.A(1, 0) = -w_ * w_;
    lp.A(2, 0) = c_;
    lp.b0.setZero(3);
    lp.omega.clear();
    lp.exact = false;
    lp.version = 1;
    return true;
  }

 private:
  double w_, eps_, c_;
};

struct Samples : stickslip::NullObserver {
  std::vector<Eigen::Vector3d> x;
  bool on_sample(double, const Eigen::Vector3d& xs, const int&) {
    x.push_back(xs);
    return true;
  }
};

// Largest error over the samples every 0.4 (multiples of every step used): no cancellation at a
// single end time.
double error_with_step(Duffing& sys, const Eigen::Vector3d& x0, double t_end, double h,
                       const std::vector<Eigen::Vector3d>& ref) {
  stickslip::StepperOptions<double> opt;  // fixed steps: all accepted, none larger than h
  opt.rtol = 1e6;
  opt.atol = 1e6;
  opt.initial_step = h;
  opt.max_step = h;
  opt.output_interval = 0.4;
  stickslip::ExactLinearStepper<Duffing> stepper(sys, opt);
  Samples log;
  const auto r = stepper.integrate(0, 0.0, x0, t_end, log);
  EXPECT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(log.x.size(), ref.size());
  double err = 0;
  for (std::size_t i = 0; i < std::min(log.x.size(), ref.size()); ++i)
    err = std::max(err, (log.x[i] - ref[i]).lpNorm<Eigen::Infinity>());
  return err;
}

std::vector<Eigen::Vector3d> reference(Duffing& sys, const Eigen::Vector3d& x0, double t_end) {
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-14;
  opt.atol = 1e-16;
  opt.max_step = 0.4;  // samples at step ends, not from the order-4 dense output
  Samples log;
  opt.output_interval = 0.4;
  stickslip::HybridStepper<Duffing, stickslip::DormandPrince54> sampled(sys, opt);
  const auto r = sampled.integrate(0, 0.0, x0, t_end, log);
  EXPECT_TRUE(r.ok()) << r.message;
  return log.x;
}

// Non-stiff: w = 2, eps = 1, c = 0.5, steps 0.4 .. 0.025 over [0, 4]. The errors (3e-4 ..
// 2e-11) stay above the reference's (~1e-13), so the ratios measure the method: order 5
// (measured 5.7, 6.3, 6.4, 5.5 pre-asymptotically), asserted in [4.5, 6.5] (the brief asks >= 4;
// a first-order splitting error or a wrong tableau entry gives <= 2).
TEST(ExactLinearStepperExponential, LawsonDormandPrinceConvergesWithOrderFive) {
  Duffing sys(2.0, 1.0, 0.5);
  const Eigen::Vector3d x0(1.0, 0.0, 0.5);
  const double t_end = 4.0;
  const auto ref = reference(sys, x0, t_end);
  std::vector<double> err;
  for (double h : {0.4, 0.2, 0.1, 0.05, 0.025}) err.push_back(error_with_step(sys, x0, t_end, h, ref));
  ode_exact_test::expect_order_five(err, "Duffing");
}

// Stiff linear part: w = 400 with steps w h = 80 .. 10, far beyond the stability limit of any
// explicit method (w h <~ 3.3 for Dormand-Prince); the remainder -eps x^3 is small (eps = 1e3,
// |x| ~ 1e-2: eps x^3 ~ 1e-3 against w^2 x ~ 1.6e3) but oscillates at 3 w, so the asymptotic
// regime starts only at w h ~ 10 (measured orders 0.3, 2.3, 3.7). Asserted: the error stays
// bounded (< 1e-3 of |x0|) at every step, no instability, and the last pair converges with
// order > 3.
TEST(ExactLinearStepperExponential, NoStabilityLimitFromTheLinearPart) {
  Duffing sys(400.0, 1e3, 0.5);
  const Eigen::Vector3d x0(1e-2, 0.0, 0.5);
  const double t_end = 1.0;
  const auto ref = reference(sys, x0, t_end);
  std::vector<double> err;
  for (double h : {0.2, 0.1, 0.05, 0.025}) {
    err.push_back(error_with_step(sys, x0, t_end, h, ref));
    EXPECT_LT(err.back(), 1e-3 * x0.norm()) << "h " << h;  // bounded: no instability
  }
  for (std::size_t i = 0; i + 1 < err.size(); ++i)
    std::printf("stiff: errors %.3e -> %.3e: order %.2f\n", err[i], err[i + 1],
                std::log2(err[i] / err[i + 1]));
  EXPECT_GT(std::log2(err[err.size() - 2] / err.back()), 3.0);
}

}  // namespace
}  // namespace ode_exact_exponential_order_test

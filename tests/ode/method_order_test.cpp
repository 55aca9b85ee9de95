// Measured orders of convergence of the integration methods, on problems with closed forms.

#include <stickslip/ode.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include "ode/ode_test_systems.hpp"

namespace {

using stickslip::DormandPrince54;
using stickslip::HybridStepper;
using stickslip::NullObserver;
using stickslip::Rosenbrock23;
using stickslip::RungeKutta4;
using stickslip::Status;
using stickslip::StepperOptions;
using Linear2 = stickslip::test::LinearSystem<2>;

constexpr double kOmega = 3.0;

Linear2 oscillator() {
  Linear2 s;
  s.a << 0.0, 1.0, -kOmega * kOmega, 0.0;
  return s;
}

// Options that make an adaptive method take exactly steps of h: tolerances so loose that no step
// is rejected, and max_step = initial_step = h.
StepperOptions<double> fixed_steps(double h) {
  StepperOptions<double> opt;
  opt.fixed_step = h;
  opt.initial_step = h;
  opt.max_step = h;
  opt.rtol = 1.0;
  opt.atol = 1.0;
  return opt;
}

// Global error at t = 1 of x(t) = cos(omega t) integrated with steps h.
template <class Method>
double oscillator_error(double h) {
  Linear2 sys = oscillator();
  HybridStepper<Linear2, Method> stepper(sys, fixed_steps(h));
  const auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), 1.0);
  EXPECT_EQ(r.status, Status::Success) << r.message;
  EXPECT_NEAR(static_cast<double>(r.stats.accepted_steps), 1.0 / h, 1.0);
  return std::hypot(r.x[0] - std::cos(kOmega), r.x[1] + kOmega * std::sin(kOmega));
}

// The tolerance 0.2 on a measured order: the asymptotic regime is reached to a few percent in
// the step ranges chosen (errors from 1e-3 down to 1e-10, far above round-off).
TEST(MethodOrder, RungeKutta4IsFourthOrder) {
  for (double h : {0.05, 0.025, 0.0125})
    EXPECT_NEAR(std::log2(oscillator_error<RungeKutta4>(h) / oscillator_error<RungeKutta4>(h / 2)),
                4.0, 0.2)
        << "h = " << h;
}

TEST(MethodOrder, DormandPrince54IsFifthOrder) {
  // The leading error term of DOPRI5 is small on this problem: the measured slope approaches 5
  // from above (5.45 at h = 0.1, 5.25 at h = 0.05), hence the smaller steps here.
  for (double h : {0.025, 0.0125})
    EXPECT_NEAR(
        std::log2(oscillator_error<DormandPrince54>(h) / oscillator_error<DormandPrince54>(h / 2)),
        5.0, 0.2)
        << "h = " << h;
}

TEST(MethodOrder, Rosenbrock23IsSecondOrder) {
  for (double h : {0.02, 0.01, 0.005})
    EXPECT_NEAR(
        std::log2(oscillator_error<Rosenbrock23>(h) / oscillator_error<Rosenbrock23>(h / 2)), 2.0,
        0.15)
        << "h = " << h;
}

// Error of the dense output a quarter into one step of size h on x' = -x^2, x(0) = 1, from the
// exact state: a continuous extension of order q has local error O(h^(q+1)). (Not the midpoint,
// where the Dormand-Prince extension is of order 5 by construction, and not a linear problem, on
// which it is of higher order too.)
template <class Method>
double dense_quarter_error(double h) {
  using Riccati = stickslip::test::Riccati;
  struct Quarter : NullObserver {
    double t = -1, x = 0;
    bool on_sample(double ts, const Riccati::State& xs, const int&) {
      if (t < 0 && ts > 0) {
        t = ts;
        x = xs[0];
      }
      return true;
    }
  } quarter;
  Riccati sys;
  auto opt = fixed_steps(h);
  opt.output_interval = h / 4;
  HybridStepper<Riccati, Method> stepper(sys, opt);
  const auto r = stepper.integrate(0, 0.0, Riccati::State(1.0), h, quarter);
  EXPECT_EQ(r.stats.accepted_steps, 1);
  EXPECT_DOUBLE_EQ(quarter.t, h / 4);
  return std::abs(quarter.x - Riccati::exact(h / 4, 1.0));
}

TEST(MethodOrder, DormandPrinceDenseOutputIsFourthOrder) {
  // Order-4 continuous extension: local error O(h^5).
  for (double h : {0.1, 0.05, 0.025})
    EXPECT_NEAR(std::log2(dense_quarter_error<DormandPrince54>(h) /
                          dense_quarter_error<DormandPrince54>(h / 2)),
                5.0, 0.2)
        << "h = " << h;
}

TEST(MethodOrder, RungeKutta4HermiteDenseOutputIsThirdOrder) {
  // Cubic Hermite on RK4 end values: local error O(h^4).
  for (double h : {0.1, 0.05, 0.025})
    EXPECT_NEAR(std::log2(dense_quarter_error<RungeKutta4>(h) /
                          dense_quarter_error<RungeKutta4>(h / 2)),
                4.0, 0.2)
        << "h = " << h;
}

// Stiff linear system with eigenvalues -1 and -1e6, x(t) = V diag(e^-t, e^-1e6 t) V^-1 x0.
struct StiffCase {
  Eigen::Matrix2d v, a;
  StiffCase() {
    v << 1.0, 1.0, 1.0, -1.0;
    const Eigen::Vector2d lambda(-1.0, -1e6);
    a = v * lambda.asDiagonal() * v.inverse();
  }
  Eigen::Vector2d exact(double t, const Eigen::Vector2d& x0) const {
    const Eigen::Vector2d c = v.inverse() * x0;
    return v * Eigen::Vector2d(c[0] * std::exp(-t), c[1] * std::exp(-1e6 * t));
  }
};

TEST(MethodOrder, Rosenbrock23DenseOutputIsSecondOrder) {
  // Local error O(h^3).
  for (double h : {0.05, 0.025, 0.0125})
    EXPECT_NEAR(std::log2(dense_quarter_error<Rosenbrock23>(h) /
                          dense_quarter_error<Rosenbrock23>(h / 2)),
                3.0, 0.15)
        << "h = " << h;
}

TEST(MethodOrder, Rosenbrock23ConvergesAtOrderTwoOnStiffLinearSystem) {
  // Fixed steps h >> 1e-6: the stiff component is damped (L-stability) and the error is the
  // order-2 error of the slow mode.
  StiffCase c;
  const Eigen::Vector2d x0(2.0, 0.0);
  auto err = [&](double h) {
    stickslip::test::LinearSystemWithJacobian<2> sys;
    sys.a = c.a;
    HybridStepper<decltype(sys), Rosenbrock23> stepper(sys, fixed_steps(h));
    const auto r = stepper.integrate(0, 0.0, x0, 1.0);
    EXPECT_EQ(r.status, Status::Success);
    return (r.x - c.exact(1.0, x0)).norm();
  };
  for (double h : {0.02, 0.01, 0.005}) EXPECT_NEAR(std::log2(err(h) / err(h / 2)), 2.0, 0.2);
}

TEST(StiffSystem, Rosenbrock23CompletesInFewStepsWithFiniteDifferenceJacobian) {
  StiffCase c;
  Linear2 sys;
  sys.a = c.a;
  StepperOptions<double> opt;
  opt.rtol = 1e-6;
  opt.atol = 1e-9;
  HybridStepper<Linear2, Rosenbrock23> stepper(sys, opt);
  const Eigen::Vector2d x0(2.0, 0.0);
  const auto r = stepper.integrate(0, 0.0, x0, 10.0);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  // The fast transient lasts ~1e-5 and the slow mode needs steps h ~ rtol^(1/3): a few hundred,
  // against ~3e6 for an explicit method bounded by |h lambda| < 3.3.
  EXPECT_LT(r.stats.accepted_steps, 1000);
  EXPECT_EQ(r.stats.jacobian_evaluations, r.stats.accepted_steps);
  // Global error of a tolerance-controlled method: local errors of about rtol * max|x| = 2e-6
  // per unit time, damped by e^-t; 2e-6 is the tolerance scale of the largest state.
  EXPECT_LT((r.x - c.exact(10.0, x0)).norm(), 2e-6);
}

TEST(StiffSystem, DormandPrinceNeedsStabilityBoundStepsOrReportsMaxSteps) {
  StiffCase c;
  Linear2 sys;
  sys.a = c.a;
  const Eigen::Vector2d x0(2.0, 0.0);
  StepperOptions<double> opt;
  HybridStepper<Linear2, DormandPrince54> dp(sys, opt);
  const auto r = dp.integrate(0, 0.0, x0, 0.1);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  // Stability of DOPRI5 on the negative real axis ends near h lambda = -3.3: at least
  // 0.1 * 1e6 / 3.3 = 3e4 steps.
  EXPECT_GT(r.stats.accepted_steps, 30000);
  EXPECT_LT((r.x - c.exact(0.1, x0)).norm(), 1e-5);
  opt.max_steps = 1000;
  HybridStepper<Linear2, DormandPrince54> capped(sys, opt);
  EXPECT_EQ(capped.integrate(0, 0.0, x0, 0.1).status, Status::MaxSteps);
}

}  // namespace

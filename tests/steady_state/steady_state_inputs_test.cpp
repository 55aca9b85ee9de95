// Caller errors (std::invalid_argument naming the parameter), the statuses of failed orbit
// computations, and the Floquet classification on matrices with known eigenvalues.

#include "contact/contact_test_util.hpp"
#include "steady_state/smooth_forced_systems.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

namespace steady_state_inputs_test {
namespace {

using contact_test::expect_invalid_argument;
using namespace steady_state_test;
constexpr double kPi = 3.14159265358979323846;
using Linear1 = ForcedOscillator<1>;

TEST(SteadyStateInputs, ShootingRejectsBadArgumentsNamingThem) {
  Linear1 sys;
  sys.C(0, 0) = 0.1;
  stickslip::Shooting<Linear1> shooting(sys);
  const Linear1::State x0 = Linear1::State::Zero();
  expect_invalid_argument([&] { shooting.forced(0, 0.0, x0, 0.0); }, {"Shooting", "period", "0"});
  expect_invalid_argument([&] { shooting.forced(0, std::nan(""), x0, 1.0); }, {"Shooting", "t0"});
  expect_invalid_argument([&] { shooting.forced(0, 0.0, Linear1::State(1.0, std::nan("")), 1.0); },
                          {"Shooting", "x0"});
  auto bad = [&](auto edit, const char* name) {
    stickslip::ShootingOptions<double> o;
    edit(o);
    stickslip::Shooting<Linear1> s(sys, o);
    expect_invalid_argument([&] { s.forced(0, 0.0, x0, 1.0); }, {"Shooting", name});
  };
  bad([](auto& o) { o.periodic = {0, 2}; }, "options.periodic");
  bad([](auto& o) { o.periodic = {1, 1}; }, "options.periodic");
  bad([](auto& o) { o.amplitude_components = {-1}; }, "options.amplitude_components");
  bad([](auto& o) { o.tolerance = 0; }, "options.tolerance");
  bad([](auto& o) { o.max_iterations = 0; }, "options.max_iterations");
  bad([](auto& o) { o.fd_step = 0.5; }, "options.fd_step");
  bad([](auto& o) { o.samples_per_period = -1; }, "options.samples_per_period");
  bad([](auto& o) { o.stepper.rtol = -1; }, "options.rtol");
}

TEST(SteadyStateInputs, ContinuationRejectsBadArgumentsNamingThem) {
  Linear1 sys;
  auto set = [](Linear1& s, double w) { s.omega = w; };
  auto period = [](double w) { return 2 * kPi / w; };
  using C = stickslip::Continuation<Linear1>;
  expect_invalid_argument([&] { C(sys, nullptr, period); }, {"Continuation", "set_parameter"});
  expect_invalid_argument([&] { C(sys, set, nullptr); }, {"Continuation", "period"});
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = 2;
  co.parameter_max = 1;
  expect_invalid_argument([&] { C(sys, set, period, {}, co); },
                          {"Continuation", "options.parameter_max"});
  co.parameter_min = 0.5;
  co.parameter_max = 1.5;
  co.direction = 0;
  expect_invalid_argument([&] { C(sys, set, period, {}, co); }, {"Continuation", "options.direction"});
  co.direction = 1;
  co.initial_step = 1;
  expect_invalid_argument([&] { C(sys, set, period, {}, co); },
                          {"Continuation", "options.initial_step"});
  co.initial_step = 0.01;
  C cont(sys, set, period, {}, co);
  expect_invalid_argument([&] { cont.run(0, 0.0, Linear1::State::Zero(), 3.0); },
                          {"Continuation::run", "p0", "3"});
}

TEST(SteadyStateInputs, SplitContinuationRejectsBadArgumentsNamingThem) {
  Linear1 a, b;
  auto set = [](Linear1& s, double w) { s.omega = w; };
  auto period = [](double w) { return 2 * kPi / w; };
  using SC = stickslip::SplitContinuation<Linear1>;
  expect_invalid_argument([&] { SC({}, set, period); }, {"SplitContinuation", "systems", "empty"});
  expect_invalid_argument([&] { SC({&a, nullptr}, set, period); }, {"SplitContinuation", "systems[k]", "1"});
  expect_invalid_argument([&] { SC({&a, &b, &a}, set, period); }, {"SplitContinuation", "distinct", "2"});
  expect_invalid_argument([&] { SC({&a, &b}, nullptr, period); }, {"SplitContinuation", "set_parameter"});
  expect_invalid_argument([&] { SC({&a, &b}, set, nullptr); }, {"SplitContinuation", "period"});
  stickslip::ContinuationOptions<double> co;
  co.max_points = 0;
  expect_invalid_argument([&] { SC({&a, &b}, set, period, {}, co); },
                          {"SplitContinuation", "options.max_points"});
  SC split({&a, &b}, set, period);
  for (double tol : {0.0, 1.0, std::nan("")})
    expect_invalid_argument([&] { split.join_tolerance(tol); }, {"SplitContinuation::join_tolerance", "tolerance"});
  expect_invalid_argument([&] { split.run(nullptr); }, {"SplitContinuation::run", "start"});
}

// x'' + x = cos t over T = 2 pi: no periodic orbit (resonance without damping) and M = I, so
// M - I is singular: SingularJacobian with the residual, not a silent point.
TEST(SteadyStateInputs, UndampedResonanceIsASingularJacobian) {
  Linear1 sys;
  stickslip::Shooting<Linear1> shooting(sys);
  const auto orbit = shooting.forced(0, 0.0, Linear1::State::Zero(), 2 * kPi);
  EXPECT_EQ(orbit.status, stickslip::ShootingStatus::SingularJacobian);
  EXPECT_NE(orbit.message.find("residual"), std::string::npos) << orbit.message;
  EXPECT_GT(orbit.residual, 1.0);  // the secular growth pi over one period
}

// Newton with one iteration from a far guess: NoConvergence, the message with the residual.
TEST(SteadyStateInputs, NewtonOutOfIterationsSaysSoWithTheResidual) {
  Linear1 sys;
  sys.C(0, 0) = 0.1;
  sys.k3 = 1.0;
  auto o = stickslip::ShootingOptions<double>();
  o.max_iterations = 1;
  stickslip::Shooting<Linear1> shooting(sys, o);
  const auto orbit = shooting.forced(0, 0.0, Linear1::State(3.0, 0.0), 2 * kPi);
  EXPECT_EQ(orbit.status, stickslip::ShootingStatus::NoConvergence);
  EXPECT_NE(orbit.message.find("residual"), std::string::npos) << orbit.message;
  EXPECT_NE(orbit.message.find("quasi-periodic"), std::string::npos) << orbit.message;
}

// A state that never changes and a mode that toggles at every integer time (guard sin(pi t)):
// x(1) = x(0) but the mode sequence has period 2, which shooting with T = 1 must report.
struct TogglingMode {
  using Scalar = double;
  using State = Eigen::Matrix<double, 1, 1>;
  using Mode = int;
  void rhs(const Mode&, double, const State&, State& dxdt) const { dxdt.setZero(); }
  Eigen::Index num_guards(const Mode&) const { return 1; }
  void guards(const Mode&, double t, const State&, Eigen::VectorXd& g) const {
    g[0] = std::sin(kPi * t);
  }
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards&, double,
                                         State&) const {
    m = 1 - m;
    return stickslip::TransitionAction::proceed();
  }
};

TEST(SteadyStateInputs, ModeSequenceThatDoesNotCloseIsReported) {
  TogglingMode sys;
  auto o = stickslip::ShootingOptions<double>();
  // The guard depends on t only: the error estimate is 0 and the step would grow over two
  // crossings (both missed); the stepper sees a crossing only at step ends.
  o.stepper.max_step = 0.1;
  stickslip::Shooting<TogglingMode> shooting(sys, o);
  const auto orbit = shooting.forced(0, 0.5, TogglingMode::State(1.0), 1.0);
  EXPECT_EQ(orbit.status, stickslip::ShootingStatus::ModeNotPeriodic);
  EXPECT_NE(orbit.message.find("mode"), std::string::npos) << orbit.message;
  const auto twice = shooting.forced(0, 0.5, TogglingMode::State(1.0), 2.0);  // the 2T orbit
  EXPECT_TRUE(twice.ok()) << twice.message;
  EXPECT_EQ(twice.events.size(), 2u);
}

// Classification on matrices whose eigenvalues are known by construction.
TEST(SteadyStateInputs, FloquetClassificationOfKnownSpectra) {
  using M = Eigen::MatrixXd;
  const double tol = 1e-9;
  auto classify = [&](const M& m, bool autonomous) {
    return stickslip::floquet_multipliers<double>(m, autonomous, tol);
  };
  const auto stable = classify(Eigen::Vector2d(0.5, -0.9).asDiagonal().toDenseMatrix(), false);
  EXPECT_TRUE(stable.stable);
  EXPECT_EQ(stable.instability, stickslip::Instability::None);
  EXPECT_NEAR(stable.max_modulus, 0.9, 1e-15);
  const auto fold = classify(Eigen::Vector2d(0.5, 1.2).asDiagonal().toDenseMatrix(), false);
  EXPECT_EQ(fold.instability, stickslip::Instability::Fold);
  const auto flip = classify(Eigen::Vector2d(0.5, -1.2).asDiagonal().toDenseMatrix(), false);
  EXPECT_EQ(flip.instability, stickslip::Instability::PeriodDoubling);
  M rotation(2, 2);  // 1.1 times a rotation by 0.3 rad: the pair 1.1 e^{+-0.3 i}
  rotation << std::cos(0.3), -std::sin(0.3), std::sin(0.3), std::cos(0.3);
  const auto ns = classify(1.1 * rotation, false);
  EXPECT_EQ(ns.instability, stickslip::Instability::NeimarkSacker);
  EXPECT_NEAR(ns.max_modulus, 1.1, 1e-14);
  // Autonomous: the eigenvalue nearest 1 is the trivial one, the rest decide.
  const auto autonomous = classify(Eigen::Vector3d(0.2, 1.0 + 1e-12, -0.7).asDiagonal().toDenseMatrix(), true);
  ASSERT_TRUE(autonomous.has_trivial);
  EXPECT_NEAR(autonomous.trivial.real(), 1.0, 1e-11);
  ASSERT_EQ(autonomous.multipliers.size(), 2);
  EXPECT_NEAR(autonomous.multipliers[0].real(), -0.7, 1e-15);
  EXPECT_TRUE(autonomous.stable);
}


// Found by a probe of the steady-state layer (2026-11-25). A first orbit run that fails reports
// the guess as its last iterate (x0 and period were left unset: uninitialised memory for a
// fixed-size state).
TEST(SteadyStateInputs, FailedFirstRunReportsTheGuessAsTheLastIterate) {
  Linear1 sys;
  sys.C(0, 0) = 0.1;
  auto o = stickslip::ShootingOptions<double>();
  o.stepper.max_steps = 5;
  stickslip::Shooting<Linear1> shooting(sys, o);
  const Linear1::State guess(0.25, -0.5);
  const auto orbit = shooting.forced(0, 0.0, guess, 2 * kPi);
  EXPECT_EQ(orbit.status, stickslip::ShootingStatus::IntegrationFailed);
  EXPECT_EQ(orbit.x0, guess);
  EXPECT_EQ(orbit.period, 2 * kPi);
  EXPECT_EQ(orbit.iterations, 1);
  EXPECT_NE(orbit.message.find("max_steps"), std::string::npos) << orbit.message;
}

// At t0 = 1e17 a period of 4.8 is below the time resolution (ulp 16): t0 + T rounds to t0, the
// "period" run returned its start and every guess closed (Converged at (5, 0); the orbit's
// amplitude is 1 / |1 - w^2 + i c w| = 1.42). Refused, naming the period, by Shooting,
// run_period and poincare_sections; at t0 = 1e3 the same shooting finds the closed form.
TEST(SteadyStateInputs, PeriodBelowTheTimeResolutionAtT0IsRefused) {
  Linear1 sys;
  sys.C(0, 0) = 0.1;
  sys.omega = 1.3;
  const double T = 2 * kPi / sys.omega;
  const Linear1::State guess(5.0, 0.0);
  auto o = stickslip::ShootingOptions<double>();
  o.samples_per_period = 0;
  stickslip::Shooting<Linear1> shooting(sys, o);
  expect_invalid_argument([&] { shooting.forced(0, 1e17, guess, T); },
                          {"Shooting", "period", "min_step", "resolve"});
  expect_invalid_argument([&] { stickslip::run_period(sys, 0, 1e17, guess, T, o, false); },
                          {"run_period", "T", "min_step"});
  stickslip::PoincareOptions<double> po;
  expect_invalid_argument([&] { stickslip::poincare_sections(sys, 0, 1e17, guess, T, po); },
                          {"poincare_sections", "T", "min_step"});
  const auto orbit = shooting.forced(0, 1e3, guess, T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  const double amplitude = 1 / std::abs(std::complex<double>(1 - 1.69, 0.13));
  EXPECT_NEAR(std::hypot(orbit.x0[0], orbit.x0[1] / sys.omega), amplitude, 1e-6 * amplitude);
}

// A damped, unforced linear oscillator has no periodic orbit but its equilibrium, which closes
// for any period: autonomous shooting from (1, 0) walked to x0 ~ 3e-12 and reported it
// Converged with the period guess. Now NoConvergence naming the equilibrium.
TEST(SteadyStateInputs, AutonomousShootingOntoAnEquilibriumIsNoOrbit) {
  Linear1 sys;
  sys.C(0, 0) = 0.1;
  sys.f.setZero();
  stickslip::Shooting<Linear1> shooting(sys);
  for (double guess : {6.0, 3.0}) {
    const auto orbit = shooting.autonomous(0, Linear1::State(1.0, 0.0), guess);
    EXPECT_EQ(orbit.status, stickslip::ShootingStatus::NoConvergence) << "T guess " << guess;
    EXPECT_NE(orbit.message.find("equilibrium"), std::string::npos) << orbit.message;
  }
}

TEST(SteadyStateInputs, FloquetMultipliersRejectBadMatricesAndTolerances) {
  using M = Eigen::MatrixXd;
  const M good = Eigen::Vector2d(0.5, 0.2).asDiagonal().toDenseMatrix();
  M nan = good;
  nan(1, 0) = std::nan("");
  M inf = good;
  inf(0, 1) = HUGE_VAL;
  expect_invalid_argument([&] { stickslip::floquet_multipliers<double>(nan, false, 1e-9); },
                          {"floquet_multipliers", "M", "finite"});
  expect_invalid_argument([&] { stickslip::floquet_multipliers<double>(inf, false, 1e-9); },
                          {"floquet_multipliers", "M", "finite"});
  expect_invalid_argument([&] { stickslip::floquet_multipliers<double>(M(2, 3), false, 1e-9); },
                          {"floquet_multipliers", "square"});
  expect_invalid_argument([&] { stickslip::floquet_multipliers<double>(good, false, -1.0); },
                          {"floquet_multipliers", "tolerance"});
  expect_invalid_argument([&] { stickslip::floquet_multipliers<double>(good, false, std::nan("")); },
                          {"floquet_multipliers", "tolerance"});
  EXPECT_TRUE(stickslip::floquet_multipliers<double>(good, false, 0.0).stable);
}

}  // namespace
}  // namespace steady_state_inputs_test

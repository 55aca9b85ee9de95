// The cancellation hook of the steady-state solvers (ShootingOptions::interrupt,
// PoincareOptions::interrupt; stickslip/steady_state/interrupt.hpp) on a damped linear oscillator
// x'' + 0.2 x' + x = cos t:
//  - a hook that never fires changes nothing (the orbit equals the one without a hook, bit for bit);
//  - a hook that fires at its n-th call stops Shooting, poincare_sections and Continuation at
//    once: no call after the n-th (Shooting does not go on to its backtracking trials), the
//    status says so (IntegrationFailed, Interrupted) and the message starts "interrupted";
//  - Continuation keeps the points it had.

#include "steady_state/smooth_forced_systems.hpp"

#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/poincare.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <gtest/gtest.h>

#include <string>

namespace steady_state_interrupt_test {  // named: the steady-state test files share one unity TU
namespace {

using Oscillator = steady_state_test::ForcedOscillator<1>;
constexpr double kPi = 3.14159265358979323846;

Oscillator oscillator() {
  Oscillator o;
  o.C(0, 0) = 0.2;
  return o;
}

// A hook that counts its calls and fires from call `fire_at` on (0: never).
struct CountingInterrupt {
  long calls = 0;
  long fire_at = 0;
  stickslip::InterruptCheck hook() {
    return [this] { return ++calls >= fire_at && fire_at > 0; };
  }
};

bool starts_interrupted(const std::string& message) {
  return message.find("interrupted: options.interrupt returned true") != std::string::npos;
}

TEST(SteadyStateInterrupt, AHookThatNeverFiresChangesNothing) {
  Oscillator sys = oscillator();
  stickslip::ShootingOptions<double> plain;
  const auto reference = stickslip::Shooting<Oscillator>(sys, plain).forced(0, 0.0, Eigen::Vector2d(0.5, 0.0), 2 * kPi);
  ASSERT_TRUE(reference.ok()) << reference.message;
  CountingInterrupt never;
  stickslip::ShootingOptions<double> hooked = plain;
  hooked.interrupt = never.hook();
  const auto orbit = stickslip::Shooting<Oscillator>(sys, hooked).forced(0, 0.0, Eigen::Vector2d(0.5, 0.0), 2 * kPi);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  EXPECT_EQ(orbit.x0, reference.x0);
  EXPECT_EQ(orbit.iterations, reference.iterations);
  // Asked after every step and sample of both runs (256 samples a period): more than 512 times.
  EXPECT_GT(never.calls, 512);
}

TEST(SteadyStateInterrupt, ShootingStopsAtTheCallThatFires) {
  Oscillator sys = oscillator();
  // The first run makes 460 calls (its steps and 256 samples; measured), so call 700 falls in the
  // second run (the first Newton trial): without the stop, 5 backtracking trials would each
  // call it again.
  CountingInterrupt stop{0, 700};
  stickslip::ShootingOptions<double> opt;
  opt.interrupt = stop.hook();
  const auto orbit = stickslip::Shooting<Oscillator>(sys, opt).forced(0, 0.0, Eigen::Vector2d(0.5, 0.0), 2 * kPi);
  EXPECT_EQ(orbit.status, stickslip::ShootingStatus::IntegrationFailed);
  EXPECT_TRUE(starts_interrupted(orbit.message)) << orbit.message;
  EXPECT_EQ(stop.calls, 700);
  // The finite-difference monodromy's runs too: call 1000 falls in the 4 runs after the first
  // run's 460 calls (measured: 1287 calls in all for the first period).
  CountingInterrupt fd{0, 1000};
  opt.interrupt = fd.hook();
  opt.monodromy = stickslip::MonodromyMethod::FiniteDifference;
  const auto fd_orbit = stickslip::Shooting<Oscillator>(sys, opt).forced(0, 0.0, Eigen::Vector2d(0.5, 0.0), 2 * kPi);
  EXPECT_EQ(fd_orbit.status, stickslip::ShootingStatus::IntegrationFailed);
  EXPECT_TRUE(starts_interrupted(fd_orbit.message)) << fd_orbit.message;
  EXPECT_EQ(fd.calls, 1000);
}

TEST(SteadyStateInterrupt, PoincareSectionsStopAtTheCallThatFires) {
  Oscillator sys = oscillator();
  CountingInterrupt stop{0, 1000};
  stickslip::PoincareOptions<double> opt;
  opt.transient_periods = 1000;
  opt.interrupt = stop.hook();
  const auto s = stickslip::poincare_sections(sys, 0, 0.0, Eigen::Vector2d(0.5, 0.0), 2 * kPi, opt);
  EXPECT_EQ(s.status, stickslip::PoincareStatus::IntegrationFailed);
  EXPECT_TRUE(starts_interrupted(s.message)) << s.message;
  EXPECT_EQ(stop.calls, 1000);
}

TEST(SteadyStateInterrupt, ContinuationEndsInterruptedWithItsPoints) {
  Oscillator sys = oscillator();
  bool fire = false;
  stickslip::ShootingOptions<double> opt;
  opt.interrupt = [&fire] { return fire; };
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = 0.5;
  co.parameter_max = 1.5;
  co.initial_step = 0.05;
  stickslip::Continuation<Oscillator> cont(
      sys, [](Oscillator& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, opt, co);
  int points = 0;
  cont.on_point([&](const stickslip::ContinuationPoint<Oscillator>&) { fire = ++points == 3; });
  const auto r = cont.run(0, 0.0, Eigen::Vector2d(0.5, 0.0), 0.5);
  EXPECT_EQ(r.status, stickslip::ContinuationStatus::Interrupted);
  EXPECT_EQ(r.points.size(), 3u);
  EXPECT_TRUE(starts_interrupted(r.message)) << r.message;
  EXPECT_STREQ(stickslip::to_string(r.status), "interrupted");
}

}  // namespace
}  // namespace steady_state_interrupt_test

// Failure messages that name the mechanism which made Newton stall on the period map
// (stall_diagnosis.hpp) and the option that addresses it, and the progress callbacks
// (progress.hpp), on Den Hartog's forced Coulomb oscillator (tests/contact/den_hartog_orbit.hpp).

#include "contact/den_hartog_orbit.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace steady_state_stall_test {  // named: the steady-state test files share one unity TU
namespace {

using contact_test::DenHartogOrbit;
using contact_test::SingleDofParameters;
using namespace steady_state_test;

constexpr double kMass = 2.0, kStiffness = 50.0, kForce = 10.0, kMuK = 0.25;

SingleDofParameters parameters(double omega, double ratio) {
  SingleDofParameters p;
  p.mass = kMass;
  p.stiffness = kStiffness;
  p.force_amplitude = kForce;
  p.force_frequency = omega;
  p.normal_force = ratio * kForce / kMuK;
  return p;
}

bool contains(const std::string& s, const char* what) { return s.find(what) != std::string::npos; }

struct Event {
  double t;
};

// An orbit whose reversal lies 1e-6 T before the section t0 (continuous sliding, closed form):
// started in the mode after the reversal with a velocity of the wrong sign, the run switches at
// once, and the orbit it closes has another mode at t0 + T than at t0: Shooting must say that an
// event sits at the period start and name the remedies (another t0, section_margin).
TEST(SteadyStateStall, OrbitStartingOnItsReversalNamesAnEventAtThePeriodStart) {
  const double w = 0.6 * std::sqrt(kStiffness / kMass), ratio = 0.1;
  const double N = ratio * kForce / kMuK;
  const DenHartogOrbit ref(kMass, kStiffness, kForce, w, kMuK * N, kMuK * N);
  ASSERT_TRUE(ref.valid);
  const double t0 = ref.t1 - 1e-6 * ref.T;
  double x = 0, v = 0;
  ref.state(t0, x, v);
  v += 0.01 * ref.X * w;
  Oscillator sys(parameters(w, ratio), Contact(Law(kMuK, kMuK)));
  stickslip::Shooting<Oscillator> shooting(sys, oscillator_options());
  const auto orbit = shooting.forced(S::SlipPositive, t0, Eigen::Vector4d(x, v, 0, 0), ref.T);
  ASSERT_EQ(orbit.status, stickslip::ShootingStatus::ModeNotPeriodic) << orbit.message;
  EXPECT_TRUE(contains(orbit.message, "an event at the period start")) << orbit.message;
  EXPECT_TRUE(contains(orbit.message, "another t0")) << orbit.message;
  EXPECT_TRUE(contains(orbit.message, "section_margin")) << orbit.message;
}

// The classification itself, from the evidence of the runs (the order in which the mechanisms
// are tested is the specificity: an event on the section explains a jump or a change of the
// event count, not the reverse), and the option each message names.
TEST(SteadyStateStall, EvidenceNamesEachMechanismAndItsOption) {
  const double T = 2.0;
  {  // an event 1 % of T after t0 = 1
    stickslip::StallEvidence<double> e;
    e.note_run(1.0, T, std::vector<Event>{{1.02}, {2.0}}, 0);
    EXPECT_EQ(e.mechanism(), stickslip::StallMechanism::EventAtPeriodStart);
    const std::string c = e.describe(true, 0.0), s = e.describe(false);
    EXPECT_TRUE(contains(c, "an event at the period start")) << c;
    EXPECT_TRUE(contains(c, "ContinuationOptions::section_margin above 0.01")) << c;
    EXPECT_TRUE(contains(s, "another t0")) << s;
  }
  {  // 4 events, then 2: a stick phase vanished between iterates
    stickslip::StallEvidence<double> e;
    e.note_run(0.0, T, std::vector<Event>{{0.3}, {0.6}, {1.3}, {1.6}}, 0);
    e.note_run(0.0, T, std::vector<Event>{{0.5}, {1.5}}, 0);
    e.note_residual(1e-3, 1.2e-3);  // a plateau, not a jump
    EXPECT_EQ(e.mechanism(), stickslip::StallMechanism::Grazing);
    const std::string c = e.describe(true), s = e.describe(false);
    EXPECT_TRUE(contains(c, "a grazing")) << c;
    EXPECT_TRUE(contains(c, "from 4 to 2")) << c;
    EXPECT_TRUE(contains(c, "max_corrector_distance")) << c;
    EXPECT_TRUE(contains(s, "FiniteDifference")) << s;
  }
  {  // tangent events of a variational run count as a grazing too
    stickslip::StallEvidence<double> e;
    e.note_run(0.0, T, std::vector<Event>{{0.5}, {1.5}}, 1);
    EXPECT_EQ(e.mechanism(), stickslip::StallMechanism::Grazing);
  }
  {  // the residual more than doubles: a jump of the map, even where the event count changed
    stickslip::StallEvidence<double> e;
    e.note_run(0.0, T, std::vector<Event>{{0.5}, {1.5}}, 0);
    e.note_run(0.0, T, std::vector<Event>{{0.3}, {0.6}, {1.3}, {1.6}}, 0);
    e.note_residual(1e-4, 5e-3);
    EXPECT_EQ(e.mechanism(), stickslip::StallMechanism::PeriodMapDiscontinuity);
    const std::string c = e.describe(true);
    EXPECT_TRUE(contains(c, "a discontinuity of the period map")) << c;
    EXPECT_TRUE(contains(c, "max_corrector_distance")) << c;
    EXPECT_TRUE(contains(c, "max_step")) << c;
  }
  {  // nothing seen
    stickslip::StallEvidence<double> e;
    e.note_run(0.0, T, std::vector<Event>{{0.5}, {1.5}}, 0);
    e.note_residual(1e-3, 5e-4);
    EXPECT_EQ(e.mechanism(), stickslip::StallMechanism::None);
    EXPECT_TRUE(contains(e.describe(true), "quasi-periodic or chaotic"));
  }
}

// Progress: Shooting calls back once for the guess's run and once per Newton iteration, with a
// residual that ends below the tolerance, CPU seconds that do not decrease, and no time left at
// the converged iterate; Continuation once per point (the start included), with `covered`
// rising to the end of the range and the same parameters as the points.
TEST(SteadyStateStall, ProgressIsReportedPerIterationAndPerPoint) {
  const double w = 0.6 * std::sqrt(kStiffness / kMass), ratio = 0.1;
  const double N = ratio * kForce / kMuK;
  const DenHartogOrbit ref(kMass, kStiffness, kForce, w, kMuK * N, kMuK * N);
  ASSERT_TRUE(ref.valid);
  const double t0 = ref.t1 + ref.T / 4;
  double x = 0, v = 0;
  ref.state(t0, x, v);
  Oscillator sys(parameters(w, ratio), Contact(Law(kMuK, kMuK)));
  std::vector<stickslip::ShootingProgress> seen;
  auto opt = oscillator_options();
  opt.progress = [&seen](const stickslip::ShootingProgress& p) { seen.push_back(p); };
  stickslip::Shooting<Oscillator> shooting(sys, opt);
  const auto orbit = shooting.forced(S::SlipPositive, t0, Eigen::Vector4d(1.1 * x, 0.9 * v, 0, 0), ref.T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  ASSERT_GE(seen.size(), 2u);  // the guess is 10 % off: at least one Newton step
  for (std::size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(seen[k].iteration, static_cast<int>(k));
    if (k > 0) {
      EXPECT_GE(seen[k].cpu_seconds, seen[k - 1].cpu_seconds);
    }
  }
  EXPECT_LE(seen.back().residual, seen.back().tolerance);
  EXPECT_EQ(seen.back().remaining_seconds, 0.0);
  EXPECT_EQ(seen.back().runs, orbit.iterations);
  EXPECT_GT(seen.front().residual, seen.front().tolerance);

  stickslip::ContinuationOptions<double> co;
  co.parameter_min = w;
  co.parameter_max = 1.2 * w;
  co.initial_step = 0.02;
  co.max_step = 0.1;
  std::vector<stickslip::ContinuationProgress> points;
  co.progress = [&points](const stickslip::ContinuationProgress& p) { points.push_back(p); };
  stickslip::Continuation<Oscillator> cont(
      sys, [](Oscillator& o, double wp) { o = Oscillator(parameters(wp, 0.1), o.contact()); },
      [](double wp) { return 2 * contact_test::kDenHartogPi / wp; }, oscillator_options(), co);
  cont.start_mode([](Oscillator& o, double t, const Oscillator::State& xs, const S&) { return o.consistent_mode(t, xs); });
  const auto branch = cont.run(S::SlipPositive, t0, orbit.x0, w);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_EQ(points.size(), branch.points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(points[k].points, static_cast<int>(k) + 1);
    EXPECT_EQ(points[k].parameter, branch.points[k].parameter);
    EXPECT_NEAR(points[k].covered, (branch.points[k].parameter - w) / (0.2 * w), 1e-12);
    if (k > 0) {
      EXPECT_GE(points[k].remaining_seconds, 0.0);
    }
  }
  EXPECT_EQ(points.front().remaining_seconds, -1.0);  // nothing covered yet: not known
  EXPECT_EQ(points.front().covered, 0.0);
  EXPECT_GT(points.back().covered, 0.5);
}

}  // namespace
}  // namespace steady_state_stall_test

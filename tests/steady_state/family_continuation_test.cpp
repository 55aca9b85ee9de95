// Continuation through a family of orbits: Den Hartog's forced Coulomb oscillator
// (tests/contact/den_hartog_orbit.hpp) followed in the friction ratio r = mu N / F0 at a fixed
// frequency, from continuous sliding (closed form) through stick-slip into the stuck-all-period
// orbits, and back down from a stuck orbit. Stuck all period, the oscillator stays at any x with
// |k x| + F0 <= mu N (|k x - F0 cos wt| <= mu N for all t): a family, M - I singular (M = [1 T;
// 0 1]: x' is constant in stick and moves x). Before the corrector and the start tangent had the
// minimum-norm step, the branch up ended with StepTooSmall at the family (a singular corrector
// matrix) and the branch down did not start (StartFailed: M - I singular at p0).

#include "contact/den_hartog_orbit.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace steady_state_family_test {  // named: the steady-state test files share one unity TU
namespace {

using contact_test::DenHartogOrbit;
using contact_test::SingleDofParameters;
using namespace steady_state_test;

constexpr double kMass = 2.0, kStiffness = 50.0, kForce = 10.0, kMu = 0.25;
constexpr double kOmega = 3.0;  // beta = 0.6: below resonance
constexpr double kT = 2 * contact_test::kDenHartogPi / kOmega;

double normal_force(double ratio) { return ratio * kForce / kMu; }

SingleDofParameters parameters(double ratio) {
  SingleDofParameters p;
  p.mass = kMass;
  p.stiffness = kStiffness;
  p.force_amplitude = kForce;
  p.force_frequency = kOmega;
  p.normal_force = normal_force(ratio);
  return p;
}

stickslip::Continuation<Oscillator> ratio_continuation(Oscillator& sys, double lo, double hi,
                                                       int direction, double max_corrector_distance = 0) {
  stickslip::ContinuationOptions<double> co;
  co.max_corrector_distance = max_corrector_distance;
  // A fixed section: where the branch enters the stuck family, a section moved away from the
  // stick-slip orbits' events leads the corrector along other paths onto the family's 2-D set,
  // and the checks below follow the branch through stick-slip on the start's section.
  co.section_margin = 0;
  co.parameter_min = lo;
  co.parameter_max = hi;
  co.initial_step = 0.01;
  co.max_step = 0.05;
  co.max_points = 400;
  co.direction = direction;
  stickslip::Continuation<Oscillator> cont(
      sys, [](Oscillator& s, double r) { s = Oscillator(parameters(r), s.contact()); },
      [](double) { return kT; }, oscillator_options(), co);
  // The orbit's mode at t0 changes along the branch (stops appear, then it sticks throughout).
  cont.start_mode([](Oscillator& s, double t, const Oscillator::State& x, const S&) {
    return s.consistent_mode(t, x);
  });
  return cont;
}

// Checks of one point against the closed forms. Continuous sliding: the runs' rtol 1e-10 and the
// Newton tolerance 1e-9 max(1, |x|) put the orbit within ~1e-8 of its scale (the Den Hartog
// shooting test); 1e-7 of the amplitude. Stuck all period: no event, x' = 0 to the Newton
// tolerance, k |x| + F0 <= mu N (the family's bound; 1e-9 for round-off), multipliers 1 (M is
// exact here: the stick rhs is linear).
void check_point(const stickslip::ContinuationPoint<Oscillator>& pt, int& sliding, int& stuck) {
  const double r = pt.parameter, N = normal_force(r);
  SCOPED_TRACE(::testing::Message() << "ratio " << r);
  const DenHartogOrbit ref(kMass, kStiffness, kForce, kOmega, kMu * N, kMu * N);
  if (ref.valid) {
    ++sliding;
    double x = 0, v = 0;
    ref.state(pt.orbit.t0, x, v);
    EXPECT_NEAR(pt.orbit.x0[0], x, 1e-7 * ref.X);
    EXPECT_NEAR(pt.orbit.x0[1], v, 1e-7 * ref.X * kOmega);
    EXPECT_NEAR(pt.orbit.amplitudes[0], ref.X, 1e-7 * ref.X);
  }
  if (r > 1.0 + 1e-6) {  // mu N > F0: only stuck orbits exist (the force never overcomes mu N
                          // at a stuck x = 0, and a moving orbit would have to start from a stop)
    ++stuck;
    EXPECT_TRUE(pt.orbit.events.empty());
    EXPECT_EQ(pt.orbit.mode, S::Stick);
    EXPECT_LE(std::abs(pt.orbit.x0[1]), 1e-9);
    EXPECT_LE(kStiffness * std::abs(pt.orbit.x0[0]) + kForce, kMu * N + 1e-9);
    for (Eigen::Index k = 0; k < pt.orbit.floquet.multipliers.size(); ++k)
      EXPECT_NEAR(std::abs(pt.orbit.floquet.multipliers[k]), 1.0, 1e-9);
  }
}

// Up from continuous sliding (r = 0.3) through stick-slip into the family (r > 1). Where the
// branch reaches the family the arclength hyperplane cuts it (a 2-D set in (x, r)) and the
// corrector may land anywhere on it: the branch jumps (here from r ~ 0.92 to the family), and
// the points there are checked against the family's closed form.
TEST(SteadyStateFamily, BranchInTheFrictionRatioEntersTheStuckFamily) {
  const double r0 = 0.3;
  Oscillator sys(parameters(r0), Contact(Law(kMu, kMu)));
  const DenHartogOrbit ref(kMass, kStiffness, kForce, kOmega, kMu * normal_force(r0),
                           kMu * normal_force(r0));
  ASSERT_TRUE(ref.valid);
  const double t0 = ref.t1 + ref.T / 4;  // mid of the x' > 0 half period
  double x = 0, v = 0;
  ref.state(t0, x, v);
  auto cont = ratio_continuation(sys, 0.2, 1.5, +1);
  const auto branch = cont.run(S::SlipPositive, t0, Eigen::Vector4d(x, v, 0, 0), r0);
  ASSERT_TRUE(branch.completed()) << to_string(branch.status) << ": " << branch.message;
  int sliding = 0, stuck = 0, stick_slip = 0;
  for (const auto& pt : branch.points) {
    check_point(pt, sliding, stuck);
    stick_slip += pt.orbit.events.size() == 4 ? 1 : 0;  // two stops and two breakaways
  }
  EXPECT_GE(sliding, 3);
  EXPECT_GE(stick_slip, 3);
  EXPECT_GE(stuck, 2);
}

// The largest distance |y_k - y_{k-1}| / ds_k between consecutive points (y = (x, x', r), the
// periodic components and the parameter; ds_k the step that produced point k).
double largest_relative_jump(const stickslip::ContinuationResult<Oscillator>& branch) {
  double worst = 0;
  for (std::size_t k = 1; k < branch.points.size(); ++k) {
    const auto& a = branch.points[k - 1];
    const auto& b = branch.points[k];
    const Eigen::Vector3d ya(a.orbit.x0[0], a.orbit.x0[1], a.parameter), yb(b.orbit.x0[0], b.orbit.x0[1], b.parameter);
    worst = std::max(worst, (yb - ya).norm() / b.step);
  }
  return worst;
}

// max_corrector_distance: the branch of the test above jumps onto the stuck family (the
// arclength hyperplane cuts the 2-D family and the corrector lands anywhere on the cut: from
// r ~ 0.92 to 1.3, many steps away). With the check at 2 ds every accepted point lies within
// ds (prediction) + 2 ds (correction) of the previous one, by the triangle inequality.
TEST(SteadyStateFamily, CorrectorDistanceCheckRejectsTheJumpOntoTheFamily) {
  const double r0 = 0.3;
  const DenHartogOrbit ref(kMass, kStiffness, kForce, kOmega, kMu * normal_force(r0), kMu * normal_force(r0));
  ASSERT_TRUE(ref.valid);
  const double t0 = ref.t1 + ref.T / 4;
  double x = 0, v = 0;
  ref.state(t0, x, v);
  Oscillator free_sys(parameters(r0), Contact(Law(kMu, kMu)));
  auto unchecked = ratio_continuation(free_sys, 0.2, 1.5, +1);
  const auto jumping = unchecked.run(S::SlipPositive, t0, Eigen::Vector4d(x, v, 0, 0), r0);
  EXPECT_GT(largest_relative_jump(jumping), 3.0);  // the jump the check is for
  Oscillator sys(parameters(r0), Contact(Law(kMu, kMu)));
  auto checked = ratio_continuation(sys, 0.2, 1.5, +1, 2.0);
  const auto branch = checked.run(S::SlipPositive, t0, Eigen::Vector4d(x, v, 0, 0), r0);
  ASSERT_GE(branch.points.size(), 2u) << to_string(branch.status) << ": " << branch.message;
  EXPECT_LE(largest_relative_jump(branch), 3.0 + 1e-9);
}

// Down from an orbit of the family (x = 0 stuck, r = 1.25) to the family's edge r = 1: the start
// tangent is the minimum-norm one (x stays), and so is every step: x0 = 0 at every point.
TEST(SteadyStateFamily, BranchStartsOnTheStuckFamilyAndCrossesItTheLeast) {
  const double r0 = 1.25;
  Oscillator sys(parameters(r0), Contact(Law(kMu, kMu)));
  auto cont = ratio_continuation(sys, 1.0, 1.3, -1);
  const auto branch = cont.run(S::Stick, 0.0, Eigen::Vector4d::Zero(), r0);
  ASSERT_TRUE(branch.completed()) << to_string(branch.status) << ": " << branch.message;
  int sliding = 0, stuck = 0;
  for (const auto& pt : branch.points) {
    check_point(pt, sliding, stuck);
    EXPECT_EQ(pt.orbit.x0[0], 0.0);
  }
  EXPECT_GE(stuck, 5);
  EXPECT_LT(branch.points.back().parameter, 1.01);
}

}  // namespace
}  // namespace steady_state_family_test

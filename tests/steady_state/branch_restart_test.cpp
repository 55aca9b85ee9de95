// RestartingContinuation (steady_state/branch_restart.hpp) on a harmonically forced Coulomb
// oscillator with mu_s = 1.5 mu_k and heavy friction (mu_k N = 0.5 F0), two stick phases per
// period, followed up in frequency: the continuation stops where the period map is discontinuous
// (the corrector's residual jumps along its Newton step; a stick phase that ends at mu_s N,
// entered or not by a trajectory a little above or below, moves the orbit by a finite amount).
//  - without restarts the branch ends StepTooSmall there, short of the range's end;
//  - with restarts a later segment lies beyond the stall, and each of its orbits is a genuine
//    periodic orbit (re-run over its period: the state returns) whose amplitude equals that of a
//    long transient at its frequency from the state the restart began from (an independent
//    computation: HybridStepper alone);
//  - bad options throw std::invalid_argument naming the option.

#include "steady_state/steady_state_test_support.hpp"

#include <stickslip/steady_state/branch_restart.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace steady_state_branch_restart_test {  // named: the steady-state test files share one unity TU
namespace {

using namespace steady_state_test;

constexpr double kPi = 3.14159265358979323846;
constexpr double kMass = 2.0, kStiffness = 50.0, kForce = 10.0, kMuK = 0.25, kRatio = 0.5;
const double kOmegaN = std::sqrt(kStiffness / kMass);

// The oscillator at beta = omega / omega_n (the continuation parameter: order one).
contact_test::SingleDofParameters params(double beta) {
  contact_test::SingleDofParameters p;
  p.mass = kMass;
  p.stiffness = kStiffness;
  p.force_amplitude = kForce;
  p.force_frequency = beta * kOmegaN;
  p.normal_force = kRatio * kForce / kMuK;
  return p;
}

Oscillator oscillator(double beta) { return Oscillator(params(beta), Contact(Law(1.5 * kMuK, kMuK))); }
double period(double beta) { return 2 * kPi / (beta * kOmegaN); }

struct Scene {
  Oscillator sys = oscillator(kLo);
  stickslip::ContinuationOptions<double> co;
  stickslip::RestartOptions<double> ro;
  static constexpr double kLo = 0.33, kHi = 0.40;
  Scene() {
    co.parameter_min = kLo;
    co.parameter_max = kHi;
    co.initial_step = 0.01;
    co.max_step = 0.05;
    co.max_points = 300;
    co.max_corrector_distance = 2;
    // The section stays at the end of the start's transient, t0 = 40 T (not t0 mod T): there
    // the branch stalls short of the range's end (near beta = 0.353), the stall the restarts
    // are tested on.
    co.wrap_section = false;
    ro.gap = 0.02;
    ro.max_restarts = 3;
    ro.settle_periods = 30;
    ro.max_period = 4;
    ro.record_periods = 12;
  }
  stickslip::RestartingContinuation<Oscillator> make() {
    stickslip::RestartingContinuation<Oscillator> rc(
        sys, [](Oscillator& o, double b) { o = oscillator(b); }, period, oscillator_options(), co, ro);
    rc.start_mode([](Oscillator& o, double t, const Oscillator::State& x, const S&) { return o.consistent_mode(t, x); });
    return rc;
  }
  // The branch from the end of a 40-period transient from rest at kLo.
  stickslip::RestartedBranch<Oscillator> run() {
    auto rc = make();
    stickslip::HybridStepper<Oscillator, stickslip::DormandPrince54> st(
        sys, stickslip::ShootingOptions<double>::tight_stepper());
    const double T = period(kLo);
    const auto tr = st.integrate(S::Stick, 0.0, Eigen::Vector4d::Zero(), 40 * T);
    EXPECT_TRUE(tr.ok()) << tr.message;
    Eigen::Vector4d x = tr.x;
    x[2] = x[3] = 0;
    return rc.run(tr.mode, 40 * T, x, kLo);
  }
};

// The farthest parameter of a segment.
double farthest(const stickslip::BranchSegment<Oscillator>& s) {
  double f = -1;
  for (const auto& pt : s.branch.points) f = std::max(f, pt.parameter);
  return f;
}

// max |x| over `periods` forcing periods after a transient of 200 periods at beta from
// (mode, t0, x0) (dense output at T/512 besides every step: the peak is sampled within
// (2 pi / 512)^2 / 8 ~ 2e-5 of the amplitude at worst, at a smooth maximum of x).
double transient_amplitude(double beta, int periods, S mode, double t0, const Eigen::Vector4d& x0) {
  Oscillator sys = oscillator(beta);
  const double T = period(beta);
  stickslip::StepperOptions<double> o = stickslip::ShootingOptions<double>::tight_stepper();
  stickslip::HybridStepper<Oscillator, stickslip::DormandPrince54> settle(sys, o);
  const auto tr = settle.integrate(mode, t0, x0, t0 + 200 * T);
  EXPECT_TRUE(tr.ok()) << tr.message;
  struct Peak : stickslip::NullObserver {
    double a = 0;
    bool on_step(double, const Eigen::Vector4d& x, const S&) {
      a = std::max(a, std::abs(x[0]));
      return true;
    }
    bool on_sample(double t, const Eigen::Vector4d& x, const S& m) { return on_step(t, x, m); }
  } peak;
  o.output_interval = T / 512;
  stickslip::HybridStepper<Oscillator, stickslip::DormandPrince54> record(sys, o);
  const auto last = record.integrate(tr.mode, t0 + 200 * T, tr.x, t0 + (200 + periods) * T, peak);
  EXPECT_TRUE(last.ok()) << last.message;
  return peak.a;
}

TEST(SteadyStateBranchRestart, PlainContinuationStallsAtTheDiscontinuity) {
  Scene s;
  s.ro.max_restarts = 0;
  const auto r = s.run();
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_EQ(r.restarts, 0);
  EXPECT_EQ(r.status, stickslip::ContinuationStatus::StepTooSmall) << r.message;
  EXPECT_LT(farthest(r.segments[0]), 0.36) << r.message;  // short of the range's end 0.40
}

TEST(SteadyStateBranchRestart, RestartCarriesTheBranchPastTheStall) {
  Scene s;
  int progress_calls = 0, last_points = 0;
  bool points_grow = true;
  s.co.progress = [&](const stickslip::ContinuationProgress& pr) {
    ++progress_calls;
    points_grow = points_grow && pr.points == last_points + 1;
    last_points = pr.points;
  };
  const auto r = s.run();
  ASSERT_GE(r.segments.size(), 2u) << r.message;
  const auto& first = r.segments[0];
  EXPECT_EQ(first.kind, stickslip::SegmentKind::Start);
  EXPECT_EQ(first.branch.status, stickslip::ContinuationStatus::StepTooSmall);
  const double stall = farthest(first);
  EXPECT_LT(stall, 0.36);
  // The progress callback sees every point of every segment, numbered over the whole branch.
  EXPECT_EQ(static_cast<std::size_t>(progress_calls), r.points());
  EXPECT_TRUE(points_grow);
  EXPECT_EQ(r.restarts, static_cast<int>(r.segments.size() - 1 + r.failed.size()));
  std::printf("branch restart: stall at beta %.5f; %zu segments, %zu failed restarts, %zu points\n", stall,
              r.segments.size(), r.failed.size(), r.points());
  for (const auto& f : r.failed) std::printf("  failed at %.4f: %s\n", f.parameter, f.reason.c_str());
  int checked = 0;
  for (std::size_t k = 1; k < r.segments.size(); ++k) {
    const auto& seg = r.segments[k];
    SCOPED_TRACE(::testing::Message() << "segment " << k << " from beta " << seg.start_parameter);
    EXPECT_NE(seg.kind, stickslip::SegmentKind::Start);
    EXPECT_EQ(seg.kind == stickslip::SegmentKind::Subharmonic, seg.period_multiple > 1);
    EXPECT_FALSE(seg.after.empty());
    // Past the stall by at least one gap (restarts settle one gap beyond the farthest point).
    EXPECT_GE(seg.start_parameter, stall + s.ro.gap - 1e-12);
    ASSERT_FALSE(seg.branch.points.empty());
    for (const auto& pt : seg.branch.points) {
      // A genuine orbit: re-run over its period k T from its state, the state returns to within
      // Newton's tolerance 1e-9 max(1, |x|) plus the re-run's integration error (rtol 1e-10 over
      // one period of O(1) states): 1e-8.
      EXPECT_NEAR(pt.orbit.period, seg.period_multiple * period(pt.parameter), 1e-12);
      Oscillator sys = oscillator(pt.parameter);
      const auto re = stickslip::run_period(sys, pt.orbit.mode, pt.orbit.t0, pt.orbit.x0, pt.orbit.period,
                                            oscillator_options(), false);
      ASSERT_TRUE(re.ok()) << re.message;
      EXPECT_LT((re.x_end - pt.orbit.x0).head(2).cwiseAbs().maxCoeff(), 1e-8);
    }
    // The segment's first orbit against a long transient at its frequency from the state the
    // restart started from (the stalled segment's last orbit: where a slow sweep jumps to; 200
    // periods from rest end 1.3 % away: another stick-slip orbit or a slower transient), by
    // HybridStepper alone. Two stick phases per period collapse the state (a multiplier 0), so
    // 200 periods reach the orbit to the integration error; the transient's peak is sampled at
    // T/512 (relative error <= 2e-5 of a smooth maximum, see transient_amplitude), the orbit's
    // over 256 samples per period plus every step and event (ShootingOptions::
    // samples_per_period): 1e-4 relative.
    const auto& pt = seg.branch.points.front();
    const auto& from = r.segments[k - 1].branch.points.back().orbit;
    const double ref = transient_amplitude(pt.parameter, seg.period_multiple, from.mode, from.t0, from.x0);
    EXPECT_NEAR(pt.orbit.amplitudes[0], ref, 1e-4 * ref);
    ++checked;
  }
  EXPECT_GE(checked, 1);
}

// A range narrower than the first step: the first corrected point lies beyond parameter_max, so
// the segment is Completed with its start alone. It left by the far end (exit_parameter), not
// back past its start: the whole is Completed, without restarts.
TEST(SteadyStateBranchRestart, FirstStepPastTheEndOfANarrowRangeCompletesWithoutRestarts) {
  Scene s;
  s.co.wrap_section = true;  // from t0 mod T the first step advances beta by ~1e-3
  s.co.parameter_max = Scene::kLo + 2e-4;
  s.ro.gap = 1e-4;
  const auto r = s.run();
  EXPECT_EQ(r.status, stickslip::ContinuationStatus::Completed) << r.message;
  ASSERT_EQ(r.segments.size(), 1u) << r.message;
  EXPECT_EQ(r.restarts, 0);
  EXPECT_EQ(r.segments[0].branch.points.size(), 1u);
  EXPECT_GT(r.segments[0].exit_parameter, s.co.parameter_max);
}

TEST(SteadyStateBranchRestart, BadOptionsThrowNamingTheParameter) {
  auto expect_throw = [](auto change, const std::string& name) {
    Scene s;
    change(s);
    try {
      s.make();
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  expect_throw([](Scene& s) { s.ro.gap = 0; }, "restart.gap");
  expect_throw([](Scene& s) { s.ro.gap = 0.07; }, "restart.gap");  // the range is 0.07 wide
  expect_throw([](Scene& s) { s.ro.max_restarts = -1; }, "restart.max_restarts");
  expect_throw([](Scene& s) { s.ro.settle_periods = -1; }, "restart.settle_periods");
  expect_throw([](Scene& s) { s.ro.max_period = 0; }, "restart.max_period");
  expect_throw([](Scene& s) { s.ro.record_periods = 7; }, "restart.record_periods");
  expect_throw([](Scene& s) { s.ro.recurrence_tolerance = 0; }, "restart.recurrence_tolerance");
  expect_throw([](Scene& s) { s.ro.stall_points = 1; }, "restart.stall_points");
  expect_throw([](Scene& s) { s.ro.stall_points = 5; }, "restart.stall_progress");
  expect_throw([](Scene& s) { s.co.max_points = 0; }, "options.max_points");
  // p0 outside the range
  Scene s;
  auto rc = s.make();
  EXPECT_THROW(rc.run(S::Stick, 0.0, Eigen::Vector4d::Zero(), 0.5), std::invalid_argument);
}

}  // namespace
}  // namespace steady_state_branch_restart_test

// simulate() with Integrator::Exponential (ExactLinearStepper on FrictionDampedSystem::linear_part)
// on the work-precision study's three regimes (2.0 N gross slip, 2.6 N stick-slip,
// 26 N stick) of the paper's T-frame. Reference: the library's Dormand-Prince at rtol 1e-12, an
// independent integrator of the same equations (it never calls linear_part). The energy audit is
// checked against its own largest term.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace exponential_run_test {

using namespace model_test;

/// "1.2e-09" (for RecordProperty: the margins of each tolerance in the XML output).
std::string scientific(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", v);
  return buf;
}

struct ModelRun {
  Recorder rec;
  HybridResult<double, System::State, DamperStates> result;
  double E0 = 0;
};

/// Five excitation periods (2 pi / 200 rad/s each, the work-precision study's horizon) from rest,
/// tip samples every 1e-4 s. Under the sanitizers (STICKSLIP_SANITIZED) two: the 2.6 N run has 87
/// events in five periods and 36 in the first two (measured), and at five it took 15 s of CPU
/// there, the second longest test of that suite.
#if defined(STICKSLIP_SANITIZED)
constexpr double kRunPeriods = 2;
#else
constexpr double kRunPeriods = 5;
#endif
ModelRun run_scene(System& sys, Integrator integrator) {
  RunOptions<double> opt;
  opt.integrator = integrator;
  opt.stepper.rtol = 1e-12;
  opt.stepper.atol = 1e-15;
  opt.stepper.output_interval = 1e-4;
  opt.stepper.max_steps = 10'000'000;
  ModelRun r;
  r.result = run_from_rest(sys, kRunPeriods * 2 * M_PI / 200.0, opt, r.rec, &r.E0);
  return r;
}

class ExponentialRun : public ::testing::TestWithParam<double> {};

TEST_P(ExponentialRun, SameEventsTipHistoryAndClosedEnergyAuditAsDopriAtRtol1e12) {
  const double preload = GetParam();
  const TScene s = make_t_frame(6);
  System sys(s.frame, s.basis, paper_dampers(s, preload), paper_load(s));
  const ModelRun ref = run_scene(sys, Integrator::DormandPrince54);
  const ModelRun ex = run_scene(sys, Integrator::Exponential);
  ASSERT_EQ(ref.result.status, Status::Success) << ref.result.message;
  ASSERT_EQ(ex.result.status, Status::Success) << ex.result.message;

  // Event sequence: same count, same transitions, times within 1e-9 s. The two runs each locate
  // events to 1e-12 s on solutions that agree to ~1e-10 relative (DOPRI's global error at rtol
  // 1e-12 over ~30 periods); a guard's crossing rate of order 1 (scaled) turns that into 1e-10 s.
  for (std::size_t k = 0; k < std::min(ex.rec.events.size(), ref.rec.events.size()); ++k)
    if (!(ex.rec.events[k].from == ref.rec.events[k].from) || !(ex.rec.events[k].to == ref.rec.events[k].to) ||
        std::abs(ex.rec.events[k].t - ref.rec.events[k].t) > 1e-9) {
      std::printf("first differing event %zu: exponential at %.12f s (%d %d -> %d %d), DOPRI at %.12f s "
                  "(%d %d -> %d %d)\n", k, ex.rec.events[k].t, static_cast<int>(ex.rec.events[k].from[0]),
                  static_cast<int>(ex.rec.events[k].from[1]), static_cast<int>(ex.rec.events[k].to[0]),
                  static_cast<int>(ex.rec.events[k].to[1]), ref.rec.events[k].t,
                  static_cast<int>(ref.rec.events[k].from[0]), static_cast<int>(ref.rec.events[k].from[1]),
                  static_cast<int>(ref.rec.events[k].to[0]), static_cast<int>(ref.rec.events[k].to[1]));
      break;
    }
  ASSERT_EQ(ex.rec.events.size(), ref.rec.events.size());
  for (std::size_t k = 0; k < ref.rec.events.size(); ++k) {
    EXPECT_EQ(ex.rec.events[k].from, ref.rec.events[k].from) << "event " << k;
    EXPECT_EQ(ex.rec.events[k].to, ref.rec.events[k].to) << "event " << k;
    EXPECT_NEAR(ex.rec.events[k].t, ref.rec.events[k].t, 1e-9) << "event " << k;
  }
  // The regimes the preloads stand for on this mesh: stick at 26 N has no event; slip at 2.0 and
  // 2.6 N does (the span holds the first stick-slip cycles, each with several events).
  if (preload > 10) EXPECT_TRUE(ref.rec.events.empty());
  else EXPECT_GE(ref.rec.events.size(), 4u);

  // Tip history at the same sample times: max difference relative to the tip's amplitude. 1e-7:
  // an event time shift of 1e-10 s moves the post-event state by rate * 1e-10 ~ 1e-8 of the
  // amplitude at 200 rad/s and the modes' rates, and DOPRI's own error is ~1e-10 relative.
  ASSERT_EQ(ex.rec.t.size(), ref.rec.t.size());
  const Eigen::VectorXd tip = nodal(s.basis, s.tip, Dof::X);
  const Index n = sys.num_modes();
  double amp = 0, diff = 0;
  for (std::size_t k = 0; k < ref.rec.t.size(); ++k) {
    ASSERT_EQ(ex.rec.t[k], ref.rec.t[k]);
    const double a = tip.dot(ref.rec.x[k].head(n)), b = tip.dot(ex.rec.x[k].head(n));
    amp = std::max(amp, std::abs(a));
    diff = std::max(diff, std::abs(a - b));
  }
  ASSERT_GT(amp, 0.0);
  RecordProperty("events", static_cast<int>(ref.rec.events.size()));
  RecordProperty("tip_relative_difference", scientific(diff / amp));
  EXPECT_LT(diff / amp, 1e-7) << "max tip difference " << diff << " m, amplitude " << amp << " m";

  // Energy audit: (E - E0) - (W_ext - D_visc - D_fric + W_slope) at t_end against the largest
  // term. Measured (this scene, Release): 1.9e-9, 2.5e-10, 7.4e-9 at 2.0, 2.6, 26 N - larger than
  // the 5-point Gauss-Legendre quadratures alone would leave at 8 grid steps per shortest period
  // (~1e-12) and than DOPRI's at rtol 1e-12 (1e-12..1e-11); see docs/performance.md. 1e-7 bounds them with margin and still
  // fails for an audit that misses one event's work (a switch moves ~1e-3 of the energy). DOPRI's
  // residual at rtol 1e-12 is recorded beside it for comparison.
  auto relative_residual = [&](const ModelRun& r) {
    const auto eb = sys.energy_balance(r.result.mode, r.result.t, r.result.x, r.E0);
    const double largest = std::max({std::abs(eb.mechanical), std::abs(eb.external_work),
                                     eb.viscous_dissipation, eb.friction_dissipation, std::abs(eb.slope_work)});
    return largest > 0 ? std::abs(eb.residual) / largest : std::abs(eb.residual);
  };
  const double res_ex = relative_residual(ex), res_ref = relative_residual(ref);
  RecordProperty("energy_relative_residual", scientific(res_ex));
  RecordProperty("energy_relative_residual_dopri", scientific(res_ref));
  EXPECT_LT(res_ex, 1e-7) << "relative audit residual " << res_ex << " (DOPRI: " << res_ref << ")";
}

// Under the sanitizers (STICKSLIP_SANITIZED) the 2.0 N gross-slip run is left out (52 s there,
// the longest test of that suite): 2.6 N still slides with moving contact points between its
// stick phases, so the slipping path (frozen A_m, remainder, refreshes) stays under ASan + UBSan.
#if defined(STICKSLIP_SANITIZED)
constexpr double kRegimePreloads[] = {2.6, 26.0};
#else
constexpr double kRegimePreloads[] = {2.0, 2.6, 26.0};
#endif
INSTANTIATE_TEST_SUITE_P(Regimes, ExponentialRun, ::testing::ValuesIn(kRegimePreloads),
                         [](const ::testing::TestParamInfo<double>& i) {
                           return "N0_" + std::to_string(static_cast<int>(10 * i.param)) + "dN";
                         });

TEST(ExponentialRunParse, NamesRoundTrip) {
  EXPECT_EQ(parse_integrator("exponential"), Integrator::Exponential);
  EXPECT_EQ(parse_integrator("exact"), Integrator::Exponential);
  EXPECT_STREQ(to_string(Integrator::Exponential), "exponential");
  EXPECT_THROW(parse_integrator("expo"), std::invalid_argument);
}

}  // namespace exponential_run_test

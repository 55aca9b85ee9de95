// Integrator::Auto (choose_integrator's rule, simulate()'s default) and simulate()'s
// event-sequence convergence check (RunOptions::check_event_sequence, TradeRow::sequence_differs).
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

namespace auto_integrator_test {

using namespace model_test;

// ---------------------------------------------------------------- Integrator::Auto

/// The cantilever's one bending mode with one damper on a spring, pressed on the member at a
/// fixed contact: psi_u = 0 along the member, so the damper is a linear oscillator on its own
/// spring, with Coulomb friction against a grounded surface. Started with the spring stretched
/// past mu_s N0 / k (1 mm: 1 N against 0.35 N), so that it slips, reverses and sticks.
System slider(const Cantilever& c, bool moving_contact) {
  ModelOptions<double> opt;
  opt.moving_contact = moving_contact;
  std::vector<PointDamper<double>> d;
  d.emplace_back(c.member, 0.15, 0.01, 1e3, 1.0, CoulombLaw<double>(0.35, 0.3));
  return System(c.frame, c.basis, d, {}, opt);
}

/// The same with a regularised law of slope mu / v_eps = 0.3 / 1e-6 at V = 0: its slip equation
/// has the real rate ~ mu'(0) N0 / m = 3e7 1/s, against 261 rad/s (the bending mode) and
/// sqrt(k / m) = 316 rad/s (the damper's oscillator) to resolve.
System regularised_slider(const Cantilever& c) {
  ModelOptions<double> opt;
  opt.moving_contact = false;
  std::vector<PointDamper<double>> d;
  d.emplace_back(c.member, 0.15, 0.01, 1e3, 1.0, RegularisedLaw<double>(0.3, 1e-6));
  return System(c.frame, c.basis, d, {}, opt);
}

/// The run of `sys` from the stretched spring with `integrator`.
SimulationResult<System> run(System& sys, Integrator integrator, double rtol, double t_end) {
  System::State x0 = sys.initial_state();
  x0[sys.x_offset()] = 1e-3;
  DamperStates mode = sys.requested_mode();
  EXPECT_TRUE(sys.make_consistent(mode, 0.0, x0));
  RunOptions<double> opt;
  opt.integrator = integrator;
  opt.stepper.rtol = rtol;
  opt.stepper.atol = rtol * 1e-3;
  return simulate(sys, mode, 0.0, x0, t_end, opt);
}

/// The stated stiffness test of choose_integrator, evaluated here from the system's rates: the
/// fastest non-oscillating decay over the fastest other rate, against 33 / rtol^(1/3).
double stiffness_ratio(const System& sys, double span) {
  double decay = 0, resolved = 1.0 / span;
  for (const auto& r : sys.step_rates()) {
    const double mag = std::abs(r.lambda);
    if (r.lambda.real() < 0 && std::abs(r.lambda.imag()) <= -r.lambda.real())
      decay = std::max(decay, mag);
    else
      resolved = std::max(resolved, mag);
  }
  return decay / resolved;
}

/// Auto's run equals the run of the method it chose, named explicitly (same final state to the
/// bit, same counters), and names that method.
void expect_same_as_explicit(System (*make)(const Cantilever&), Integrator expected, double rtol,
                             double t_end, long min_events) {
  const Cantilever c;
  System a = make(c), b = make(c);
  const auto ra = run(a, Integrator::Auto, rtol, t_end);
  const auto rb = run(b, expected, rtol, t_end);
  ASSERT_TRUE(ra.ok()) << ra.message;
  ASSERT_TRUE(rb.ok()) << rb.message;
  EXPECT_EQ(ra.method, to_string(expected)) << ra.method_reason;
  EXPECT_EQ(rb.method_reason, "options.integrator");
  EXPECT_EQ(ra.x, rb.x);
  EXPECT_EQ(ra.stats.events, rb.stats.events);
  EXPECT_EQ(ra.stats.accepted_steps, rb.stats.accepted_steps);
  EXPECT_GE(ra.stats.events, min_events) << "the slider must slip and stick";
}

System fixed_slider(const Cantilever& c) { return slider(c, false); }

// Fixed contact, Coulomb law, no time_function load: every mode exactly linear (the system says
// so), hence the exponential method.
TEST(AutoIntegrator, GroundedCoulombSliderTakesTheExponentialMethod) {
  const Cantilever c;
  System sys = slider(c, false);
  EXPECT_TRUE(sys.every_mode_exact());
  const IntegratorChoice choice = choose_integrator(sys, sys.requested_mode(), 0.0, sys.initial_state(), 0.05, 1e-8);
  EXPECT_EQ(choice.integrator, Integrator::Exponential) << choice.reason;
  expect_same_as_explicit(&fixed_slider, Integrator::Exponential, 1e-8, 0.05, 2);
}

// The paper's T-frame with its two dampers on moving contacts: not every mode exact; its rates
// are the structure's modes and the dampers' oscillators (undamped: nothing decays), so not
// stiff: Dormand-Prince.
TEST(AutoIntegrator, MovingContactsTakeDormandPrince) {
  const TScene s = make_t_frame(4);
  System sys(s.frame, s.basis, paper_dampers(s, 3.0), paper_load(s));
  EXPECT_FALSE(sys.every_mode_exact());
  EXPECT_LE(stiffness_ratio(sys, 0.02), 33.0 / std::cbrt(1e-6));
  const IntegratorChoice choice = choose_integrator(sys, sys.requested_mode(), 0.0, sys.initial_state(), 0.02, 1e-6);
  EXPECT_EQ(choice.integrator, Integrator::DormandPrince54) << choice.reason;
  // The run equals Dormand-Prince's (a short one: 2 ms of the 200 rad/s load from rest).
  System a(s.frame, s.basis, paper_dampers(s, 3.0), paper_load(s));
  System b(s.frame, s.basis, paper_dampers(s, 3.0), paper_load(s));
  Recorder ra_rec, rb_rec;
  RunOptions<double> opt;
  opt.stepper.rtol = 1e-6;
  const auto ra = run_from_rest(a, 0.002, opt, ra_rec);
  opt.integrator = Integrator::DormandPrince54;
  const auto rb = run_from_rest(b, 0.002, opt, rb_rec);
  ASSERT_TRUE(ra.ok()) << ra.message;
  EXPECT_EQ(ra.method, "dopri5") << ra.method_reason;
  EXPECT_EQ(ra.x, rb.x);
  EXPECT_EQ(ra.stats.rhs_evaluations, rb.stats.rhs_evaluations);
}

// The same scene at the paper's 26 N stays stuck: the contacts move only while they slip, so not
// every mode is exact, but the start mode (both stuck) is, and mode_residence bounds its stick
// guards above zero until t_end (the forced response of the stuck frame plus the free one from
// rest). Auto takes the exponential method. Checked independently: Dormand-Prince at rtol 1e-10
// over the same 0.1 s (20 load periods from rest) finds no event, and the two runs end at the
// same state to 1e-7 of its size (DOPRI's error at rtol 1e-10 on this 0.1 s, with margin).
TEST(AutoIntegrator, StuckSceneWithMovingContactsTakesTheExponentialMethod) {
  const TScene s = make_t_frame(4);
  System sys(s.frame, s.basis, paper_dampers(s, 26.0), paper_load(s));
  EXPECT_FALSE(sys.every_mode_exact());
  System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
  const IntegratorChoice choice = choose_integrator(sys, mode, 0.0, x0, 0.1, 1e-10);
  EXPECT_EQ(choice.integrator, Integrator::Exponential) << choice.reason;
  EXPECT_NE(choice.reason.find("guards stay positive"), std::string::npos) << choice.reason;

  System a(s.frame, s.basis, paper_dampers(s, 26.0), paper_load(s));
  System b(s.frame, s.basis, paper_dampers(s, 26.0), paper_load(s));
  Recorder ra_rec, rb_rec;
  RunOptions<double> opt;
  opt.stepper.rtol = 1e-10;
  opt.stepper.atol = 1e-14;
  const auto ra = run_from_rest(a, 0.1, opt, ra_rec);
  opt.integrator = Integrator::DormandPrince54;
  const auto rb = run_from_rest(b, 0.1, opt, rb_rec);
  ASSERT_TRUE(ra.ok()) << ra.message;
  ASSERT_TRUE(rb.ok()) << rb.message;
  EXPECT_EQ(ra.method, "exponential") << ra.method_reason;
  EXPECT_EQ(rb_rec.events.size(), 0u) << "the independent run left the stuck mode";
  EXPECT_EQ(ra_rec.events.size(), 0u);
  const Eigen::Index n = a.num_modes();
  const double scale = rb.x.head(2 * n).cwiseAbs().maxCoeff();
  EXPECT_LE((ra.x.head(2 * n) - rb.x.head(2 * n)).cwiseAbs().maxCoeff(), 1e-7 * scale);
}

// At 3 N the same scene slips within the run: the bound of its stick guards reaches zero and Auto
// keeps Dormand-Prince, naming the guard that may fire.
TEST(AutoIntegrator, SceneThatMaySlipKeepsDormandPrince) {
  const TScene s = make_t_frame(4);
  System sys(s.frame, s.basis, paper_dampers(s, 3.0), paper_load(s));
  System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
  const IntegratorChoice choice = choose_integrator(sys, mode, 0.0, x0, 0.1, 1e-8);
  EXPECT_EQ(choice.integrator, Integrator::DormandPrince54) << choice.reason;
  EXPECT_NE(choice.reason.find("may fire"), std::string::npos) << choice.reason;
}

// A regularised law with a steep slope at V = 0: its real rate is 1e5 x the fastest rate to
// resolve, far above 33 / rtol^(1/3) = 711 at rtol 1e-4: Rosenbrock23.
TEST(AutoIntegrator, SteepRegularisedLawIsStiffAndTakesRosenbrock23) {
  const Cantilever c;
  System sys = regularised_slider(c);
  EXPECT_FALSE(sys.every_mode_exact());
  EXPECT_GT(stiffness_ratio(sys, 0.01), 33.0 / std::cbrt(1e-4));
  const IntegratorChoice choice = choose_integrator(sys, sys.requested_mode(), 0.0, sys.initial_state(), 0.01, 1e-4);
  EXPECT_EQ(choice.integrator, Integrator::Rosenbrock23) << choice.reason;
  EXPECT_NE(choice.reason.find("regularised friction slope"), std::string::npos) << choice.reason;
  // A 10 ms run (the damper's spring relaxes by slipping; a regularised law has no switches).
  expect_same_as_explicit(&regularised_slider, Integrator::Rosenbrock23, 1e-4, 0.01, 0);
}

TEST(AutoIntegrator, ParsesAndNamesAuto) {
  EXPECT_EQ(parse_integrator("auto"), Integrator::Auto);
  EXPECT_STREQ(to_string(Integrator::Auto), "auto");
  EXPECT_EQ(RunOptions<double>{}.integrator, Integrator::Auto);
}

// ---------------------------------------------------------------- event-sequence check

/// An oscillator x'' = -x from (1, 0) (x = cos t, peaks of 1 at t = 2 pi k) whose mass sticks
/// for 0.05 s to a stop at x_c = 1 - delta when it reaches it (mode 0 -> 1, Rising guard
/// x - x_c), armed only from t = 9 pi on, so that the stop can catch the peak at t = 10 pi alone;
/// after the stick (mode 1 -> 2) it oscillates freely. Exactly, the stick starts at
/// 10 pi - acos(1 - delta). Dormand-Prince's amplitude error at that peak (measured at rtol =
/// atol: -7.1e-4 at 1e-4, -1.1e-4 at 1e-5) decides whether a run reaches the stop: with
/// delta = 3e-4 the run at rtol 1e-4 misses the short stick phase, the check's run at 1e-5
/// finds it; with delta = 1e-2 both find it. 32 guard samples per step: the excursion above
/// x_c lasts 2 sqrt(2 (delta - 1.1e-4)) = 0.04 s against steps of ~0.4 s, and must not fall
/// between step ends.
struct StopOscillator {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double x_c = 1.0, gate = 9.0 * M_PI, hold = 0.05, release = 0.0;
  void rhs(const Mode& m, double, const State& x, State& d) const {
    if (m == 1) {
      d << 0.0, 0.0;
    } else {
      d << x[1], -x[0];
    }
  }
  Eigen::Index num_guards(const Mode& m) const { return m == 2 ? 0 : 1; }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) const {
    if (m == 0)
      g[0] = t < gate ? -2.0 : x[0] - x_c;
    else
      g[0] = release - t;
  }
  CrossingDirection guard_direction(const Mode& m, Eigen::Index) const {
    return m == 0 ? CrossingDirection::Rising : CrossingDirection::Falling;
  }
  TransitionAction transition(Mode& m, const TriggeredGuards&, double t, State& x) {
    if (m == 0) {
      m = 1;
      x[1] = 0.0;
      release = t + hold;
    } else {
      m = 2;
    }
    return TransitionAction::proceed();
  }
};

SimulationResult<StopOscillator> run_checked(double delta, double rtol) {
  StopOscillator sys;
  sys.x_c = 1.0 - delta;
  RunOptions<double> opt;
  opt.stepper.rtol = opt.stepper.atol = rtol;
  opt.stepper.guard_samples = 32;
  opt.check_event_sequence = true;
  return simulate(sys, 0, 0.0, Eigen::Vector2d(1.0, 0.0), 10.0 * M_PI + 1.0, opt);
}

// The missed stick phase: the run has no switch, the tighter one two; they differ first at the
// tighter run's stick, within 0.01 s of the exact 10 pi - acos(1 - delta) (its amplitude error
// of ~1.2e-4 moves the crossing by sqrt(2 delta) - sqrt(2 (delta - 1.2e-4)) = 0.0055 s).
TEST(EventSequenceCheck, MissedShortStickPhaseDisagreesAtItsTime) {
  const double delta = 3e-4;
  const auto r = run_checked(delta, 1e-4);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.method, "dopri5");
  ASSERT_TRUE(r.sequence_check.checked);
  EXPECT_FALSE(r.sequence_check.agree);
  EXPECT_EQ(r.sequence_check.events, 0);
  EXPECT_EQ(r.sequence_check.events_tight, 2);
  EXPECT_EQ(r.sequence_check.rtol_tight, 1e-5);
  EXPECT_NEAR(r.sequence_check.first_difference, 10.0 * M_PI - std::acos(1.0 - delta), 0.01);
}

// A stick phase 30 times deeper than the amplitude error: both runs have it.
TEST(EventSequenceCheck, WellResolvedStickPhaseAgrees) {
  const auto r = run_checked(1e-2, 1e-4);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_TRUE(r.sequence_check.checked);
  EXPECT_TRUE(r.sequence_check.agree);
  EXPECT_EQ(r.sequence_check.events, 2);
  EXPECT_EQ(r.sequence_check.events_tight, 2);
  EXPECT_TRUE(std::isnan(r.sequence_check.first_difference));
  // Without the option nothing is checked.
  StopOscillator sys;
  const auto plain = simulate(sys, 0, 0.0, Eigen::Vector2d(1.0, 0.0), 1.0);
  EXPECT_FALSE(plain.sequence_check.checked);
}

// The trade study flags the variant whose switches differ from the reference's (rtol 1e-4 misses
// the stick phase that the reference at rtol 1e-8 has), with the time of the first difference,
// and not the variant that has the same switches.
TEST(EventSequenceCheck, TradeStudyFlagsTheVariantThatMissesTheStickPhase) {
  const double delta = 3e-4;
  auto variant = [delta](const std::string& name, double rtol) {
    TradeVariant<StopOscillator> v;
    v.name = name;
    v.setup = [delta] {
      StopOscillator s;
      s.x_c = 1.0 - delta;
      return TradeSetup<StopOscillator>{s, 0, Eigen::Vector2d(1.0, 0.0)};
    };
    v.run.stepper.rtol = v.run.stepper.atol = rtol;
    v.run.stepper.guard_samples = 32;
    return v;
  };
  TradeStudyOptions<StopOscillator> opt;
  opt.t_end = 10.0 * M_PI + 1.0;
  opt.output_interval = 0.01;
  opt.repeats = 1;
  opt.output = [](const StopOscillator&, double, const Eigen::Vector2d& x) { return x[0]; };
  const auto result = trade_study(variant("reference", 1e-8), {variant("loose", 1e-4), variant("tight", 1e-6)}, opt);
  ASSERT_EQ(result.rows.size(), 2u);
  EXPECT_TRUE(result.rows[0].sequence_differs);
  EXPECT_NEAR(result.rows[0].first_sequence_difference, 10.0 * M_PI - std::acos(1.0 - delta), 0.01);
  EXPECT_EQ(result.rows[0].method, "dopri5");
  EXPECT_FALSE(result.rows[1].sequence_differs);
  EXPECT_TRUE(std::isnan(result.rows[1].first_sequence_difference));
}

}  // namespace auto_integrator_test

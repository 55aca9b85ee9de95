// trade_study() on systems whose answers are closed form: the harmonic
// oscillator x = cos(w t) of tests/ode/ode_test_systems.hpp, whose RK4 phase and energy errors
// are known per step, and whose zeros (k - 1/2) pi / w give the switch times of its guard.
#include "model/model_test_scenes.hpp"
#include "ode/ode_test_systems.hpp"

#include <stickslip/model/trade_study.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace trade_study_test {

using stickslip::Integrator;
using stickslip::Status;
using stickslip::TradeRow;
using stickslip::TradeSetup;
using stickslip::TradeStudyOptions;
using stickslip::TradeVariant;
using stickslip::test::Oscillator;

const double pi = std::acos(-1.0);

/// A variant on the oscillator x'' = -w^2 x from x = 1, x' = 0 (guarded: its zeros are events).
TradeVariant<Oscillator> oscillator_variant(std::string name, double omega, bool guarded,
                                            stickslip::RunOptions<double> run) {
  TradeVariant<Oscillator> v;
  v.name = std::move(name);
  v.setup = [omega, guarded] {
    Oscillator o;
    o.omega = omega;
    o.guarded = guarded;
    return TradeSetup<Oscillator>{o, 0, Oscillator::State(1.0, 0.0)};
  };
  v.run = run;
  return v;
}

stickslip::RunOptions<double> dopri(double rtol) {
  stickslip::RunOptions<double> run;
  run.stepper.rtol = rtol;
  run.stepper.atol = rtol * 1e-2;
  return run;
}

stickslip::RunOptions<double> rk4(double h) {
  stickslip::RunOptions<double> run;
  run.integrator = Integrator::RungeKutta4;
  run.stepper.fixed_step = h;
  return run;
}

/// Output x(t); energy residual |E(t_end) - E(0)| with E = (x'^2 + w^2 x^2) / 2, E(0) = w^2 / 2.
TradeStudyOptions<Oscillator> oscillator_study(double t_end, double interval) {
  TradeStudyOptions<Oscillator> opt;
  opt.t_end = t_end;
  opt.output_interval = interval;
  opt.repeats = 3;
  opt.output = [](const Oscillator&, double, const Oscillator::State& x) { return x[0]; };
  opt.energy_residual = [](const Oscillator& o, const stickslip::SimulationResult<Oscillator>& r) {
    const double w2 = o.omega * o.omega;
    return std::abs(0.5 * (r.x[1] * r.x[1] + w2 * r.x[0] * r.x[0]) - 0.5 * w2);
  };
  return opt;
}

// A variant identical to the reference reproduces it bit for bit (the runs are deterministic):
// zero output error, zero switch-time error, the same events. The reference's validation (rtol
// and atol / 100) differs from it by about its own tolerance: dopri5 at rtol 1e-10 keeps the
// global error of cos(3 t) over 3 s near 1e-9, so 1e-7 is a loose bound that a broken
// validation (e.g. comparing different grids or not tightening) would not meet by luck, and the
// bound must not be exactly 0 (a rerun with different tolerances takes different steps).
TEST(TradeStudy, IdenticalVariantHasZeroErrorAndTheReferenceIsValidated) {
  const auto ref = oscillator_variant("ref", 3.0, true, dopri(1e-10));
  const auto result = stickslip::trade_study(ref, {ref}, oscillator_study(3.0, 0.05));
  ASSERT_TRUE(result.reference.ok()) << result.reference.message;
  EXPECT_EQ(result.reference.events, 3);  // zeros at pi/6, pi/2, 5 pi/6 < 3 s
  ASSERT_TRUE(result.validation.ok()) << result.validation.message;
  EXPECT_GT(result.validation.output_error_max, 0.0);
  EXPECT_LT(result.validation.output_error_max, 1e-7);
  EXPECT_LT(result.validation.switch_time_error, 1e-7);
  EXPECT_NE(result.validation_method.find("rtol and atol divided by 100"), std::string::npos)
      << result.validation_method;
  ASSERT_EQ(result.rows.size(), 1u);
  const auto& row = result.rows[0];
  ASSERT_TRUE(row.ok()) << row.message;
  EXPECT_EQ(row.name, "ref");
  EXPECT_EQ(row.output_error_max, 0.0);
  EXPECT_EQ(row.output_error_rms, 0.0);
  EXPECT_EQ(row.switch_time_error, 0.0);
  EXPECT_EQ(row.missed_switches, 0);
  EXPECT_EQ(row.extra_switches, 0);
  EXPECT_EQ(row.events, result.reference.events);
  EXPECT_EQ(row.rhs_evaluations, result.reference.rhs_evaluations);
  EXPECT_GE(row.cpu_seconds, 0.0);
}

// RK4 on x'' = -w^2 x multiplies the phase per step by arg R(i theta) = theta - theta^5 / 120 +
// O(theta^7), theta = w h, and the amplitude squared by |R(i theta)|^2 = 1 - theta^6 / 72 +
// O(theta^8). After t the phase lags by delta(t) = (t / h) theta^5 / 120, so the output error is
// |cos(w t - delta) - cos(w t)| = delta |sin(w t)| + O(delta^2), and the energy has lost
// (t / h) theta^6 / 72 E0. The predictions hold to O(theta^2) = 0.4 % (theta = 0.06) plus the
// reference's ~1e-9 against errors ~1e-6: 2 % tolerances. Halving h divides the output error by
// 16 and the energy error by 32 ((t / h) theta^5 and (t / h) theta^6: orders 4 and 5): ratios
// within 3 %.
TEST(TradeStudy, Rk4ErrorsMatchThePhaseAndEnergyErrorsPerStep) {
  const double omega = 3.0, t_end = 2.0, interval = 0.1;
  const auto ref = oscillator_variant("ref", omega, false, dopri(1e-11));
  const auto result = stickslip::trade_study(
      ref, {oscillator_variant("rk4 h", omega, false, rk4(0.02)),
            oscillator_variant("rk4 h/2", omega, false, rk4(0.01))},
      oscillator_study(t_end, interval));
  ASSERT_TRUE(result.reference.ok()) << result.reference.message;
  ASSERT_EQ(result.rows.size(), 2u);
  for (int k = 0; k < 2; ++k) {
    const auto& row = result.rows[static_cast<std::size_t>(k)];
    ASSERT_TRUE(row.ok()) << row.message;
    const double h = k == 0 ? 0.02 : 0.01;
    const double theta = omega * h;
    double predicted = 0;
    for (int i = 0; i <= 20; ++i) {  // samples t_i = 0.1 i; max |x_ref| = 1
      const double t = interval * i;
      predicted = std::max(predicted, t / h * std::pow(theta, 5) / 120 * std::abs(std::sin(omega * t)));
    }
    EXPECT_NEAR(row.output_error_max, predicted, 0.02 * predicted) << row.name;
    const double energy = t_end / h * std::pow(theta, 6) / 72 * 0.5 * omega * omega;
    EXPECT_NEAR(row.energy_residual, energy, 0.02 * energy) << row.name;
    // 4 stages a step, plus the derivative the stepper takes at the start of the (only) mode.
    EXPECT_EQ(row.rhs_evaluations, 4 * std::lround(t_end / h) + 1);
  }
  EXPECT_NEAR(result.rows[0].output_error_max / result.rows[1].output_error_max, 16.0, 0.03 * 16);
  EXPECT_NEAR(result.rows[0].output_error_rms / result.rows[1].output_error_rms, 16.0, 0.03 * 16);
  EXPECT_NEAR(result.rows[0].energy_residual / result.rows[1].energy_residual, 32.0, 0.03 * 32);
}

// Switches of a different scene against the closed form: the guarded oscillator at w = 3 has
// zeros at (k - 1/2) pi / 3 = 0.52, 1.57, 2.62 s before t_end = 3; at w = 3.8 it has four,
// (k - 1/2) pi / 3.8 <= 2.89 s. The pairs (k-1 -> k) match in order, the largest difference is
// the third, 2.5 pi (1/3 - 1/3.8), and the fourth is extra; with the roles swapped it is missed.
// Both runs locate zeros to ~1e-10 s (rtol 1e-10, event bracket 1e-12): 1e-8 tolerance.
TEST(TradeStudy, SwitchTimeErrorAndExtraOrMissedSwitchesMatchTheClosedForm) {
  const auto slow = oscillator_variant("w = 3", 3.0, true, dopri(1e-10));
  const auto fast = oscillator_variant("w = 3.8", 3.8, true, dopri(1e-10));
  auto opt = oscillator_study(3.0, 0.05);
  opt.repeats = 1;
  const double dt = 2.5 * pi * (1.0 / 3.0 - 1.0 / 3.8);
  const auto extra = stickslip::trade_study(slow, {fast}, opt);
  ASSERT_EQ(extra.rows.size(), 1u);
  ASSERT_TRUE(extra.rows[0].ok()) << extra.rows[0].message;
  EXPECT_EQ(extra.rows[0].events, 4);
  EXPECT_NEAR(extra.rows[0].switch_time_error, dt, 1e-8);
  EXPECT_EQ(extra.rows[0].extra_switches, 1);
  EXPECT_EQ(extra.rows[0].missed_switches, 0);
  const auto missed = stickslip::trade_study(fast, {slow}, opt);
  ASSERT_EQ(missed.rows.size(), 1u);
  EXPECT_NEAR(missed.rows[0].switch_time_error, dt, 1e-8);
  EXPECT_EQ(missed.rows[0].extra_switches, 0);
  EXPECT_EQ(missed.rows[0].missed_switches, 1);
}

// The matching of switches in the middle of a run, on hand-built records: reference
// 0->1 at 1.0, 1->0 at 2.0, 0->1 at 3.0; run 0->1 at 1.1, 0->1 at 3.05. The first pair matches
// (|dt| = 0.1), then 1->0 at 2.0 has no partner before the run's 0->1 at 3.05 (missed), and
// that one matches the reference's third (|dt| = 0.05): largest |dt| 0.1, one missed, none extra.
TEST(TradeStudy, SwitchesMatchByModePairInTimeOrder) {
  using Record = stickslip::detail::TradeRecord<Oscillator>;
  Record ref, run;
  ref.samples = run.samples = {1.0, 0.5};
  ref.switches = {{1.0, 0, 1}, {2.0, 1, 0}, {3.0, 0, 1}};
  run.switches = {{1.1, 0, 1}, {3.05, 0, 1}};
  TradeRow<double> row;
  row.started = true;
  stickslip::detail::compare_trade_records(row, run, ref);
  EXPECT_NEAR(row.switch_time_error, 0.1, 1e-15);  // |1.1 - 1.0| in double
  EXPECT_EQ(row.missed_switches, 1);
  EXPECT_EQ(row.extra_switches, 0);
  EXPECT_EQ(row.output_error_max, 0.0);
}

// A variant whose run fails (one step allowed) and one whose options are invalid become rows
// with their status or message, and the study goes on to the next variant.
TEST(TradeStudy, FailedVariantsBecomeRowsAndTheStudyGoesOn) {
  auto one_step = dopri(1e-8);
  one_step.stepper.max_steps = 1;
  auto bad = dopri(1e-8);
  bad.stepper.rtol = -1;
  const auto ref = oscillator_variant("ref", 3.0, true, dopri(1e-10));
  auto opt = oscillator_study(1.0, 0.1);
  opt.repeats = 1;
  const auto result = stickslip::trade_study(
      ref, {oscillator_variant("one step", 3.0, true, one_step),
            oscillator_variant("bad rtol", 3.0, true, bad), oscillator_variant("fine", 3.0, true, dopri(1e-8))},
      opt);
  ASSERT_EQ(result.rows.size(), 3u);
  EXPECT_TRUE(result.rows[0].started);
  EXPECT_EQ(result.rows[0].status, Status::MaxSteps);
  EXPECT_LT(result.rows[0].t_reached, 1.0);
  EXPECT_TRUE(std::isnan(result.rows[0].output_error_max));
  EXPECT_FALSE(result.rows[1].started);
  EXPECT_NE(result.rows[1].message.find("options.rtol"), std::string::npos) << result.rows[1].message;
  EXPECT_TRUE(std::isnan(result.rows[1].output_error_max));
  EXPECT_TRUE(result.rows[2].ok()) << result.rows[2].message;
  EXPECT_LT(result.rows[2].output_error_max, 1e-5);  // dopri5 at rtol 1e-8 over 1 s

  std::ostringstream csv;
  stickslip::write_trade_csv(csv, result.rows);
  std::istringstream lines(csv.str());
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), 12);
  EXPECT_EQ(first.rfind("\"one step\",max_steps,", 0), 0u) << first;
  EXPECT_EQ(second.rfind("\"bad rtol\",not_started,", 0), 0u) << second;
}

// Options out of range throw std::invalid_argument naming the option.
TEST(TradeStudy, InvalidStudyOptionsNameTheOption) {
  const auto ref = oscillator_variant("ref", 3.0, false, dopri(1e-8));
  auto expect_throw = [&](TradeStudyOptions<Oscillator> opt, const std::string& name) {
    try {
      (void)stickslip::trade_study(ref, {}, opt);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  auto opt = oscillator_study(1.0, 0.1);
  opt.output = nullptr;
  expect_throw(opt, "options.output");
  opt = oscillator_study(0.0, 0.1);
  expect_throw(opt, "options.t_end");
  opt = oscillator_study(1.0, 0.0);
  expect_throw(opt, "options.output_interval");
  opt = oscillator_study(1.0, 0.1);
  opt.repeats = 0;
  expect_throw(opt, "options.repeats");
  opt = oscillator_study(1.0, 0.1);
  opt.validation_factor = 1;
  expect_throw(opt, "options.validation_factor");
}

// On the paper's T-frame (FrictionDampedSystem<double>, modes = DamperStates) with a model
// variant (fixed contact point) built by the factory: the row's tip error and event counts equal
// those computed here from two independent simulate() runs with the tests' Recorder (same
// deterministic runs, so equal to the last bit), and the identical variant has zero error.
TEST(TradeStudy, ModelVariantOnTheTFrameMatchesAHandComparison) {
  using model_test::System;
  const auto scene = std::make_shared<model_test::TScene>(model_test::make_t_frame());
  auto make = [scene](bool moving_contact) {
    stickslip::ModelOptions<double> mo;
    mo.moving_contact = moving_contact;
    System sys(scene->frame, scene->basis, model_test::paper_dampers(*scene, 3.0),
               model_test::paper_load(*scene), mo);
    System::State x0 = sys.initial_state();
    stickslip::DamperStates mode = sys.requested_mode();
    EXPECT_TRUE(sys.make_consistent(mode, 0.0, x0));
    return TradeSetup<System>{std::move(sys), mode, x0};
  };
  stickslip::RunOptions<double> run;
  run.stepper.rtol = 1e-8;
  run.stepper.atol = 1e-14;  // modal coordinates ~1e-5
  const TradeVariant<System> ref{"moving contact", [make] { return make(true); }, run};
  const TradeVariant<System> fixed{"fixed contact", [make] { return make(false); }, run};
  const Eigen::VectorXd tip = model_test::nodal(scene->basis, scene->tip, stickslip::Dof::X);
  const Eigen::Index n = tip.size();
  TradeStudyOptions<System> opt;
  opt.t_end = 0.05;
  opt.output_interval = 1e-3;
  opt.repeats = 1;
  opt.output = [tip, n](const System&, double, const System::State& x) { return tip.dot(x.head(n)); };
  const auto result = stickslip::trade_study(ref, {ref, fixed}, opt);
  ASSERT_TRUE(result.reference.ok()) << result.reference.message;
  ASSERT_EQ(result.rows.size(), 2u);
  EXPECT_EQ(result.rows[0].output_error_max, 0.0);
  EXPECT_EQ(result.rows[0].switch_time_error, 0.0);

  auto hand_run = [&](const TradeVariant<System>& v, model_test::Recorder& rec) {
    auto setup = v.setup();
    auto r = run;
    r.stepper.output_interval = opt.output_interval;
    return stickslip::simulate(setup.system, setup.mode, 0.0, setup.x0, opt.t_end, r, rec);
  };
  model_test::Recorder rec_ref, rec_fixed;
  ASSERT_TRUE(hand_run(ref, rec_ref).ok());
  ASSERT_TRUE(hand_run(fixed, rec_fixed).ok());
  ASSERT_EQ(rec_ref.x.size(), rec_fixed.x.size());
  ASSERT_GE(rec_ref.events.size(), 2u) << "the scene must switch";
  double diff = 0, amp = 0;
  for (std::size_t k = 0; k < rec_ref.x.size(); ++k) {
    const double a = tip.dot(rec_ref.x[k].head(n)), b = tip.dot(rec_fixed.x[k].head(n));
    diff = std::max(diff, std::abs(a - b));
    amp = std::max(amp, std::abs(a));
  }
  const auto& row = result.rows[1];
  ASSERT_TRUE(row.ok()) << row.message;
  EXPECT_GT(row.output_error_max, 0.0);
  EXPECT_EQ(row.output_error_max, diff / amp);
  EXPECT_EQ(row.events, static_cast<long>(rec_fixed.events.size()));
  EXPECT_EQ(result.reference.events, static_cast<long>(rec_ref.events.size()));
  // Every switch is matched, missed or extra: matched = ref - missed = run - extra.
  EXPECT_EQ(result.reference.events - row.missed_switches, row.events - row.extra_switches);
}

}  // namespace trade_study_test

// Helpers of the composition layer: stuck_natural_modes, static_preload_start
// and the DamperStatistics observer. References: the finite-element frame with each stuck damper
// as an explicit point mass and spring (component 1 alone), closed forms of one-mode scenes from
// component 2's nodal values, a static finite-element solve, the model's own event log and a
// closed-form response sampled by brute force.
#include "model/model_test_scenes.hpp"

#include <stickslip/detail/cpu_time.hpp>

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>
#include <vector>

namespace helpers_test {

using namespace model_test;

/// The T-frame of the model tests with every mode of its 36 free DOFs retained: on a complete
/// basis the modal reduction is exact, so the reduced system must reproduce finite-element
/// results to round-off.
constexpr int kAllModes = 36;

/// The node of `member` at the damper's contact coordinate X = 0.01 k (the platform has four
/// 0.01 m elements, so the dampers of paper_dampers sit on nodes 1 and 3).
Index platform_node(const TScene& s, int k) {
  return s.frame.member(s.platform).nodes[static_cast<std::size_t>(k)];
}

// ---- stuck_natural_modes ------------------------------------------------------------------------

TEST(StuckNaturalModes, MatchTheFrameWithEachDamperAsAnExplicitMassAndSpring) {
  // A stuck damper with an inertial normal load moves with the platform along u (= global X
  // here) and w (= global Y) and is held by its spring along u: a point mass m_eff on the node's
  // X and Y and a grounded spring k_eff on X, added to the finite-element frame itself.
  const TScene s = make_t_frame(kAllModes);
  ASSERT_EQ(s.basis.size(), kAllModes);
  const auto dampers = paper_dampers(s, 12.0);
  ModelOptions<double> options;
  options.moving_contact = false;
  const System sys(s.frame, s.basis, dampers, {}, options);
  const StuckModes<double> stuck = stuck_natural_modes(sys);

  TScene ref = make_t_frame(1);
  for (int k : {1, 3}) {
    const auto& d = dampers[k == 1 ? 0 : 1];
    ref.frame.add_point_mass(platform_node(ref, k), d.effective_mass());
    ref.frame.add_spring(platform_node(ref, k), Dof::X, d.effective_stiffness());
  }
  ModalOptions<double> mo;
  mo.num_modes = kAllModes;
  const ModalBasis<double> fe = compute_modes(ref.frame.assemble(), mo);
  ASSERT_EQ(stuck.omega.size(), fe.omega().size());
  // The six lowest frequencies (30 Hz ... a few kHz, the ones a forcing meets): two dense
  // generalized eigensolves of matrices whose eigenvalues span ~1e9 (axial modes of 1 cm
  // elements) agree to eps * lambda_max / lambda ~ 1e-7 relative in omega^2 for the lowest, so
  // 1e-6 relative in omega; a damper left out or counted once too often moves them by >1e-3.
  for (Index j = 0; j < 6; ++j)
    EXPECT_NEAR(stuck.omega[j] / fe.omega()[j], 1.0, 1e-6) << "mode " << j;
  // Shapes: M-normalised in modal coordinates (v^T M v = 1, M = I + sum m (a a^T + b b^T)).
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(kAllModes, kAllModes);
  for (int k : {1, 3}) {
    const double m = dampers[k == 1 ? 0 : 1].effective_mass();
    const Eigen::VectorXd a = nodal(s.basis, platform_node(s, k), Dof::Y);
    const Eigen::VectorXd b = nodal(s.basis, platform_node(s, k), Dof::X);
    M += m * (a * a.transpose() + b * b.transpose());
  }
  const Eigen::MatrixXd G = stuck.shapes.transpose() * M * stuck.shapes;
  EXPECT_LE((G - Eigen::MatrixXd::Identity(kAllModes, kAllModes)).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(StuckNaturalModes, OneModeAndOneDamperIsTheClosedFormOfOneDegreeOfFreedom) {
  // One mode q (unit modal mass, stiffness omega1^2) carrying a stuck damper at a node: kinetic
  // energy 1/2 (1 + m (b^2 + a^2)) q'^2 (a^2 only with an inertial normal load), strain energy
  // 1/2 (omega1^2 + k b^2) q^2, so omega^2 = (omega1^2 + k b^2) / (1 + m (b^2 [+ a^2])), with
  // a, b the node's Y and X values of the mode (component 2, not the model's point shapes).
  const TScene s = make_t_frame(1);
  auto dampers = paper_dampers(s, 12.0, 0.35, 0.3, 3e5);
  dampers.pop_back();
  const double a = s.basis.nodal(platform_node(s, 1), Dof::Y)(0);
  const double b = s.basis.nodal(platform_node(s, 1), Dof::X)(0);
  const double m = dampers[0].effective_mass(), k = dampers[0].effective_stiffness();
  const double w1 = s.basis.omega()[0];
  for (NormalLoad normal : {NormalLoad::Inertial, NormalLoad::Constant}) {
    ModelOptions<double> options;
    options.normal_load = normal;
    const System sys(s.frame, s.basis, dampers, {}, options);
    const double inertia = 1 + m * (b * b + (normal == NormalLoad::Inertial ? a * a : 0.0));
    const double expected = std::sqrt((w1 * w1 + k * b * b) / inertia);
    // one closed-form square root against a 1 x 1 generalized eigensolve: round-off
    EXPECT_NEAR(stuck_natural_modes(sys).omega[0] / expected, 1.0, 1e-13);
    EXPECT_GT(std::abs(expected / w1 - 1), 1e-3);  // the damper changes the frequency visibly
  }
  const System sys(s.frame, s.basis, dampers);
  EXPECT_THROW(stuck_natural_modes(sys, Eigen::VectorXd::Zero(2)), std::invalid_argument);
}

// ---- static_preload_start ----------------------------------------------------------------------

TEST(StaticPreloadStart, OneModeIsOmegaSquaredQEqualsPsiWTimesN0) {
  // Closed form of a one-mode scene: omega^2 q0 = sum_i N0_i psi_w(X_i), psi_w at the damper
  // nodes = the mode's global Y value (platform along +X, dampers pressing along +w = +Y).
  const TScene s = make_t_frame(1);
  const auto dampers = paper_dampers(s, 12.0);
  System sys(s.frame, s.basis, dampers, paper_load(s));
  const StartState<System> start = static_preload_start(sys);
  double load = 0;
  for (int k : {1, 3}) load += 12.0 * s.basis.nodal(platform_node(s, k), Dof::Y)(0);
  const double w2 = s.basis.omega()[0] * s.basis.omega()[0];
  EXPECT_NEAR(start.x[0] / (load / w2), 1.0, 1e-13);  // a sum of two products: round-off
  System::State expected = sys.initial_state();  // q' = 0, x = x' = 0, X = X0, audit integrals 0
  expected[0] = start.x[0];
  EXPECT_EQ(start.x, expected);
  EXPECT_EQ(start.mode, DamperStates(2, ContactState::Stick));
}

TEST(StaticPreloadStart, OnACompleteBasisIsTheFiniteElementStaticDeflection) {
  // With all modes, Phi q0 = K^-1 F (the modal expansion of the static solution is complete):
  // F = N0 along global Y at the two damper nodes, K the assembled frame, solved by a sparse
  // LDL^T - component 1 alone.
  const TScene s = make_t_frame(kAllModes);
  const auto dampers = paper_dampers(s, 12.0);
  System sys(s.frame, s.basis, dampers);
  const StartState<System> start = static_preload_start(sys);
  const AssembledFrame<double> asm_frame = s.frame.assemble();
  Eigen::VectorXd F = Eigen::VectorXd::Zero(asm_frame.num_free());
  for (int k : {1, 3}) F[asm_frame.dofs.free_index(platform_node(s, k), Dof::Y)] += 12.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(asm_frame.stiffness);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd u = ldlt.solve(F);
  // Nodal displacements from the modal state: rows of the basis (component 2).
  double worst = 0;
  for (int k : {1, 3})
    for (Dof dof : {Dof::X, Dof::Y, Dof::Rz}) {
      const Index node = platform_node(s, k);
      const double modal = nodal(s.basis, node, dof).dot(start.x.head(kAllModes));
      worst = std::max(worst, std::abs(modal - u[asm_frame.dofs.free_index(node, dof)]));
    }
  // Relative to the largest displacement: the modal sum over omega_j^2 spanning 1e9 and the
  // sparse solve of K (condition ~1e9) each carry ~1e-7 of the largest component; 1e-6 leaves a
  // margin, a missing preload or a wrong sign is of order 1.
  EXPECT_LE(worst, 1e-6 * u.cwiseAbs().maxCoeff());
}

/// Largest |q'| over the samples of a run, and its events.
struct Motion {
  double max_qd = 0;
  std::size_t events = 0;
  Status status = Status::Success;
};

Motion run_without_loads(System& sys, DamperStates mode, System::State x0, const RunOptions<double>& run) {
  EXPECT_TRUE(sys.make_consistent(mode, 0.0, x0));
  Recorder rec;
  const auto result = simulate(sys, mode, 0.0, x0, 1.0, run, rec);
  Motion m;
  m.status = result.status;
  m.events = rec.events.size();
  for (const auto& x : rec.x)
    m.max_qd = std::max(m.max_qd, x.segment(sys.num_modes(), sys.num_modes()).cwiseAbs().maxCoeff());
  return m;
}

TEST(StaticPreloadStart, ARunWithoutLoadsStaysAtRestWhereTheStepStartOscillates) {
  // One damper left of the blade tip: its preload bends the blade (with both paper dampers the
  // vertical forces balance about the tip and load the stiff blade axially, q0 ~ 1e-19).
  const TScene s = make_t_frame(6);
  auto dampers = paper_dampers(s, 12.0);
  dampers.pop_back();
  System sys(s.frame, s.basis, dampers);  // moving contact, inertial N, no loads
  const StartState<System> start = static_preload_start(sys);
  RunOptions<double> run;
  run.stepper.output_interval = 1e-3;
  const Motion step = run_without_loads(sys, sys.requested_mode(), sys.initial_state(), run);
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-13;
  const Motion rest = run_without_loads(sys, start.mode, start.x, run);
  ASSERT_EQ(rest.status, Status::Success);
  ASSERT_EQ(step.status, Status::Success);
  EXPECT_EQ(rest.events, 0u);
  // The preload step rings the structure: |q'| ~ 1e-2 (q0 ~ 1e-4 at omega ~ 2e2 rad/s). From the
  // equilibrium, the initial imbalance omega^2 q0 - N0 a is round-off, and what moves is the
  // integrator's error at atol 1e-13 carried by modes up to ~1e4 rad/s (measured 2.6e-10, 2e-8
  // of the step's). An error delta in q0 would ring at delta times the step's motion, so the
  // bound 1e-6 checks q0 to 1e-6 with a margin of 50 over the integrator's floor.
  EXPECT_GT(step.max_qd, 1e-3);
  EXPECT_LE(rest.max_qd, 1e-6 * step.max_qd);
}

// ---- DamperStatistics ----------------------------------------------------------------------------

TEST(DamperStatistics, RegimeRuleIsTheBladeExamplesOne) {
  // examples/blade_damper: >= 0.999 stick, < 0.05 gross slip, in between stick-slip.
  EXPECT_EQ(classify_regime(1.0), DamperRegime::Stick);
  EXPECT_EQ(classify_regime(0.999), DamperRegime::Stick);
  EXPECT_EQ(classify_regime(0.9989), DamperRegime::StickSlip);
  EXPECT_EQ(classify_regime(0.05), DamperRegime::StickSlip);
  EXPECT_EQ(classify_regime(0.0499), DamperRegime::GrossSlip);
  EXPECT_EQ(classify_regime(0.0), DamperRegime::GrossSlip);
  EXPECT_EQ(classify_regime(std::numeric_limits<double>::quiet_NaN()), DamperRegime::NotReached);
  EXPECT_STREQ(to_string(DamperRegime::StickSlip), "stick-slip");
  EXPECT_STREQ(to_string(DamperRegime::GrossSlip), "gross slip");
}

TEST(DamperStatistics, BadWindowsThrowNamingTheParameter) {
  const TScene s = make_t_frame(2);
  System sys(s.frame, s.basis, paper_dampers(s, 12.0));
  const auto x0 = sys.initial_state();
  const auto mode = sys.requested_mode();
  using W = StatisticsWindow<double>;
  for (const W& w : {W{1.0, 1.0, 0.1}, W{0.0, 1.0, 0.0}, W{0.0, 1.0, -1.0},
                     W{0.0, std::numeric_limits<double>::infinity(), 0.1}}) {
    try {
      DamperStatistics<System> stats(sys, mode, 0.0, x0, w);
      ADD_FAILURE() << "no throw";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("window."), std::string::npos) << e.what();
    }
  }
}

/// A run of the paper's scene from rest (five excitation periods) with statistics over
/// [t_start, t_end] and samples every `dt`.
struct StatisticsRun {
  Recorder rec;
  std::vector<DamperWindowStatistics<double>> stats;
  DamperStates mode0;
  HybridResult<double, System::State, DamperStates> result;
};

/// Forwards the callbacks to the recorder and the statistics (one observer for simulate()).
struct Both {
  Recorder& rec;
  DamperStatistics<System>& stats;
  bool on_step(double t, const System::State& x, const DamperStates& m) { return stats.on_step(t, x, m); }
  void on_event(const EventRecord<double, DamperStates>& r, const System::State& x) {
    rec.on_event(r, x);
    stats.on_event(r, x);
  }
  bool on_sample(double t, const System::State& x, const DamperStates& m) { return rec.on_sample(t, x, m); }
};

StatisticsRun run_with_statistics(System& sys, const StatisticsWindow<double>& w, double t_end, double dt) {
  StatisticsRun r;
  System::State x0 = sys.initial_state();
  r.mode0 = sys.requested_mode();
  EXPECT_TRUE(sys.make_consistent(r.mode0, 0.0, x0));
  sys.clear_events();
  DamperStatistics<System> stats(sys, r.mode0, 0.0, x0, w);
  Both both{r.rec, stats};
  RunOptions<double> run;
  run.stepper.output_interval = dt;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-13;
  run.stepper.max_step = 2e-5;
  r.result = simulate(sys, r.mode0, 0.0, x0, t_end, run, both);
  for (Index i = 0; i < stats.num_dampers(); ++i) r.stats.push_back(stats.statistics(i));
  return r;
}

const double kPeriod = 2 * M_PI / 200.0;

TEST(DamperStatistics, HighPreloadSticksThroughoutTheWindow) {
  // 26 N on this mesh: no event in five periods (docs/model.md's exponential study), so both
  // dampers stick all the time: fraction exactly 1 and no switch.
  const TScene s = make_t_frame(6);
  System sys(s.frame, s.basis, paper_dampers(s, 26.0), paper_load(s));
  const StatisticsWindow<double> w{0.05, 5 * kPeriod, kPeriod};
  StatisticsRun r = run_with_statistics(sys, w, 5 * kPeriod, 1e-3);
  ASSERT_EQ(r.result.status, Status::Success) << r.result.message;
  ASSERT_TRUE(sys.events().empty());
  for (const auto& st : r.stats) {
    EXPECT_EQ(st.stick_fraction, 1.0);
    EXPECT_EQ(st.switches, 0);
    EXPECT_EQ(st.switches_per_period, 0.0);
    EXPECT_EQ(st.regime, DamperRegime::Stick);
    EXPECT_NEAR(st.observed_time, w.t_end - w.t_start, 1e-15);  // a sum of step lengths
  }
  // The documented use: the statistics alone as simulate()'s observer, over a window that
  // reaches past the run's end (only the covered part counts).
  System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
  DamperStatistics<System> alone(sys, mode, 0.0, x0, {0.1, 1.0, kPeriod});
  ASSERT_TRUE(simulate(sys, mode, 0.0, x0, 0.12, RunOptions<double>{}, alone).ok());
  EXPECT_NEAR(alone.statistics(1).observed_time, 0.02, 1e-15);
  EXPECT_EQ(alone.statistics(1).stick_fraction, 1.0);
  EXPECT_THROW(alone.statistics(2), std::invalid_argument);
}

TEST(DamperStatistics, StickSlipMatchesTheEventLogAndAFineSampling) {
  // 2.6 N: stick-slip from the first periods. References: (1) the stick time rebuilt from the
  // model's event log (sys.events(): time, damper, from, to) starting from the consistent
  // initial mode - the same event times summed another way, so round-off; (2) the fraction of
  // 1e-5 s samples in Stick - within one sample interval per switch and window end.
  const TScene s = make_t_frame(6);
  System sys(s.frame, s.basis, paper_dampers(s, 2.6), paper_load(s));
  const StatisticsWindow<double> w{0.03, 5 * kPeriod, kPeriod};
  const double dt = 1e-5;
  StatisticsRun r = run_with_statistics(sys, w, 5 * kPeriod, dt);
  ASSERT_EQ(r.result.status, Status::Success) << r.result.message;
  const double span = w.t_end - w.t_start;
  for (Index i = 0; i < 2; ++i) {
    SCOPED_TRACE(i);
    const auto& st = r.stats[static_cast<std::size_t>(i)];
    // (1) the event log
    ContactState state = r.mode0[i];
    double t = 0, stuck = 0;
    long switches = 0;
    auto add = [&](double until) {
      const double a = std::max(t, w.t_start), b = std::min(until, w.t_end);
      if (state == ContactState::Stick && b > a) stuck += b - a;
    };
    for (const auto& ev : sys.events()) {
      if (ev.damper != i) continue;
      add(ev.t);
      t = ev.t;
      state = ev.to;
      if (ev.t >= w.t_start && ev.t <= w.t_end) ++switches;
    }
    add(w.t_end);
    EXPECT_GE(switches, 2);  // a real stick-slip window
    EXPECT_EQ(st.switches, switches);
    EXPECT_NEAR(st.stick_time, stuck, 1e-12);
    EXPECT_NEAR(st.stick_fraction, stuck / span, 1e-12);
    EXPECT_NEAR(st.switches_per_period, double(switches) * kPeriod / span, 1e-9);
    EXPECT_EQ(st.regime, classify_regime(stuck / span));
    EXPECT_GT(st.stick_fraction, 0.0);
    EXPECT_LT(st.stick_fraction, 1.0);
    // (2) fine sampling
    long in = 0, total = 0;
    for (std::size_t k = 0; k < r.rec.t.size(); ++k)
      if (r.rec.t[k] >= w.t_start && r.rec.t[k] < w.t_end) {
        ++total;
        in += r.rec.mode[k][i] == ContactState::Stick;
      }
    EXPECT_NEAR(st.stick_fraction, double(in) / double(total), double(switches + 2) * dt / span);
  }
}

TEST(DamperStatistics, RegularisedDamperIsStuckWhileItsSpeedIsBelowVEps) {
  // One mode, a fixed contact, one regularised damper with preload 0 and a constant normal load:
  // no friction (f = -mu(V) N0 = 0), so the mode follows the closed form of the undamped forced
  // oscillator from rest, q' = p W / (omega^2 - W^2) (cos W t - cos omega t), the damper stays at
  // x = 0 and V = -b q'. Reference: the fraction of 4e6 points of the window with |V| < v_eps and
  // the number of changes of that indicator, on the closed form (nothing from the run).
  const TScene s = make_t_frame(1);
  auto dampers = paper_dampers(s, 0.0);
  dampers.pop_back();
  dampers[0].mass = 0.01;
  dampers[0].normal_load = NormalLoad::Constant;
  dampers[0].initial_state = ContactState::SlipPositive;
  const double W = 200.0, amplitude = 20.0;
  ModelOptions<double> options;
  options.moving_contact = false;
  const double v_eps = 2e-3;
  dampers[0].law = RegularisedLaw<double>(0.3, v_eps);
  System sys(s.frame, s.basis, dampers, paper_load(s, amplitude), options);

  const double w = s.basis.omega()[0];
  const Index load_node = s.frame.member(s.blade).nodes[2];  // 0.05 m above the root
  const double p = amplitude * s.basis.nodal(load_node, Dof::X)(0);
  const double b = s.basis.nodal(platform_node(s, 1), Dof::X)(0);
  auto V = [&](double t) { return -b * p * W / (w * w - W * W) * (std::cos(W * t) - std::cos(w * t)); };

  const StatisticsWindow<double> win{0.02, 0.3, 2 * M_PI / W};
  StatisticsRun r = run_with_statistics(sys, win, 0.3, 1e-3);
  ASSERT_EQ(r.result.status, Status::Success) << r.result.message;
  const auto& st = r.stats[0];

  const long points = 4'000'000;
  const double h = (win.t_end - win.t_start) / double(points);
  long in = 0, changes = 0;
  bool prev = std::abs(V(win.t_start)) < v_eps;
  for (long k = 0; k < points; ++k) {
    const bool now = std::abs(V(win.t_start + (double(k) + 0.5) * h)) < v_eps;
    in += now;
    changes += now != prev;
    prev = now;
  }
  const double fraction = double(in) / double(points);
  ASSERT_GT(changes, 20);  // the beat brings |V| below v_eps many times
  ASSERT_GT(fraction, 0.0);
  EXPECT_EQ(st.switches, changes);
  // Crossings from a linear V between step ends 2e-5 s apart: error h^2 |V''| / (8 |V'|) per
  // crossing, ~1e-8 s here; the sampled reference errs by one point (7e-8 s) per crossing: 1e-5
  // of the fraction covers both for the ~100 crossings with a margin of ten.
  EXPECT_NEAR(st.stick_fraction, fraction, 1e-5);
  EXPECT_EQ(st.regime, classify_regime(fraction));
}

// ---- CPU time of one run among parallel runs ------------------------------------------------

// trade_study() and the blade example's threaded sweep time each run by the CPU time of the thread
// that runs it. The process's CPU time (std::clock(), used before) also counts every other
// thread: a sweep on two threads booked about twice the CPU to each run. Here the measuring thread
// only waits while a second thread burns at least 0.05 s of CPU of its own (counted by its own
// thread clock, so the burn happens whatever else loads the machine): the waiting thread's CPU
// time must stay far below that. The bound 0.02 s leaves room for the waiting thread's own work
// (thread start, a condition poll every millisecond); std::clock() gives >= 0.05 s here.
TEST(ThreadCpuTime, CountsTheCallingThreadOnly) {
  std::atomic<bool> done{false};
  const double start = stickslip::detail::thread_cpu_seconds();
  std::thread burner([&done] {
    const double t0 = stickslip::detail::thread_cpu_seconds();
    volatile double sink = 0;
    while (stickslip::detail::thread_cpu_seconds() - t0 < 0.05)
      for (int i = 0; i < 10000; ++i) sink = sink + std::sqrt(static_cast<double>(i));
    done = true;
  });
  while (!done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  burner.join();
  const double waited = stickslip::detail::thread_cpu_seconds() - start;
  EXPECT_GE(waited, 0.0);
  EXPECT_LT(waited, 0.02);
}

}  // namespace helpers_test

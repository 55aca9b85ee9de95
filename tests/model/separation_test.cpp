// A damper that leaves its member and lands again (PointDamper::separation =
// Separate; docs/model_separation.md "Separation"). The scene: the T-frame truncated to its first mode
// (the blade's bending, which moves the platform both along its axis, psi_u, and across it,
// psi_w), one damper at a fixed contact point, lifted off by a harmonic load at the mode's
// frequency. Every impact is checked on the states just before and after the transition,
// from the shapes at the contact (point_shape) and the definitions of the quantities, not
// from the model's impact code:
//   * the generalised momentum q' + m (a y_d' + b x') is unchanged (the impulses act between
//     the mode and the damper: dq' = L_n a - L_t b, m dy_d' = -L_n, m dx' = L_t);
//   * Newton's law on the relative normal velocity gap' = a q' - y_d': -e v_n, or 0 when the
//     impact lands;
//   * Coulomb's law for the impulses read from the damper's velocity jumps (L_n = -m dy_d',
//     L_t = m dx');
//   * the kinetic energy lost equals the loss booked in the audit's impact term.
// The lift-off instant: the normal force from an independent solve of the contact rows is zero
// there. Runs with e = 1 (no friction, no damping) conserve the energy over many impacts; e = 0
// lands at every impact without a Zeno stop; the energy audit closes over runs with bounces,
// with DOPRI and with the exponential integrator.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace separation_test {

using namespace model_test;

/// An observer of the transitions: the state just before and just after each one (the steppers
/// call on_step at the event time before the transition, then on_event with the state after).
struct TransitionLog {
  struct Snapshot {
    double t;
    DamperStates from, to;
    System::State before, after;
  };
  std::vector<Snapshot> snapshots;
  System::State last;  // the state of the last on_step
  double t_last = 0;

  bool on_step(double t, const System::State& x, const DamperStates&) {
    last = x;
    t_last = t;
    return true;
  }
  void on_event(const EventRecord<double, DamperStates>& r, const System::State& after) {
    EXPECT_EQ(t_last, r.t) << "no step ended at the event";
    snapshots.push_back({r.t, r.from, r.to, last, after});
  }
  bool on_sample(double, const System::State&, const DamperStates&) { return true; }
};

struct Scene {
  TScene frame = make_t_frame(1);
  double m = 0.02, k = 1e3, preload = 0.4, X0 = 0.01;
  Eigen::VectorXd a, b;  // side * psi_w and psi_u at the contact (one entry: one mode)

  PointDamper<double> damper(double e, double mu_s, double mu_k) const {
    PointDamper<double> d(frame.platform, X0, m, k, preload, CoulombLaw<double>(mu_s, mu_k));
    d.separation = Separation::Separate;
    d.restitution = e;
    d.contact_point = ContactPoint::Fixed;
    return d;
  }
  std::vector<PointLoad<double>> load(double amplitude) const {
    return {PointLoad<double>::harmonic(frame.blade, 0.05, LoadDirection::GlobalX, amplitude,
                                        frame.basis.omega()[0])};
  }
};

/// Kinetic energy of the mode and of the damper (x' along u, y' along the normal: y_d' in
/// flight, a q' in contact at a fixed contact point).
double kinetic(const System& sys, const Scene& sc, const DamperStates& mode, const System::State& x) {
  const double qd = x[1], xd = x[sys.xd_offset()];
  const double yd = mode[0] == ContactState::Separated ? x[sys.flight_offset() + 1] : sc.a[0] * qd;
  return 0.5 * qd * qd + 0.5 * sc.m * (xd * xd + yd * yd);
}

RunOptions<double> run_options() {
  RunOptions<double> run;
  run.stepper.rtol = 1e-9;
  run.stepper.atol = 1e-13;
  run.stepper.output_interval = 1e-3;
  run.stepper.max_step = 1e-4;
  return run;
}

/// A run from the consistent start with `integrator`, its transitions in `log`.
SimulationResult<System> run(System& sys, double t_end, double* E0, TransitionLog& log,
                             Integrator integrator = Integrator::DormandPrince54) {
  System::State x = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  EXPECT_TRUE(sys.make_consistent(mode, 0.0, x));
  *E0 = sys.mechanical_energy(mode, 0.0, x);
  RunOptions<double> opt = run_options();
  opt.integrator = integrator;
  return simulate(sys, mode, 0.0, x, t_end, opt, log);
}

/// The shapes at the contact, read through point_shape (the load-vector path of the model,
/// not its impact code).
void read_shapes(const System& sys, Scene& sc) {
  sc.a = sys.point_shape(sc.frame.platform, sc.X0, LoadDirection::Transverse);
  sc.b = sys.point_shape(sc.frame.platform, sc.X0, LoadDirection::Axial);
}

/// Normal force of the damper in contact state `s` at (t, x), from the contact rows solved
/// here: q'' = -omega^2 q + F(t) psi_F + N a - f b (one undamped mode), N + m a q'' = N0, and
/// slip f = -sigma mu_k N, or stick f - m b q'' = k x.
double normal_force(const System& sys, const Scene& sc, ContactState s, double t, const System::State& x,
                    double mu_k) {
  const double w2 = sys.omega_squared()[0];
  const double psiF = sys.point_shape(sc.frame.blade, 0.05, LoadDirection::GlobalX)[0];
  const double r = -w2 * x[0] + sys.loads()[0].value(t) * psiF;
  const double a = sc.a[0], b = sc.b[0], m = sc.m, N0 = sc.preload;
  if (s == ContactState::Stick) {
    Eigen::Matrix3d A;
    A << 1.0, -a, b,  // q'' - a N + b f = r
        m * a, 1.0, 0.0,  // N + m a q'' = N0
        -m * b, 0.0, 1.0;  // f - m b q'' = k x
    return A.partialPivLu().solve(Eigen::Vector3d(r, N0, sc.k * x[sys.x_offset()]))[1];
  }
  const double sigma_mu = slip_sign(s) * mu_k;
  return (N0 - m * a * r) / (1.0 + m * a * (a + sigma_mu * b));
}

/// Gap acceleration in flight at a fixed contact, a q'' - N0/m, with q'' of the mode alone (the
/// damper in flight exerts no force): q'' = -omega^2 q + F(t) psi_F.
double flight_gap_acceleration(const System& sys, const Scene& sc, double t, const System::State& x) {
  const double psiF = sys.point_shape(sc.frame.blade, 0.05, LoadDirection::GlobalX)[0];
  const double qdd = -sys.omega_squared()[0] * x[0] + sys.loads()[0].value(t) * psiF;
  return sc.a[0] * qdd - sc.preload / sc.m;
}

struct Counts {
  int lift_offs = 0, bounces = 0, landings = 0;
};

/// Checks every lift-off and impact of a run of one damper (see the file comment); returns
/// the counts (a landing that leaves at once counts as a landing and a lift-off).
Counts check_transitions(const System& sys, const TransitionLog& log, const Scene& sc, double e, double mu_s, double mu_k) {
  Counts c;
  const Index yo = sys.flight_offset(), o = sys.energy_offset(), xo = sys.x_offset(), xdo = sys.xd_offset();
  const double a = sc.a[0], b = sc.b[0], m = sc.m;
  std::size_t k = 0;  // next impact of the log
  for (const auto& s : log.snapshots) {
    const System::State &x0 = s.before, &x1 = s.after;
    if (s.from[0] != ContactState::Separated) {
      if (s.to[0] != ContactState::Separated) continue;
      ++c.lift_offs;
      // N = 0 at the located event: to the event tolerance (time 1e-10 relative, N' ~ N0 omega
      // so |N| ~ 1e-9 N0), bound 1e-6 N0.
      EXPECT_NEAR(normal_force(sys, sc, s.from[0], s.t, x0, mu_k), 0.0, 1e-6 * sc.preload) << "lift-off at t = " << s.t;
      // The flight starts on the member with its velocity: y_d = a q, y_d' = a q' (fixed contact).
      EXPECT_NEAR(x1[yo], a * x0[0], 1e-15);
      EXPECT_NEAR(x1[yo + 1], a * x0[1], 1e-15);
      continue;
    }
    // The impact log tells a bounce from a landing; a landing whose normal force is not positive
    // leaves the member again in the same transition (a touch: the snapshot ends Separated).
    EXPECT_LT(k, sys.impacts().size());
    if (k >= sys.impacts().size()) break;
    const ContactState landed = sys.impacts()[k++].to;
    const bool bounce = landed == ContactState::Separated;
    (bounce ? c.bounces : c.landings) += 1;
    if (!bounce && s.to[0] == ContactState::Separated) ++c.lift_offs;
    const double yd0 = x0[yo + 1], yd1 = s.to[0] == ContactState::Separated ? x1[yo + 1] : a * x1[1];
    const double v_n = a * x0[1] - yd0, v_n1 = a * x1[1] - yd1;  // gap' before, after
    const double V1 = x1[xdo] - b * x1[1];
    const double L_n = -m * (yd1 - yd0), L_t = m * (x1[xdo] - x0[xdo]);
    const double scale = std::abs(x0[1]) + m * (std::abs(a * yd0) + std::abs(b * x0[xdo]));
    // Positions do not jump; the momentum of the pair is unchanged (round-off of the
    // velocity updates: 1e-13 of the terms).
    EXPECT_EQ(x1[0], x0[0]);
    EXPECT_EQ(x1[xo], x0[xo]);
    EXPECT_NEAR(x1[1] + m * (a * yd1 + b * x1[xdo]), x0[1] + m * (a * yd0 + b * x0[xdo]), 1e-13 * scale)
        << "impact at t = " << s.t;
    // Newton's law: approaching, then -e v_n (bounce) or persistent contact (landing rule:
    // e = 0, an approach slower than the landing speed, or a rebound whose apex
    // (e v_n)^2 / (2 |g''|) would not leave the landing band 1e-8 L, L = 0.04 m the platform).
    EXPECT_LT(v_n, 0.0);
    const double g2 = flight_gap_acceleration(sys, sc, s.t, x0), band = 1e-8 * 0.04;
    const bool in_band = g2 < 0 && e * e * v_n * v_n <= -2 * g2 * band;
    if (bounce) {
      EXPECT_NEAR(v_n1, -e * v_n, 1e-12 * std::abs(v_n));
      EXPECT_FALSE(in_band) << "v_n = " << v_n << ", g'' = " << g2;
    } else {
      EXPECT_TRUE(e == 0.0 || -v_n <= sys.dampers()[0].landing_speed || in_band) << "v_n = " << v_n;
    }
    // Coulomb's law for the impulses: stick (V = 0 after) within mu_s L_n, else mu_k L_n
    // against the sliding after the impact.
    EXPECT_GE(L_n, 0.0);
    const bool sticks = landed == ContactState::Stick;
    if (sticks || std::abs(V1) <= 1e-12 * std::abs(x0[xdo]) + 1e-15) {
      EXPECT_LE(std::abs(L_t), mu_s * L_n * (1 + 1e-12) + 1e-18);
    } else {
      EXPECT_NEAR(std::abs(L_t), mu_k * L_n, 1e-12 * L_n + 1e-18);
      EXPECT_LE(L_t * V1, 0.0);
    }
    // The kinetic energy lost equals the loss booked in the audit (round-off: 1e-12 of the
    // kinetic energy).
    const double lost = kinetic(sys, sc, s.from, x0) - kinetic(sys, sc, s.to, x1);
    EXPECT_NEAR(lost, x1[o + 4] - x0[o + 4], 1e-12 * kinetic(sys, sc, s.from, x0)) << "impact at t = " << s.t;
    EXPECT_GE(lost, -1e-15);
  }
  return c;
}

// e = 0.5 with friction: lift-offs, bounce sequences ending in a landing (the landing rule), and
// each transition checked as in the file comment; the audit closes (its terms ~0.3 J, residual
// to the tolerance of the run: 1e-9 relative, bound 1e-8 of the energy scale).
TEST(Separation, ImpactsKeepMomentumAndObeyNewtonAndCoulombWithTheBookedLoss) {
  Scene sc;
  const double e = 0.5, mu_s = 0.35, mu_k = 0.3;
  System sys(sc.frame.frame, sc.frame.basis, {sc.damper(e, mu_s, mu_k)}, sc.load(20.0));
  read_shapes(sys, sc);
  double E0 = 0;
  TransitionLog log;
  const auto r = run(sys, 0.3, &E0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  const Counts c = check_transitions(sys, log, sc, e, mu_s, mu_k);
  EXPECT_GE(c.lift_offs, 2);
  EXPECT_GE(c.bounces, 10);
  EXPECT_GE(c.landings, 1);
  EXPECT_EQ(sys.impacts().size(), static_cast<std::size_t>(c.bounces + c.landings));
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_GT(bal.impact_loss, 0.0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (std::abs(bal.mechanical) + bal.external_work));
}

// e = 1, no friction, no damping: the impacts bounce (landing_speed 0) and lose nothing, and
// the energy stays E0 + W_ext over many impacts (to the run's tolerance, bound 1e-8).
TEST(Separation, ElasticImpactsConserveEnergyOverManyImpacts) {
  Scene sc;
  PointDamper<double> d = sc.damper(1.0, 0.0, 0.0);
  d.landing_speed = 0.0;
  System sys(sc.frame.frame, sc.frame.basis, {d}, sc.load(20.0));
  read_shapes(sys, sc);
  double E0 = 0;
  TransitionLog log;
  const auto r = run(sys, 0.5, &E0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  const Counts c = check_transitions(sys, log, sc, 1.0, 0.0, 0.0);
  EXPECT_GE(c.bounces, 20);
  EXPECT_EQ(c.landings, 0);
  double booked = 0;
  for (const auto& imp : sys.impacts()) booked += std::abs(imp.energy_loss);
  EXPECT_LE(booked, 1e-14);  // -L (v_n - v_n)/2: zero up to round-off
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_NEAR(bal.mechanical - E0, bal.external_work, 1e-8 * (std::abs(bal.mechanical) + std::abs(bal.external_work)));
}

// e = 0: every impact lands (plastic), the run reaches its end (no ZenoGuard), and lands as
// often as it lifts off.
TEST(Separation, PlasticImpactsLandWithoutAZenoStop) {
  Scene sc;
  const double mu_s = 0.35, mu_k = 0.3;
  System sys(sc.frame.frame, sc.frame.basis, {sc.damper(0.0, mu_s, mu_k)}, sc.load(20.0));
  read_shapes(sys, sc);
  double E0 = 0;
  TransitionLog log;
  const auto r = run(sys, 0.3, &E0, log);
  ASSERT_TRUE(r.ok()) << r.message;
  const Counts c = check_transitions(sys, log, sc, 0.0, mu_s, mu_k);
  EXPECT_EQ(c.bounces, 0);
  EXPECT_GE(c.landings, 2);
  EXPECT_GE(c.lift_offs, c.landings);
  EXPECT_LE(c.lift_offs, c.landings + 1);
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (std::abs(bal.mechanical) + bal.external_work));
}

// The exponential integrator (the flight is part of the linear part of a separated mode at a
// fixed contact): the same checks, the audit closes, and the first lift-off and impact agree
// with DOPRI's to the event tolerances (1e-9 s; bound 1e-7 s).
TEST(Separation, ExponentialIntegratorAgreesWithDormandPrince) {
  Scene sc;
  const double e = 0.5, mu_s = 0.35, mu_k = 0.3;
  System dp(sc.frame.frame, sc.frame.basis, {sc.damper(e, mu_s, mu_k)}, sc.load(20.0));
  System ex(sc.frame.frame, sc.frame.basis, {sc.damper(e, mu_s, mu_k)}, sc.load(20.0));
  read_shapes(ex, sc);
  double E0 = 0, E0x = 0;
  TransitionLog log_dp, log;
  const auto rd = run(dp, 0.3, &E0, log_dp);
  const auto rx = run(ex, 0.3, &E0x, log, Integrator::Exponential);
  ASSERT_TRUE(rx.ok()) << rx.message;
  const Counts c = check_transitions(ex, log, sc, e, mu_s, mu_k);
  EXPECT_GE(c.bounces, 10);
  const auto bal = ex.energy_balance(rx.mode, rx.t, rx.x, E0x);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (std::abs(bal.mechanical) + bal.external_work));
  ASSERT_FALSE(dp.impacts().empty());
  ASSERT_FALSE(ex.impacts().empty());
  EXPECT_NEAR(ex.impacts().front().t, dp.impacts().front().t, 1e-7);
  for (const auto& ev : dp.events())
    if (ev.to == ContactState::Separated) {
      for (const auto& evx : ex.events())
        if (evx.to == ContactState::Separated) {
          EXPECT_NEAR(evx.t, ev.t, 1e-7);
          break;
        }
      break;
    }
}

// DamperStatistics counts the flight: the separated time against the flights rebuilt from the
// transitions' snapshots (sums of event times: round-off, bound 1e-12 s), bounces and landings
// against the snapshots' impact count, and the regime is intermittent contact (flights cover
// far more than 1 % of the run here).
TEST(Separation, StatisticsCountFlightsBouncesAndLandings) {
  Scene sc;
  System sys(sc.frame.frame, sc.frame.basis, {sc.damper(0.5, 0.35, 0.3)}, sc.load(20.0));
  System::State x = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double t_end = 0.3;
  // The statistics and the transition log observe the same run.
  struct Both {
    DamperStatistics<System> stats;
    TransitionLog log;
    bool on_step(double t, const System::State& y, const DamperStates& m) {
      return stats.on_step(t, y, m) && log.on_step(t, y, m);
    }
    void on_event(const EventRecord<double, DamperStates>& rec, const System::State& after) {
      stats.on_event(rec, after);
      log.on_event(rec, after);
    }
    bool on_sample(double t, const System::State& y, const DamperStates& m) { return stats.on_sample(t, y, m); }
  } both{DamperStatistics<System>(sys, mode, 0.0, x, {0.0, t_end, 2 * std::acos(-1.0) / sc.frame.basis.omega()[0]}), {}};
  const auto r = simulate(sys, mode, 0.0, x, t_end, run_options(), both);
  ASSERT_TRUE(r.ok()) << r.message;
  const auto& stats = both.stats;
  double flying = 0, since = -1;
  Index impacts = 0;
  for (const auto& s : both.log.snapshots) {
    impacts += s.from[0] == ContactState::Separated ? 1 : 0;
    const bool was = s.from[0] == ContactState::Separated, is = s.to[0] == ContactState::Separated;
    if (!was && is) since = s.t;
    if (was && !is) flying += s.t - since;
  }
  if (r.mode[0] == ContactState::Separated) flying += t_end - since;
  const auto st = stats.statistics(0);
  EXPECT_NEAR(st.separated_time, flying, 1e-12);
  EXPECT_GT(st.separated_fraction, 0.01);
  EXPECT_EQ(st.bounces + st.landings, impacts);
  EXPECT_GE(st.bounces, 10);
  EXPECT_GE(st.landings, 1);
  EXPECT_EQ(st.regime, DamperRegime::IntermittentContact);
  EXPECT_STREQ(to_string(st.regime), "intermittent contact");
  EXPECT_EQ(classify_regime(0.5, 0.0099), DamperRegime::StickSlip);
  EXPECT_EQ(classify_regime(0.5, 0.01), DamperRegime::IntermittentContact);
}

// Two dampers on the six-mode T-frame (the paper's dampers, ten times heavier, under ten times
// the paper's load; with Separation::Stop the run ends at the first lift-off): each impact's W
// includes the other damper's
// contact rows (stuck or slipping), so the audit closes only if the impulse response through
// them is right. Fixed contacts: the booked losses are the exact kinetic energy changes and
// the audit closes to the run's tolerance (bound 1e-7 of the energy scale); moving contacts:
// the other damper's slope terms are left out of W (O(slope ~ 1e-3) of the losses, bound 1e-4).
TEST(Separation, TwoDampersOnTheBladeKeepTheAuditClosed) {
  for (const bool moving : {false, true}) {
    const TScene s = make_t_frame();
    auto stopping = paper_dampers(s, 0.5);
    for (auto& d : stopping) d.mass *= 10.0;  // N0 / m = 57 m/s^2: lifted off by the platform's rocking
    auto dampers = stopping;
    for (auto& d : dampers) {
      d.separation = Separation::Separate;
      d.restitution = 0.5;
      d.landing_speed = 1e-4;
    }
    ModelOptions<double> opt;
    opt.moving_contact = moving;
    opt.end_policy = EndPolicy::Throw;
    System sys(s.frame, s.basis, dampers, paper_load(s, 200.0), opt);
    System stop(s.frame, s.basis, stopping, paper_load(s, 200.0), opt);
    Recorder rec, rec_stop;
    double E0 = 0;
    RunOptions<double> run = run_options();
    run.stepper.max_step = 1e-4;
    const auto r = run_from_rest(sys, 0.1, run, rec, &E0);
    // (with a moving contact the dampers slide off the platform at ~0.01 s under this load: the
    // audit is checked at that stop)
    ASSERT_TRUE(r.ok() || (moving && sys.stop_reason() == System::StopReason::LeftMember)) << r.message;
    const auto r_stop = run_from_rest(stop, 0.1, run, rec_stop);
    EXPECT_FALSE(r_stop.ok());  // the same scene without separation stops at a lift-off
    EXPECT_EQ(stop.stop_reason(), System::StopReason::LiftOff);
    EXPECT_GE(sys.impacts().size(), 2u) << (moving ? "moving" : "fixed");
    const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
    const double scale = std::abs(bal.mechanical) + bal.external_work + bal.friction_dissipation;
    EXPECT_GT(bal.impact_loss, 0.0);
    EXPECT_NEAR(bal.residual, 0.0, (moving ? 1e-4 : 1e-7) * scale) << (moving ? "moving" : "fixed");
  }
}

/// The blade example's scene (paper dampers at 1 N, elastic walls at the platform ends; with
/// `separable`, e = 0.5 at the platform) restarted 0.1 ms before an event of its 20 s run: at
/// t = 14.91934 s damper 1's slip towards the finish wall (0.1 mm from it) ends, V = 0, where its
/// stuck rows give N < 0 while its slip had N > 0. The audit terms start from zero.
struct BladeRestart {
  std::unique_ptr<System> sys;
  System::State x;
  DamperStates mode{2, ContactState::SlipNegative};
  double t0 = 14.919242048624225;
  SimulationResult<System> run() {
    RunOptions<double> options;  // the example's settings
    options.stepper.rtol = 1e-7;
    options.stepper.atol = 1e-10;
    options.stepper.event_time_tolerance = 1e-12;
    return simulate(*sys, mode, t0, x, t0 + 1e-3, options);
  }
};

BladeRestart blade_restart(bool separable) {
  const TScene s = make_t_frame(6, 20, 8);
  auto dampers = paper_dampers(s, 1.0);
  for (auto& d : dampers) {
    d.start_end = d.finish_end = MemberEnd::Wall;
    d.wall_restitution = 1.0;
    if (!separable) continue;
    d.separation = Separation::Separate;
    d.restitution = 0.5;
  }
  BladeRestart b;
  b.sys = std::make_unique<System>(s.frame, s.basis, dampers, paper_load(s));
  // q, q', x, x', X, then (separable) y_d, y_d' of both dampers.
  const std::vector<double> state{
      -0.0019754475810996961, -2.8626503336757632e-06, -3.5571823212488428e-06,
      -6.6557832952638914e-07, -6.5108761028171652e-08, 4.1247120196170872e-07,
      0.24409358463353442, 0.018354134404393693, 0.0058873812327234548,
      -0.0004253153240809254, -0.0058668491737447377, 0.0089618618234004153,
      9.2816649537188006e-05, 0.00020173397481291767, -0.6561302615774981, 1.3514466412464843,
      0.019775193732781426, 0.039884488357682116, 0.00017777179117795916, 0.0014293448838080722,
      -0.25001965693168976, -0.089812746511181304};
  b.x = b.sys->initial_state();
  const std::size_t used = separable ? state.size() : state.size() - 4;
  EXPECT_EQ(b.x.size(), static_cast<Index>(used) + 5);  // + the five audit terms, zero
  for (std::size_t k = 0; k < used; ++k) b.x[static_cast<Index>(k)] = state[k];
  b.mode[1] = ContactState::SlipPositive;
  return b;
}

// The transition may not leave the damper stuck with N < 0: its N guard would start the next mode
// below zero, where it cannot fire, and its stick guard mu_s N - f < 0 fired again at every step
// (in the 20 s run: 82 146 events, then a ZenoGuard stop). It separates, and the run goes on (two
// events in the millisecond: the separation, then a landing). The audit's largest term is
// 2.1e-3 J and it closes to the run's tolerance (measured 1.3e-7 of that at rtol 1e-7; bound 1e-6).
TEST(Separation, ASlipEndingWithoutNormalForceLeavesTheMember) {
  BladeRestart b = blade_restart(true);
  System& sys = *b.sys;
  const double E0 = sys.mechanical_energy(b.mode, b.t0, b.x);
  const auto r = b.run();
  ASSERT_TRUE(r.ok()) << r.message;
  bool separated = false;
  for (const auto& e : sys.events()) separated = separated || (e.damper == 1 && e.to == ContactState::Separated);
  EXPECT_TRUE(separated) << "damper 1 did not leave the member";
  const auto& e = sys.evaluate(r.mode, r.t, r.x);
  for (Index i = 0; i < 2; ++i)
    if (r.mode[i] != ContactState::Separated) {
      EXPECT_GT(e.N[i], 0.0) << "damper " << i << " in contact at the end";
    }
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  const double scale = std::max({std::abs(bal.mechanical - E0), std::abs(bal.external_work), bal.friction_dissipation,
                                 bal.impact_loss});
  EXPECT_GT(scale, 0.0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-6 * scale) << "scale " << scale << ", events " << r.stats.events;
}

// The same event with dampers that may not separate (Separation::Stop, lift-off watched): the
// run stops there with a lift-off of damper 1 instead of keeping it stuck with N < 0.
TEST(Separation, ASlipEndingWithoutNormalForceIsALiftOffWhereDampersMayNotSeparate) {
  BladeRestart b = blade_restart(false);
  const auto r = b.run();
  EXPECT_EQ(r.status, Status::StoppedBySystem) << r.message;
  EXPECT_EQ(b.sys->stop_reason(), System::StopReason::LiftOff) << r.message;
  EXPECT_EQ(b.sys->stop_damper(), 1);
  EXPECT_GT(r.t, b.t0 + 5e-5);  // at the end of the slip, 0.1 ms after the start
  EXPECT_LT(r.stats.events, 10);
}

// ---- member ends per end: a rigid wall (MemberEnd::Wall) ----------------------------------

/// The one-mode scene with a free-sliding damper (no spring) between two walls at the platform's
/// ends, started sliding at V0 with the platform loaded at the mode's frequency.
struct WallRun {
  System sys;
  TransitionLog log;
  SimulationResult<System> result;
  double E0 = 0;
};

std::unique_ptr<WallRun> run_between_walls(double e_wall, double mu, double t_end) {
  Scene sc;
  PointDamper<double> d(sc.frame.platform, 0.02, sc.m, 0.0, sc.preload, CoulombLaw<double>(mu, mu));
  d.start_end = MemberEnd::Wall;
  d.finish_end = MemberEnd::Wall;
  d.wall_restitution = e_wall;
  d.initial_state = ContactState::SlipPositive;
  auto w = std::make_unique<WallRun>(WallRun{System(sc.frame.frame, sc.frame.basis, {d}, sc.load(0.5)), {}, {}, 0.0});
  System::State x = w->sys.initial_state();
  x[w->sys.xd_offset()] = 0.2;  // V0 = 0.2 m/s: the 0.04 m platform is crossed in 0.2 s
  DamperStates mode = w->sys.requested_mode();
  EXPECT_TRUE(w->sys.make_consistent(mode, 0.0, x));
  w->E0 = w->sys.mechanical_energy(mode, 0.0, x);
  w->result = simulate(w->sys, mode, 0.0, x, t_end, run_options(), w->log);
  return w;
}

/// Every wall impact of the run, checked from its snapshot: X at an end (to the event tolerance),
/// positions unchanged, V = x' - b(X) q' reversed by Newton's law V -> -e V (b from point_shape).
int check_walls(const System& sys, const TransitionLog& log, double e_wall) {
  int walls = 0;
  const double L = 0.04;
  const Index xo = sys.contact_offset(), xdo = sys.xd_offset();
  for (const auto& s : log.snapshots) {
    const double X = s.before[xo];
    if (s.from[0] == ContactState::Separated || (X > 1e-9 && X < L - 1e-9)) continue;
    ++walls;
    const auto platform = sys.dampers()[0].member;
    const Eigen::VectorXd b = sys.point_shape(platform, std::min(std::max(X, 0.0), L), LoadDirection::Axial);
    const double V0 = s.before[xdo] - b.dot(s.before.segment(1, 1));
    const double V1 = s.after[xdo] - b.dot(s.after.segment(1, 1));
    EXPECT_EQ(s.after[0], s.before[0]);
    EXPECT_EQ(s.after[xo], X);
    EXPECT_LT(X < L / 2 ? V0 : -V0, 0.0) << "moving into the wall";
    // b(X) at the clamped X against the model's b at the located X: 1e-9 m apart (slope of psi_u
    // ~ 1/L): 1e-9 relative; bound 1e-8.
    EXPECT_NEAR(V1, -e_wall * V0, 1e-8 * std::abs(V0)) << "wall impact at t = " << s.t;
  }
  return walls;
}

// e = 1: the damper shuttles between the walls, every impact reverses V exactly, nothing is
// lost (booked losses ~ round-off) and the audit closes to the run's tolerance (bound 1e-8
// relative). The check is sharp: without the normal impulse that keeps the contact closed on
// the sloped platform (V's jump moves the damper along the normal by s dV) the residual was
// 2e-5 J, 2e-3 of the energy.
TEST(MemberEnds, ElasticWallsReverseTheSlidingVelocityAndKeepTheEnergy) {
  const auto w = run_between_walls(1.0, 0.0, 1.0);
  ASSERT_TRUE(w->result.ok()) << w->result.message;
  EXPECT_GE(check_walls(w->sys, w->log, 1.0), 4);
  double booked = 0;
  for (const auto& imp : w->sys.impacts()) {
    EXPECT_TRUE(imp.wall);
    booked += std::abs(imp.energy_loss);
  }
  EXPECT_LE(booked, 1e-15);
  const auto bal = w->sys.energy_balance(w->result.mode, w->result.t, w->result.x, w->E0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (std::abs(bal.mechanical) + std::abs(bal.external_work)));
}

// e = 0.5 with friction: the impacts lose (1 - e^2) of the relative kinetic energy, booked in
// D_imp; the audit closes (bound as above); the run never leaves the platform.
TEST(MemberEnds, InelasticWallsBookTheirLossAndTheAuditCloses) {
  const auto w = run_between_walls(0.5, 0.05, 1.0);
  ASSERT_TRUE(w->result.ok()) << w->result.message;
  EXPECT_GE(check_walls(w->sys, w->log, 0.5), 2);
  const auto bal = w->sys.energy_balance(w->result.mode, w->result.t, w->result.x, w->E0);
  EXPECT_GT(bal.impact_loss, 0.0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (std::abs(bal.mechanical) + std::abs(bal.external_work) + bal.impact_loss));
  const double X = w->result.x[w->sys.contact_offset()];
  EXPECT_GE(X, -1e-9);
  EXPECT_LE(X, 0.04 + 1e-9);
}

// An end left at Default follows ModelOptions::end_policy (Throw: stop), per end.
TEST(MemberEnds, DefaultEndStopsTheRunAsBefore) {
  Scene sc;
  PointDamper<double> d(sc.frame.platform, 0.02, sc.m, 0.0, sc.preload, CoulombLaw<double>(0.0, 0.0));
  d.finish_end = MemberEnd::Wall;  // the start end stays Default: Throw -> stop
  d.initial_state = ContactState::SlipPositive;
  System sys(sc.frame.frame, sc.frame.basis, {d}, sc.load(2.0));
  System::State x = sys.initial_state();
  x[sys.xd_offset()] = 0.2;
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const auto r = simulate(sys, mode, 0.0, x, 1.0, run_options());
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(sys.stop_reason(), System::StopReason::LeftMember);
  ASSERT_EQ(sys.impacts().size(), 1u);  // the wall at X = L first, then X = 0 stops the run
  EXPECT_TRUE(sys.impacts()[0].wall);
  EXPECT_NEAR(r.x[sys.contact_offset()], 0.0, 1e-9);
}

// The rates of a separable damper include its flight (rate 0), so RK4's stability check knows it.
TEST(Separation, StepRatesNameTheFlight) {
  Scene sc;
  const System sys(sc.frame.frame, sc.frame.basis, {sc.damper(0.5, 0.35, 0.3)}, sc.load(20.0));
  bool found = false;
  for (const auto& rate : sys.step_rates())
    if (rate.source.find("flight") != std::string::npos) {
      found = true;
      EXPECT_EQ(rate.lambda, std::complex<double>(0.0, 0.0));
    }
  EXPECT_TRUE(found);
  EXPECT_EQ(sys.state_size(), 2 + 2 + 2 + 5);  // q q' | x x' | y_d y_d' | 5 audit terms
  EXPECT_EQ(sys.linear_size(), 6);
}

}  // namespace separation_test

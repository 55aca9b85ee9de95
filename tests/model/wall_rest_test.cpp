// Resting contact at a wall (docs/model_separation.md "Resting at a wall"): a damper that its
// spring keeps pushing into a MemberEnd::Wall comes to rest against it (an arrival at or below
// PointDamper::landing_speed, or a plastic wall), the wall takes the push beyond mu_s N, and
// the damper leaves when the force pulls it away beyond the friction bound. The references are
// closed forms, not the model's code:
//   * bounces (e = 1/2) on a straight cantilever, whose bending mode has psi_u = 0 (the damper's
//     tangential motion m x'' = -k x is then that of a lone oscillator hitting a fixed stop, the
//     ball-on-a-plate analogue with the spring in place of gravity): impact speeds e^k v0, the
//     flight times (2/w) atan(v / (w x_w)), the accumulation time, then rest with the static
//     reaction k x_w;
//   * a plastic arrival on the T-frame's platform (one mode, constant normal load): while it
//     rests the coupled system is the linear oscillator (1 + m b^2) q'' + (w^2 + k b^2) q = P(t)
//     solved in closed form from the state after the arrival; the wall's reaction is the force
//     needed to hold the damper, k x + m b q'', beyond mu_s N0, and the damper leaves at the
//     first time that force falls below -mu_s N0.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace wall_rest_test {

using namespace model_test;

RunOptions<double> wall_run_options() {
  RunOptions<double> run;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-14;
  run.stepper.max_step = 1e-4;
  run.stepper.output_interval = 1e-3;
  return run;
}

/// The run's samples and the first state after the damper came to rest.
struct RestObserver : NullObserver {
  struct Sample {
    double t;
    DamperStates mode;
    System::State x;
  };
  std::vector<Sample> samples;
  bool rested = false;
  double t_rest = 0;
  System::State x_rest;
  void on_event(const EventRecord<double, DamperStates>& r, const System::State& x_after) {
    if (!rested && r.to.wall(0) != WallRest::None) {
      rested = true;
      t_rest = r.t;
      x_rest = x_after;
    }
  }
  bool on_sample(double t, const System::State& x, const DamperStates& mode) {
    samples.push_back({t, mode, x});
    return true;
  }
};

// ---- bounces on a cantilever ----------------------------------------------------------------

// e = 1/2, no friction: the damper starts at rest 5 mm from the start wall with its spring
// stretched by x0 = 10 mm, so the wall stands at x_w = 5 mm and the spring pushes it into the
// wall with k x. Between impacts the motion is x = x_w cos(w s) + (v/w) sin(w s) (w = sqrt(k/m)),
// back at the wall after T(v) = (2/w) atan(v / (w x_w)) with the speed v it left with, having
// turned at sqrt(x_w^2 + (v/w)^2) - x_w from the wall: the impact speeds are v0 e^k with
// v0 = w sqrt(x0^2 - x_w^2), the impact times t1 + sum T, and the rest comes at the first impact
// at or below the landing speed (1e-4 m/s), or at the turning point of the first rebound that
// stays within the wall band (1e-8 L = 2e-9 m here: FrictionDampedSystem::rest_at_wall), whichever
// is first (here the band, after 11 impacts; the margin to the band is 5 % in speed). Before the
// rule existed the bounces went on (97373 impacts in 0.1 s).
TEST(WallRest, BouncesDecayAsTheBallOnAPlateThenTheDamperRests) {
  const Cantilever c;
  const double m = 0.02, k = 100.0, N0 = 0.1, e = 0.5, X0 = 0.005, x0 = 0.01, x_w = x0 - X0;
  PointDamper<double> d(c.member, X0, m, k, N0, CoulombLaw<double>(0.0, 0.0));
  d.normal_load = NormalLoad::Constant;
  d.start_end = MemberEnd::Wall;
  d.finish_end = MemberEnd::Wall;
  d.wall_restitution = e;
  System sys(c.frame, c.basis, {d});
  // The premise of the closed form: the bending mode does not move the member along its axis.
  ASSERT_LT(sys.point_shape(c.member, X0, LoadDirection::Axial).cwiseAbs().maxCoeff(), 1e-12);
  System::State x = sys.initial_state();
  x[sys.x_offset()] = x0;
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(mode, 0.0, x);
  RestObserver obs;
  const auto r = simulate(sys, mode, 0.0, x, 0.1, wall_run_options(), obs);
  ASSERT_TRUE(r.ok()) << r.message;

  const double w = std::sqrt(k / m), v0 = w * std::sqrt(x0 * x0 - x_w * x_w);
  const auto flight = [&](double v) { return 2.0 / w * std::atan(v / (w * x_w)); };
  const double band = 1e-8 * 0.2;
  const auto excursion = [&](double v) { return std::sqrt(x_w * x_w + v * v / (w * w)) - x_w; };
  int k_rest = 0;  // the last impact: at or below the landing speed, or its rebound within the band
  while (v0 * std::pow(e, k_rest) > d.landing_speed && excursion(v0 * std::pow(e, k_rest + 1)) > band) ++k_rest;
  const bool rests_at_impact = v0 * std::pow(e, k_rest) <= d.landing_speed;
  const auto& hits = sys.impacts();
  ASSERT_EQ(static_cast<int>(hits.size()), k_rest + 1);
  double t_k = std::acos(x_w / x0) / w;  // first impact
  for (int j = 0; j <= k_rest; ++j) {
    const double v = v0 * std::pow(e, j);
    if (j > 0) t_k += flight(v);
    EXPECT_TRUE(hits[static_cast<std::size_t>(j)].wall);
    // Times and speeds: the run's tolerance (rtol 1e-10) and the event tolerance (1e-12 s) give
    // ~1e-10 relative; bounds 1e-8 s and 1e-8 of v0.
    EXPECT_NEAR(hits[static_cast<std::size_t>(j)].t, t_k, 1e-8) << "impact " << j;
    EXPECT_NEAR(hits[static_cast<std::size_t>(j)].sliding_velocity, -v, 1e-8 * v0) << "impact " << j;
    const bool last = j == k_rest && rests_at_impact;
    EXPECT_NEAR(hits[static_cast<std::size_t>(j)].sliding_velocity_after, last ? 0.0 : e * v, 1e-8 * v0) << "impact " << j;
    EXPECT_EQ(hits[static_cast<std::size_t>(j)].to, last ? ContactState::Stick : ContactState::SlipPositive);
  }
  // The accumulation time of the infinite sequence, t1 + sum_{j >= 1} T(v0 e^j): the rest comes
  // before it by at most the remaining flights, sum_{j > k_rest} T(v0 e^j) <= 2 v0 e^(k_rest+1) /
  // ((1 - e) w^2 x_w) (atan(z) <= z), 4e-6 s here.
  double t_inf = std::acos(x_w / x0) / w;
  for (int j = 1; j < 200; ++j) t_inf += flight(v0 * std::pow(e, j));
  const double rest_bound = 2.0 * v0 * std::pow(e, k_rest + 1) / ((1.0 - e) * w * w * x_w);
  ASSERT_TRUE(obs.rested);
  EXPECT_LE(obs.t_rest, t_inf + 1e-8);
  EXPECT_GE(obs.t_rest, t_inf - rest_bound - 1e-8);
  // At rest: at the wall (X = 0 exactly), stuck, spring at x_w (to the band), the wall holding
  // the whole push k x (no friction); a handful of events, not a Zeno sequence.
  EXPECT_EQ(r.mode.wall(0), WallRest::Start);
  EXPECT_EQ(r.mode.to_string(), "stick@start");
  EXPECT_EQ(r.x[sys.contact_offset()], 0.0);
  EXPECT_NEAR(r.x[sys.x_offset()], x_w, band + 1e-9);
  const auto& ev = sys.evaluate(r.mode, r.t, r.x);
  EXPECT_NEAR(ev.wall_force[0], k * r.x[sys.x_offset()], 1e-9 * k * x_w);
  EXPECT_EQ(ev.f[0], 0.0);
  EXPECT_LT(r.stats.events, 4 * (k_rest + 2));
  // The audit closes: the impacts' losses are booked, the resting wall does no work (residual:
  // the run's tolerance on an energy of 0.5 k x0^2 = 5e-3 J; bound 1e-8 of it).
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_GT(bal.impact_loss, 0.0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * 0.5 * k * x0 * x0);
}

// A push of 5e4 m/s^2 (k x_w / m with k = 1e5): a rebound just above the landing speed turns
// within e^2 v^2 / (2 a) ~ 3e-14 m of the wall, closer than the stepper's guard_zero_tolerance
// (1e-12), so the end guard of the slip back towards the wall starts "at zero" and cannot see the
// crossing. The damper, at rest at the wall and pushed into it, rests there (the band rule of
// FrictionDampedSystem::rest_at_wall) instead of tunnelling through the wall: before that rule
// it slid on beyond X = 0 (X < 0 at the end of the run; the blade example at 1 N with e = 1/2
// walls crept 3e-8 m past its finish wall through 9e4 bounces). The impacts before the rest
// follow the closed form as above.
TEST(WallRest, AStiffPushRestsAtTheWallInsteadOfTunnelling) {
  const Cantilever c;
  const double m = 0.02, k = 1e5, e = 0.5, X0 = 0.005, x0 = 0.015, x_w = x0 - X0;
  PointDamper<double> d(c.member, X0, m, k, 0.1, CoulombLaw<double>(0.0, 0.0));
  d.normal_load = NormalLoad::Constant;
  d.start_end = MemberEnd::Wall;
  d.wall_restitution = e;
  System sys(c.frame, c.basis, {d});
  System::State x = sys.initial_state();
  x[sys.x_offset()] = x0;
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const auto r = simulate(sys, mode, 0.0, x, 0.05, wall_run_options());
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.mode.wall(0), WallRest::Start);
  EXPECT_EQ(r.x[sys.contact_offset()], 0.0);
  const auto& ev = sys.evaluate(r.mode, r.t, r.x);
  // Static balance, no friction: the wall takes k x, x within the band 1e-8 L = 2e-9 m of x_w.
  EXPECT_NEAR(r.x[sys.x_offset()], x_w, 3e-9);
  EXPECT_NEAR(ev.wall_force[0], k * r.x[sys.x_offset()], 1e-9 * k * x_w);
  const double w = std::sqrt(k / m), v0 = w * std::sqrt(x0 * x0 - x_w * x_w);
  const auto excursion = [&](double v) { return std::sqrt(x_w * x_w + v * v / (w * w)) - x_w; };
  const auto& hits = sys.impacts();
  ASSERT_GE(hits.size(), 2u);
  for (std::size_t j = 0; j < hits.size(); ++j)  // (bound as above, 1e-8 of v0)
    EXPECT_NEAR(hits[j].sliding_velocity, -v0 * std::pow(e, static_cast<double>(j)), 1e-8 * v0) << "impact " << j;
  // It rests at the turning point of the first rebound within the band (2e-9 m).
  const double v_last = v0 * std::pow(e, static_cast<double>(hits.size() - 1));
  EXPECT_LE(excursion(e * v_last), 2e-9);
  EXPECT_GT(excursion(v_last), 2e-9);
  EXPECT_LT(r.stats.events, 4 * static_cast<Index>(hits.size() + 2));
}

// ---- a plastic arrival on the T-frame, rest under a harmonic drive, leaving ----------------

struct DriveScene {
  TScene frame = make_t_frame(1);
  double m = 0.02, k = 10.0, N0 = 0.4, mu_s = 0.35, mu_k = 0.3, X0 = 0.002, x0 = 0.02;
  double amplitude = 60.0, Omega = 0.0;  // load on the blade at 0.05 m along global X
  PointDamper<double> damper() const {
    PointDamper<double> d(frame.platform, X0, m, k, N0, CoulombLaw<double>(mu_s, mu_k));
    d.normal_load = NormalLoad::Constant;
    d.start_end = MemberEnd::Wall;
    d.finish_end = MemberEnd::Wall;
    d.wall_restitution = 0.0;
    return d;
  }
};

/// The force needed to hold the resting damper, k x + m b q'', in closed form from the state xa
/// after the arrival at ta: (1 + m b^2) q'' + (w^2 + k b^2) q = P0 + P1 sin(Omega t) with
/// x = x_a + b (q - q_a), P0 = N0 a - k b (x_a - b q_a), P1 = A psi_F.
struct RestingForce {
  double M, K, P0, B, we, C, S, ta, xa, qa, b, m, k, Omega;
  RestingForce(const System& sys, const DriveScene& sc, double t_a, const System::State& x_a) {
    const double a = sys.point_shape(sc.frame.platform, 0.0, LoadDirection::Transverse)[0];
    b = sys.point_shape(sc.frame.platform, 0.0, LoadDirection::Axial)[0];
    const double psiF = sys.point_shape(sc.frame.blade, 0.05, LoadDirection::GlobalX)[0];
    const double w2 = sys.omega_squared()[0];
    m = sc.m, k = sc.k, Omega = sc.Omega, ta = t_a;
    qa = x_a[0], xa = x_a[sys.x_offset()];
    M = 1.0 + m * b * b;
    K = w2 + k * b * b;
    P0 = sc.N0 * a - k * b * (xa - b * qa);
    B = sc.amplitude * psiF / (K - M * Omega * Omega);
    we = std::sqrt(K / M);
    C = qa - P0 / K - B * std::sin(Omega * ta);
    S = (x_a[1] - B * Omega * std::cos(Omega * ta)) / we;
  }
  double q(double t) const {
    const double s = t - ta;
    return P0 / K + B * std::sin(Omega * t) + C * std::cos(we * s) + S * std::sin(we * s);
  }
  double qdd(double t) const {
    const double s = t - ta;
    return -Omega * Omega * B * std::sin(Omega * t) - we * we * (C * std::cos(we * s) + S * std::sin(we * s));
  }
  double force(double t) const { return k * (xa + b * (q(t) - qa)) + m * b * qdd(t); }
};

// e = 0 at the start wall: the spring (k x ~ 0.18 N) pushes the damper past the friction
// bound (mu_s N0 = 0.14 N) into the wall, where it arrives plastically and rests: one wall
// impact, no chatter. While it rests the wall's reaction is k x + m b q'' - mu_s N0 and the
// friction force mu_s N0 (closed form above); the drive at 0.8 of the coupled frequency makes
// the member pull the damper away, and it leaves (slip+) when k x + m b q'' = -mu_s N0. Before
// the rule, the arrival stuck, slipped into the wall again at once and the run ended in a
// ZenoGuard stop.
TEST(WallRest, PlasticArrivalRestsWithTheStaticReactionAndLeavesWhenTheDriveReverses) {
  DriveScene sc;
  {
    const System probe(sc.frame.frame, sc.frame.basis, {sc.damper()});
    const double b = probe.point_shape(sc.frame.platform, 0.0, LoadDirection::Axial)[0];
    sc.Omega = 0.8 * std::sqrt((probe.omega_squared()[0] + sc.k * b * b) / (1.0 + sc.m * b * b));
  }
  System sys(sc.frame.frame, sc.frame.basis, {sc.damper()},
             {PointLoad<double>::harmonic(sc.frame.blade, 0.05, LoadDirection::GlobalX, sc.amplitude, sc.Omega)});
  System::State x = sys.initial_state();
  x[sys.x_offset()] = sc.x0;
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  ASSERT_EQ(mode[0], ContactState::SlipNegative);  // k x0 = 0.2 N > mu_s N0
  const double E0 = sys.mechanical_energy(mode, 0.0, x);
  RestObserver obs;
  const double t_end = 0.2;
  const auto r = simulate(sys, mode, 0.0, x, t_end, wall_run_options(), obs);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_TRUE(obs.rested);
  ASSERT_GE(sys.impacts().size(), 1u);
  EXPECT_TRUE(sys.impacts()[0].wall);
  EXPECT_EQ(sys.impacts()[0].sliding_velocity_after, 0.0);
  EXPECT_EQ(obs.x_rest[sys.contact_offset()], 0.0);

  const RestingForce hold(sys, sc, obs.t_rest, obs.x_rest);
  const double cap = sc.mu_s * sc.N0;
  // The leaving time: the first root of hold.force + mu_s N0 after the arrival (scan at 1e-5 s,
  // then bisection to 1e-14 s).
  double t_leave = -1;
  for (double t = obs.t_rest; t < t_end; t += 1e-5)
    if (hold.force(t + 1e-5) + cap < 0.0) {
      double lo = t, hi = t + 1e-5;
      while (hi - lo > 1e-14) {
        const double mid = 0.5 * (lo + hi);
        (hold.force(mid) + cap < 0.0 ? hi : lo) = mid;
      }
      t_leave = hi;
      break;
    }
  ASSERT_GT(t_leave, obs.t_rest + 1e-3) << "the drive must reverse the force within the run";
  ASSERT_GT(hold.force(obs.t_rest), cap) << "the wall must take a share at the arrival";

  // While resting (samples before t_leave), the reaction and the friction force of the
  // evaluation against the closed form (q to the run's rtol 1e-10 of ~1e-4: the forces to
  // ~1e-9 N; bound 1e-6 N).
  int resting = 0;
  for (const auto& s : obs.samples) {
    if (s.t <= obs.t_rest || s.t >= t_leave - 1e-6) continue;
    ASSERT_EQ(s.mode.wall(0), WallRest::Start) << "t = " << s.t;
    ++resting;
    const auto& ev = sys.evaluate(s.mode, s.t, s.x);
    const double f = hold.force(s.t);
    EXPECT_NEAR(ev.wall_force[0], std::max(f - cap, 0.0), 1e-6) << "t = " << s.t;
    EXPECT_NEAR(ev.f[0], std::min(f, cap), 1e-6) << "t = " << s.t;
    EXPECT_EQ(s.x[sys.contact_offset()], 0.0);
  }
  EXPECT_GE(resting, 5);
  // It leaves at the closed-form time, sliding away from the wall; no other impact before.
  const auto& events = sys.events();
  bool left = false;
  for (const auto& ev : events) {
    if (ev.t <= obs.t_rest || ev.from != ContactState::Stick) continue;
    EXPECT_EQ(ev.to, ContactState::SlipPositive);
    // (event tolerance 1e-12 s; the closed form's force against the run's, slope ~ 10 N/s: 1e-9 s)
    EXPECT_NEAR(ev.t, t_leave, 1e-7);
    left = true;
    break;
  }
  EXPECT_TRUE(left);
  EXPECT_EQ(sys.impacts()[0].to, ContactState::Stick);
  // The audit closes over arrival, rest and leaving (the arrival's loss booked; bound 1e-8 of
  // the energy scale).
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_GT(bal.impact_loss, 0.0);
  const double scale = std::abs(bal.mechanical) + std::abs(bal.external_work) + bal.friction_dissipation +
                       bal.impact_loss;
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * scale);
}

// A resting mark is checked against the damper's ends; the mark of a damper that left Stick
// does not count (wall() is None, modes compare equal).
TEST(WallRest, MarksAreValidatedAndOnlyCountWhileStuck) {
  DriveScene sc;
  PointDamper<double> d = sc.damper();
  d.start_end = MemberEnd::Stop;
  System sys(sc.frame.frame, sc.frame.basis, {d});
  System::State x = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  mode.set_wall(0, WallRest::Start);
  EXPECT_THROW(sys.evaluate(mode, 0.0, x), std::invalid_argument);
  mode.set_wall(0, WallRest::Finish);  // the finish end is a wall
  EXPECT_NO_THROW(sys.evaluate(mode, 0.0, x));
  DamperStates other = mode;
  other[0] = ContactState::SlipPositive;
  EXPECT_EQ(other.wall(0), WallRest::None);
  DamperStates plain = sys.requested_mode();
  plain[0] = ContactState::SlipPositive;
  EXPECT_EQ(other, plain);
  EXPECT_NE(mode, sys.requested_mode());
}

}  // namespace wall_rest_test

// A separated damper held at a wall in flight (docs/model_separation.md "Held at a wall in flight"): a
// flying damper whose spring pushes it into a MemberEnd::Wall bounces there with falling speeds
// and is then held (X at the end, V = 0, the wall taking the push along the member) while its
// normal coordinate keeps flying; it lands on the member at the wall. Without the hold such
// sequences (the blade example at 0.5-1.3 N with --restitution 0.5 --ends wall) end with a Zeno
// stop.
//
// References (closed forms, not the model's code): a damper of mass m on the straight
// cantilever, whose bending mode has psi_u = 0 everywhere and psi_w = 0 at the root, with the
// member at rest: in flight its tangential motion m x'' = -k x is a lone oscillator hitting a
// stop at x_w (as in wall_rest_test.cpp): impact speeds v0 e^j, times t1 + sum (2/w) atan(v/(w x_w));
// its normal motion y_d = -h + a t^2 / 2 (a = N0/m) until it lands at the wall, where the member
// does not move, at t = sqrt(2 h / a). The hold comes at the first impact at or below the landing
// speed or whose rebound e v would turn within the wall band 1e-8 L: (e v)^2 <= 2 (k x_w / m) 1e-8 L.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace wall_hold_test {

using namespace model_test;

struct Samples : NullObserver {
  struct Sample {
    double t;
    DamperStates mode;
    System::State x;
  };
  std::vector<Sample> samples;
  bool on_sample(double t, const System::State& x, const DamperStates& mode) {
    samples.push_back({t, mode, x});
    return true;
  }
};

// m = 0.02 kg, k = 100 N/m (w = 70.7 rad/s), spring stretched x0 = 10 mm at X0 = 5 mm (the wall
// at x_w = 5 mm pushes back k x_w = 0.5 N), wall restitution 1/2; N0 = 0.1 N (a = 5 m/s^2) from a
// height h = 5 cm: the bounces end in the hold at ~0.08 s, the landing comes at 0.141 s (plastic:
// e = 0), and the damper then rests stuck at the wall (its spring's push 0.5 N beyond the
// friction bound mu_s N0 = 0.03 N).
struct HeldScene {
  static constexpr double m = 0.02, k = 100.0, N0 = 0.1, e = 0.5, X0 = 0.005, x0 = 0.01, x_w = x0 - X0,
                          h = 0.05, mu = 0.3, a = N0 / m, t_end = 0.2;
  Cantilever c;
  PointDamper<double> d;
  System sys;
  System::State x;
  DamperStates mode{1, ContactState::Separated};
  RunOptions<double> run = closed_form_run_options(1e-3);

  static PointDamper<double> make_damper(const Cantilever& beam) {
    PointDamper<double> p(beam.member, X0, m, k, N0, CoulombLaw<double>(mu, mu));
    p.separation = Separation::Separate;
    p.restitution = 0.0;
    p.start_end = MemberEnd::Wall;
    p.finish_end = MemberEnd::Wall;
    p.wall_restitution = e;
    return p;
  }
  HeldScene() : d(make_damper(c)), sys(c.frame, c.basis, {d}), x(sys.initial_state()) {
    x[sys.x_offset()] = x0;
    x[sys.flight_offset()] = -h;  // gap = psi_w(X)^T q - y_d = h with the member at rest
    run.stepper.max_step = 1e-4;
  }

  // The wall impacts: speeds v0 e^j at t1 + sum of the flights; the holding impact K is the first
  // at or below the landing speed or whose rebound turns within the band.
  double w() const { return std::sqrt(k / m); }
  double v0() const { return w() * std::sqrt(x0 * x0 - x_w * x_w); }
  double band() const { return 1e-8 * c.length; }
  double flight(double v) const { return 2.0 / w() * std::atan(v / (w() * x_w)); }
  int holding_impact() const {
    int K = 0;
    while (v0() * std::pow(e, K) > d.landing_speed && std::pow(e * v0() * std::pow(e, K), 2) > 2 * (k * x_w / m) * band())
      ++K;
    return K;
  }
  double impact_time(int j) const {
    double t = std::acos(x_w / x0) / w();
    for (int i = 1; i <= j; ++i) t += flight(v0() * std::pow(e, i));
    return t;
  }
};

TEST(WallHold, AFlyingDamperPushedIntoAWallIsHeldThereUntilItLands) {
  HeldScene scene;
  System& sys = scene.sys;
  System::State x = scene.x;
  DamperStates mode = scene.mode;
  const double m = scene.m, k = scene.k, N0 = scene.N0, e = scene.e, x0 = scene.x0, x_w = scene.x_w, h = scene.h, mu = scene.mu, a = scene.a;
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(mode, 0.0, x);
  Samples obs;
  const auto r = simulate(sys, mode, 0.0, x, scene.t_end, scene.run, obs);
  ASSERT_TRUE(r.ok()) << r.message;

  // The wall impacts: speeds v0 e^j at t1 + sum of the flights. Each impact is located up to
  // z = 1e-12 m (the guard zero tolerance) beyond the last, which adds at most 2 (k x_w / m) z to
  // v^2 per impact: |dv| <= (j + 1) (k x_w / m) z / v_j, plus 1e-8 for the event tolerances.
  const double v0 = scene.v0(), band = scene.band();
  const int K = scene.holding_impact();
  ASSERT_EQ(K, 10);  // rebound 2.99e-4 m/s against the band's 3.16e-4 m/s (5 %); the 9th: 6e-4 m/s
  const auto& hits = sys.impacts();
  ASSERT_EQ(static_cast<int>(hits.size()), K + 2);  // K + 1 at the wall, then the landing
  for (int j = 0; j <= K; ++j) {
    const double v = v0 * std::pow(e, j), t_j = scene.impact_time(j);
    const auto& hit = hits[static_cast<std::size_t>(j)];
    EXPECT_TRUE(hit.wall) << "impact " << j;
    EXPECT_EQ(hit.to, ContactState::Separated) << "impact " << j;
    const double v_tol = (j + 1) * (k * x_w / m) * 1e-12 / v + 1e-8;
    EXPECT_NEAR(hit.sliding_velocity, -v, v_tol) << "impact " << j;
    EXPECT_NEAR(hit.t, t_j, 1e-8) << "impact " << j;
    EXPECT_NEAR(hit.sliding_velocity_after, j < K ? e * v : 0.0, v_tol) << "impact " << j;
  }
  const double t_hold = scene.impact_time(K), t_land = std::sqrt(2 * h / a);
  ASSERT_LT(t_hold, t_land - 0.01);
  // The landing at the wall: a plastic normal impact at sqrt(2 a h), no sliding (V = 0 before).
  const auto& land = hits.back();
  EXPECT_FALSE(land.wall);
  EXPECT_NEAR(land.t, t_land, 1e-8);
  EXPECT_NEAR(land.normal_velocity, -std::sqrt(2 * a * h), 1e-8);
  EXPECT_EQ(land.sliding_velocity, 0.0);

  // While held: X at the wall exactly, V = 0, no friction in flight, the wall's reaction the
  // spring's push k x (x within the band of x_w: the hold came at the impact, x = X + x_w), the
  // normal coordinate on its parabola (1e-9 m: the run's tolerance on 5 cm).
  int held = 0;
  for (const auto& sample : obs.samples) {
    if (sample.t <= t_hold + 1e-6 || sample.t >= t_land - 1e-6) continue;
    ++held;
    EXPECT_EQ(sample.mode.to_string(), "separated@start") << "t = " << sample.t;
    EXPECT_EQ(sample.x[sys.contact_offset()], 0.0);
    const auto& ev = sys.evaluate(sample.mode, sample.t, sample.x);
    EXPECT_EQ(ev.V[0], 0.0);
    EXPECT_EQ(ev.f[0], 0.0);
    EXPECT_NEAR(ev.wall_force[0], k * x_w, k * (band + 1e-9)) << "t = " << sample.t;
    EXPECT_NEAR(sample.x[sys.flight_offset()], -h + 0.5 * a * sample.t * sample.t, 1e-9) << "t = " << sample.t;
  }
  EXPECT_GT(held, 40);
  // Landed at the wall and pushed into it: stuck there, friction at its bound mu N0, the wall the rest.
  EXPECT_EQ(r.mode.to_string(), "stick@start");
  const auto& ev = sys.evaluate(r.mode, r.t, r.x);
  EXPECT_NEAR(ev.f[0], mu * N0, 1e-12);
  EXPECT_NEAR(ev.wall_force[0], k * r.x[sys.x_offset()] - mu * N0, 1e-9);
  // The audit closes: the wall does no work while it holds (V = 0); the losses of the bounces and
  // of the plastic landing are booked (residual: the run's tolerance on 0.5 k x0^2 + N0 h = 1e-2 J,
  // bound 1e-8 of it).
  const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
  EXPECT_NEAR(bal.residual, 0.0, 1e-8 * (0.5 * k * x0 * x0 + N0 * h));
}

// DamperStatistics over the run of the test above: K + 1 = 11 wall impacts, one rest at the wall
// (from the hold on: held in flight, then stuck there), resting time t_end - t_hold, separated
// time t_land (closed forms of the scene), one landing, no bounce on the member; a window that
// starts after the hold sees the rest time only (no impact, no new rest).
TEST(WallHold, DamperStatisticsCountTheWallImpactsAndTheRest) {
  HeldScene s;
  ASSERT_TRUE(s.sys.make_consistent(s.mode, 0.0, s.x));
  const int K = s.holding_impact();
  const double t_hold = s.impact_time(K), t_land = std::sqrt(2 * s.h / s.a), t_late = 0.5 * (t_hold + t_land);
  const double period = 0.05;
  DamperStatistics<System> all(s.sys, s.mode, 0.0, s.x, {0.0, s.t_end, period});
  DamperStatistics<System> late(s.sys, s.mode, 0.0, s.x, {t_late, s.t_end, period});
  struct Both : NullObserver {
    DamperStatistics<System>& a;
    DamperStatistics<System>& b;
    Both(DamperStatistics<System>& a_, DamperStatistics<System>& b_) : a(a_), b(b_) {}
    bool on_step(double t, const System::State& x, const DamperStates& mode) {
      return a.on_step(t, x, mode) && b.on_step(t, x, mode);
    }
    void on_event(const EventRecord<double, DamperStates>& r, const System::State& x) {
      a.on_event(r, x);
      b.on_event(r, x);
    }
  } obs(all, late);
  const auto r = simulate(s.sys, s.mode, 0.0, s.x, s.t_end, s.run, obs);
  ASSERT_TRUE(r.ok()) << r.message;
  // Times: the events are located to ~1e-12 s; 1e-8 s covers the impact times' own tolerance above.
  const auto st = all.statistics(0);
  EXPECT_EQ(st.wall_impacts, K + 1);
  EXPECT_EQ(st.wall_rests, 1);
  EXPECT_NEAR(st.wall_time, s.t_end - t_hold, 1e-8);
  EXPECT_NEAR(st.separated_time, t_land, 1e-8);
  EXPECT_EQ(st.bounces, 0);
  EXPECT_EQ(st.landings, 1);
  const auto sl = late.statistics(0);
  EXPECT_EQ(sl.wall_impacts, 0);
  EXPECT_EQ(sl.wall_rests, 0);
  EXPECT_NEAR(sl.wall_time, s.t_end - t_late, 1e-8);
  EXPECT_EQ(sl.landings, 1);
}

// The hold lasts while the wall pushes: a damper marked as held in flight whose spring pulls it
// away from the wall (x < 0 at the start wall: the force -k x points along +u) is released at
// once (make_consistent), and one pushed into it (x > 0) stays held, with the reaction k x.
TEST(WallHold, TheHoldEndsWhenTheForcePullsAway) {
  const Cantilever c;
  const double m = 0.02, k = 100.0, N0 = 0.1;
  PointDamper<double> d(c.member, 0.0, m, k, N0, CoulombLaw<double>(0.3, 0.3));
  d.separation = Separation::Separate;
  d.start_end = MemberEnd::Wall;
  System sys(c.frame, c.basis, {d});
  for (const double xs : {-1e-3, 1e-3}) {
    System::State x = sys.initial_state();
    x[sys.x_offset()] = xs;
    x[sys.flight_offset()] = -1e-3;
    DamperStates mode(1, ContactState::Separated);
    mode.set_wall(0, WallRest::Start);
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
    EXPECT_EQ(mode.wall(0), xs > 0 ? WallRest::Start : WallRest::None) << "x = " << xs;
    if (xs > 0) {
      EXPECT_NEAR(sys.evaluate(mode, 0.0, x).wall_force[0], k * xs, 1e-12);
    }
  }
}


// An elastic wall (e = 1) does not hold a flying damper: pushed into the start wall by its
// spring (constant-ish push a = k x_w / m = 25 m/s^2), it strikes at v = 2 mm/s, above the hold
// band's rebound speed sqrt(2 a 1e-8 L) = 3.2e-4 m/s, and bounces at the same speed forever with
// period T = (2/w) atan(v / (w x_w)) = 1.6e-4 s, shorter than the integrator's steps in this slow
// flight: the whole excursion off the wall (apex v^2 / (2 a) = 8e-8 m, far beyond the guard zero
// tolerance 1e-12 m) lies inside one step. Each bounce is a new crossing of an armed guard, not
// an immediate event (the Zeno guard would end the run after 101 of those, at t = 0.016 s), and
// with no accumulation point the run reaches t_end. The damper lands at 0.14 s, after t_end.
TEST(WallHold, AnElasticWallKeepsAFlyingDamperBouncingToTheEndOfTheRun) {
  const Cantilever c;
  const double m = 0.02, k = 100.0, N0 = 0.1, x_w = 0.005, v = 2e-3, h = 0.05, t_end = 0.1;
  const double w = std::sqrt(k / m), x0 = std::sqrt(x_w * x_w + (v / w) * (v / w));
  // Both steppers: HybridStepper (Dormand-Prince) and ExactLinearStepper (the exponential
  // method; its step in this flight is the guard sampling step of the mode, which also holds
  // whole bounces).
  for (const Integrator method : {Integrator::DormandPrince54, Integrator::Exponential}) {
    SCOPED_TRACE(to_string(method));
    PointDamper<double> d(c.member, x0 - x_w, m, k, N0, CoulombLaw<double>(0.3, 0.3));
    d.separation = Separation::Separate;
    d.restitution = 0.0;
    d.start_end = MemberEnd::Wall;
    d.finish_end = MemberEnd::Wall;
    d.wall_restitution = 1.0;
    System sys(c.frame, c.basis, {d});
    System::State x = sys.initial_state();
    x[sys.x_offset()] = x0;
    x[sys.flight_offset()] = -h;
    DamperStates mode{1, ContactState::Separated};
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
    const double E0 = sys.mechanical_energy(mode, 0.0, x);
    auto run = closed_form_run_options(1e-3);
    run.integrator = method;
    NullObserver obs;
    const auto r = simulate(sys, mode, 0.0, x, t_end, run, obs);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.t, t_end);
    EXPECT_EQ(r.mode.to_string(), "separated");

    // Closed forms: first impact at t1 = acos(x_w / x0) / w, then one every T, all at speed v.
    const double t1 = std::acos(x_w / x0) / w, T = 2.0 / w * std::atan(v / (w * x_w));
    const auto& hits = sys.impacts();
    const double expected = std::floor((t_end - t1) / T) + 1;
    EXPECT_NEAR(static_cast<double>(hits.size()), expected, 1.0);  // t_end may fall on an impact
    double worst = 0.0;
    for (const auto& hit : hits) {
      EXPECT_TRUE(hit.wall);
      worst = std::max(worst, std::abs(std::abs(hit.sliding_velocity) - v));
    }
    EXPECT_LT(worst, 1e-6 * v) << "largest deviation of an impact speed from v";
    // The audit closes: the elastic wall does no work; residual relative to the energy in play
    // 0.5 k x0^2 + N0 h, bounded by 1e-6 (the run's tolerance 1e-10 over ~1000 steps and 600
    // impacts).
    const auto bal = sys.energy_balance(r.mode, r.t, r.x, E0);
    EXPECT_LT(std::abs(bal.residual), 1e-6 * (0.5 * k * x0 * x0 + N0 * h));
  }
}

}  // namespace wall_hold_test

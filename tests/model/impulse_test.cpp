// ContactSystem's impacts with Coulomb friction on the impulse and its landing rule, against
// references that do not come from the system: the post-impact velocities of a point mass and
// of a rod hitting ground obliquely by hand (Newton's restitution, Coulomb's law for impulses,
// the rod's inverse effective mass assembled by hand from its point kinematics), the kinetic
// energy lost by hand, the energy of every impact of a sweep of angles, the audit of a run with
// impacts, the frictionless impact's invariants, the geometric series of a bouncing body's
// impact times, and the shaken wedge scene run through its grazing landings.

#include "model/contact_samples.hpp"
#include "model/wedge_scene.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace impulse_test {

using namespace stickslip;
using Vec2 = Eigen::Vector2d;
using System = ContactSystem<double, BodyContact<double>>;
using Mixed = ContactSystem<double, AnyContact<double>>;
using State = System::State;
using contact_samples::Samples;
using contact_samples::tight;
using wedge_scene::Ground;
using wedge_scene::kPi;
using wedge_scene::kPlatform;
using wedge_scene::Platforms;
using wedge_scene::static_state;
using wedge_scene::Wedge;

/// A body of mass m and inertia J whose point r (body coordinates) starts at gap g0 above
/// ground (normal +y) with velocity (u, w) of the centre of mass and rotation rate omega; an
/// optional constant load -P along y.
struct Drop {
  double m = 0.2, J = 1e-4, e = 0.5, mu = 0.3, g0 = 1e-4, P = 0;
  Vec2 r = Vec2::Zero();
  double u = 0, w = -1, omega = 0;
  System::Options options;
  System make(const Ground& g) const {
    RigidBody<double> body;
    body.mass = m;
    body.inertia = J;
    if (P != 0) body.loads.push_back({PlaneDirection<double>::global_y(), -P, {}});
    auto c = BodyContact<double>::on_ground({0, r}, PlaneDirection<double>::global_y(), CoulombLaw<double>(mu, mu), e);
    c.initial_gap = g0;
    c.initial_state = ContactState::Separated;
    return System(g.frame, g.basis, {body}, {c}, {}, options);
  }
  State start(const System& sys) const {
    State x = sys.initial_state();
    const Eigen::Index v = sys.num_coordinates() + sys.body_offset(0);
    x[v] = u;
    x[v + 1] = w;
    x[v + 2] = omega;
    return x;
  }
};

/// Index of V_x in the state (one mode, one body: z = (q, x, y, theta), then z').
constexpr Eigen::Index kVx = 5;

/// Kinetic energy of the body's velocities (V_x, V_y, omega) in x.
double kinetic(const Drop& d, const State& x) {
  return 0.5 * d.m * (x[kVx] * x[kVx] + x[kVx + 1] * x[kVx + 1]) + 0.5 * d.J * x[kVx + 2] * x[kVx + 2];
}

/// Runs a drop without load through its first impact (a free flight: landing at g0 / |v_n|)
/// and a short free flight after it.
struct Hit {
  State before, after;
  ContactState mode_after = ContactState::Stick;
  std::size_t impacts = 0;
  double t_impact = 0;
  double friction_dissipation = 0, residual = 0;
  Status status = Status::Success;
};
Hit hit(const Drop& d) {
  const Ground g;
  System sys = d.make(g);
  Hit h;
  h.before = d.start(sys);
  auto mode = sys.requested_mode();
  if (!sys.make_consistent(mode, 0.0, h.before)) ADD_FAILURE() << "make_consistent";
  // The contact point's approach speed (rotation moves it too: v_n = w + omega r_x).
  const double vn = d.w + d.omega * d.r.x();
  const double t_land = d.g0 / -vn;
  auto result = simulate(sys, mode, 0.0, h.before, 1.01 * t_land, tight(0));
  h.status = result.status;
  h.after = result.x;
  h.mode_after = result.mode[0];
  h.impacts = sys.events().size();
  h.t_impact = h.impacts > 0 ? sys.events()[0].t : -1;
  const auto b = sys.energy_balance(result.x, sys.mechanical_energy(h.before));
  h.friction_dissipation = b.friction_dissipation;
  h.residual = b.residual;
  return h;
}

// A point mass (contact at the centre of mass) hits ground at (v_t, v_n), v_n < 0. By hand
// (Newton, Coulomb for impulses, W = I / m): P_n = m (1 + e) |v_n|; sticking needs
// m |v_t| <= mu P_n, i.e. |v_t| <= mu (1 + e) |v_n|, and leaves v_t+ = 0; otherwise the slide
// changes v_t by mu (1 + e) |v_n| against it. v_n+ = e |v_n| either way. The kinetic energy lost
// is m (v_t^2 - v_t+^2 + (1 - e^2) v_n^2) / 2, booked as friction dissipation.
TEST(ImpactFriction, PointMassSticksOrSlidesAsTheClosedForm) {
  for (double e : {0.0, 0.5, 1.0}) {
    for (double u : {0.1, -0.1, 0.5, -2.0}) {  // |v_t| below and above mu (1 + e) |v_n| = 0.3 (1 + e)
      Drop d;
      d.e = e;
      d.u = u;
      const Hit h = hit(d);
      ASSERT_EQ(h.status, Status::Success);
      const double vn = -d.w, slide = d.mu * (1 + e) * vn;
      const bool sticks = std::abs(u) <= slide;
      const double vt_after = sticks ? 0.0 : u - std::copysign(slide, u);
      const std::string where = "e " + std::to_string(e) + " u " + std::to_string(u);
      // The impact's velocities by one small solve: round-off (1e-15 of 1 m/s).
      EXPECT_NEAR(h.after[kVx], vt_after, 1e-12) << where;
      EXPECT_NEAR(h.after[kVx + 1], e * vn, 1e-12) << where;
      EXPECT_NEAR(h.after[kVx + 2], 0.0, 1e-12) << where;  // through the centre of mass: no turn
      const double lost = 0.5 * d.m * (u * u - vt_after * vt_after + (1 - e * e) * vn * vn);
      EXPECT_NEAR(h.friction_dissipation, lost, 1e-12 * (1 + lost)) << where;
      // Landed (e = 0): stuck when it stuck through the impact, else sliding along v_t+ (no
      // normal load after it: it slides on unloaded); bounced: open.
      if (e > 0) EXPECT_EQ(h.mode_after, ContactState::Separated) << where;
      else if (sticks) EXPECT_EQ(h.mode_after, ContactState::Stick) << where;
      else EXPECT_EQ(h.mode_after, vt_after > 0 ? ContactState::SlipPositive : ContactState::SlipNegative) << where;
    }
  }
}

/// The rod's velocities (V_x, V_y, omega) after the impact by hand, its contact point r turned
/// to R r = R(theta) r at the impact. The point's velocity rows over (V_x, V_y, omega) are
/// n -> [0, 1, (R r)_x] and t -> [1, 0, -(R r)_y] (t = (n_y, -n_x) = (1, 0)), so
/// W = rows M^-1 rows^T with M = diag(m, m, J). The stick impulse
/// P = W^-1 ((1 + e) |v_n|, -v_t) if P_n >= 0 and |P_t| <= mu P_n, else the slide along
/// s = sgn v_t (or -sgn v_t when v_t would reverse: the slide needs s v_t+ >= 0),
/// P_t = -s mu P_n, P_n = (1 + e) |v_n| / (W_nn - s mu W_nt).
Eigen::Vector3d rod_after(const Drop& d, double theta, bool& sticks) {
  const Vec2 r(std::cos(theta) * d.r.x() - std::sin(theta) * d.r.y(),
               std::sin(theta) * d.r.x() + std::cos(theta) * d.r.y());
  Eigen::Matrix<double, 2, 3> rows;
  rows << 0, 1, r.x(), 1, 0, -r.y();
  const Eigen::Vector3d minv(1 / d.m, 1 / d.m, 1 / d.J);
  const Eigen::Matrix2d W = rows * minv.asDiagonal() * rows.transpose();
  const Eigen::Vector3d V(d.u, d.w, d.omega);
  const double vn = d.w + d.omega * r.x(), vt = d.u - d.omega * r.y();
  Eigen::Vector2d P = W.inverse() * Eigen::Vector2d(-(1 + d.e) * vn, -vt);
  sticks = P[0] >= 0 && std::abs(P[1]) <= d.mu * P[0];
  if (!sticks) {  // slip along sgn v_t, or against it when the sliding velocity would reverse
    for (double s : {vt > 0 ? 1.0 : -1.0, vt > 0 ? -1.0 : 1.0}) {
      const double Pn = -(1 + d.e) * vn / (W(0, 0) - s * d.mu * W(0, 1));
      P = Eigen::Vector2d(Pn, -s * d.mu * Pn);
      if (Pn >= 0 && s * (vt + W(1, 0) * P[0] + W(1, 1) * P[1]) >= 0) break;
    }
  }
  // Generalised impulse on (x, y, theta): P_n [0, 1, r_x] + P_t [1, 0, -r_y].
  const Eigen::Vector3d Q(P[1], P[0], P[0] * r.x() - P[1] * r.y());
  return V + Eigen::Vector3d(Q[0] / d.m, Q[1] / d.m, Q[2] / d.J);
}

// A rod (length 0.1 m, m = 0.2 kg, J = m L^2 / 12) tilted so that its lower end, off the centre
// of mass by r = (L/2)(cos phi, -sin phi), hits ground: the tangential and normal directions are
// coupled through the rotation (W_nt != 0). Its velocities after the impact against the closed
// form above, for sticking and sliding impacts, and the loss booked.
TEST(ImpactFriction, RodWithRotationSticksOrSlidesAsTheClosedForm) {
  int stuck = 0, slid = 0;
  for (double phi : {0.3, 0.8, 1.2}) {
    for (double u : {0.05, -0.4, 1.5}) {
      Drop d;
      d.J = d.m * 0.1 * 0.1 / 12;
      d.r = 0.05 * Vec2(std::cos(phi), -std::sin(phi));
      d.u = u;
      d.omega = 2.0;
      const Hit h = hit(d);
      ASSERT_EQ(h.status, Status::Success);
      ASSERT_EQ(h.impacts, 1u);
      bool sticks = false;
      const Eigen::Vector3d ref = rod_after(d, d.omega * h.t_impact, sticks);  // free flight: theta = omega t
      (sticks ? stuck : slid) += 1;
      const std::string where = "phi " + std::to_string(phi) + " u " + std::to_string(u);
      // One small solve: round-off, ~1e-15 of the velocities (1 m/s, 20 rad/s rates).
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(h.after[kVx + k], ref[k], 1e-11) << where << " k " << k;
      const double lost = kinetic(d, h.before) - 0.5 * d.m * (ref[0] * ref[0] + ref[1] * ref[1]) -
                          0.5 * d.J * ref[2] * ref[2];
      EXPECT_NEAR(h.friction_dissipation, lost, 1e-12 + 1e-10 * std::abs(lost)) << where;
    }
  }
  EXPECT_GT(stuck, 0);  // both cases are met
  EXPECT_GT(slid, 0);
}

// No impact creates energy: the kinetic energy after an impact is at most the energy before,
// for a point mass and a rod (the rod with e <= 0.5: Newton's kinematic restitution with the
// directions coupled may create energy at e near 1, Stronge, Impact Mechanics, ch. 4), over a
// sweep of approach angles and rod tilts.
TEST(ImpactFriction, NoImpactGainsEnergyOverASweepOfAngles) {
  int count = 0;
  for (double e : {0.0, 0.25, 0.5, 1.0}) {
    for (int k = 1; k < 18; ++k) {
      const double angle = k * kPi / 36;  // the approach velocity's angle to the ground, 5..85 deg
      for (double phi : {-1.0, 0.0, 0.4, 1.1}) {
        const bool rod = phi != -1.0;
        if (rod && e > 0.5) continue;
        Drop d;
        d.e = e;
        d.u = std::cos(angle);
        d.w = -std::sin(angle);
        if (rod) {
          d.J = d.m * 0.1 * 0.1 / 12;
          d.r = 0.05 * Vec2(std::cos(phi), -std::sin(phi));
          d.omega = -1.0;
        }
        const Hit h = hit(d);
        ASSERT_EQ(h.status, Status::Success);
        const double before = kinetic(d, h.before), after = kinetic(d, h.after);
        EXPECT_LE(after, before * (1 + 1e-14)) << "e " << e << " angle " << angle << " phi " << phi;
        // The audit books the loss (the flight carries no other energy).
        EXPECT_NEAR(h.friction_dissipation, before - after, 1e-13 * before);
        ++count;
      }
    }
  }
  EXPECT_GT(count, 100);
}

// With mu = 0 the impact is the frictionless one: the tangential velocity of a point mass keeps
// its value exactly (the normal impulse acts along n only), the normal velocity turns to
// -e v_n at the closed-form impact times of a flight under a constant load, and the audit books
// the normal loss (1 - e^2) m v_n^2 / 2 per impact only.
TEST(ImpactFriction, FrictionlessImpactKeepsTheTangentialVelocity) {
  Drop d;
  d.mu = 0;
  d.u = 0.7;
  d.w = 0;
  d.P = 4;
  d.g0 = 1e-3;
  d.options.landing_height = 0;  // every bounce a bounce
  const Ground g;
  System sys = d.make(g);
  State x = d.start(sys);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double a = d.P / d.m, t1 = std::sqrt(2 * d.g0 / a), t2 = t1 + 2 * d.e * t1;
  const double E0 = sys.mechanical_energy(x);
  auto result = simulate(sys, mode, 0.0, x, 0.5 * (t2 + t2 + 2 * d.e * d.e * t1), tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  ASSERT_EQ(sys.events().size(), 2u);
  EXPECT_NEAR(sys.events()[0].t, t1, 1e-9);  // events located to ~1e-12 s on a parabola
  EXPECT_NEAR(sys.events()[1].t, t2, 1e-9);
  EXPECT_EQ(result.x[kVx], d.u);           // V_x untouched, to the bit
  const double lost = 0.5 * d.m * (1 - d.e * d.e) * (a * t1 * a * t1) * (1 + d.e * d.e);
  const auto b = sys.energy_balance(result.x, E0);
  EXPECT_NEAR(b.friction_dissipation, lost, 1e-8 * lost);
  EXPECT_LE(b.relative_residual(), 1e-8);
}

// A rod dropped tilted with a sideways velocity under a constant load bounces on its end
// (e = 0.5) with friction on every impulse, lands by the landing rule and slides and turns on its
// end; the energy audit closes over the run, with every impact's normal and frictional loss booked.
TEST(ImpactFriction, RunWithFrictionalImpactsClosesTheEnergyAudit) {
  Drop d;
  d.J = d.m * 0.1 * 0.1 / 12;
  d.r = 0.05 * Vec2(std::cos(0.7), -std::sin(0.7));
  d.u = 0.3;
  d.w = -0.2;
  d.P = 4;
  d.g0 = 1e-3;
  const Ground g;
  System sys = d.make(g);
  State x = d.start(sys);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(x);
  auto result = simulate(sys, mode, 0.0, x, 0.1, tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  int bounces = 0;
  for (const auto& ev : sys.events()) bounces += ev.from == ContactState::Separated ? 1 : 0;
  EXPECT_GE(bounces, 3);
  const auto b = sys.energy_balance(result.x, E0);
  EXPECT_GT(b.friction_dissipation, 0.0);
  // rtol 1e-10: the audit integrals carry the integration error; impacts are booked exactly.
  EXPECT_LE(b.relative_residual(), 1e-8) << b.residual << " of " << b.scale;
}

// A body pressed onto ground by P (a = P / m) from a gap g0 lands at t1 = sqrt(2 g0 / a) with
// |v_n| = a t1; impact k (k = 1, 2, ...) comes at |v_n| = e^(k-1) a t1 and its rebound flies
// 2 e^k t1, so the bounces end at t_rest = t1 + sum_k>=1 2 e^k t1 = t1 (1 + e) / (1 - e) after
// infinitely many impacts. Rebound k rises (e^k a t1)^2 / (2 a) = e^2k g0; the landing rule lands
// impact K, the first with e^2K g0 <= landing_height: K impacts, rest at
// t_K = t_rest - 2 e^K t1 / (1 - e), the body at rest on ground afterwards (stuck, N = P), no
// Zeno stop.
TEST(LandingRule, BouncingBodyComesToRestAsTheGeometricSeries) {
  Drop d;
  d.w = 0;
  d.P = 4;
  d.g0 = 1e-3;
  d.e = 0.5;
  d.options.landing_height = 2e-9;  // K = 10: e^20 g0 = 0.95e-9, e^18 g0 = 3.8e-9
  const Ground g;
  System sys = d.make(g);
  State x = d.start(sys);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double a = d.P / d.m, t1 = std::sqrt(2 * d.g0 / a), t_rest = t1 * (1 + d.e) / (1 - d.e);
  int K = 1;
  while (std::pow(d.e, 2 * K) * d.g0 > d.options.landing_height) ++K;
  const double t_K = t_rest - 2 * std::pow(d.e, K) * t1 / (1 - d.e);
  auto result = simulate(sys, mode, 0.0, x, 2 * t_rest, tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  const auto& ev = sys.events();
  ASSERT_EQ(ev.size(), static_cast<std::size_t>(K));  // K - 1 bounces and the landing
  EXPECT_EQ(ev.back().to, ContactState::Stick);
  // Each impact time is a partial sum located to ~1e-12 s; 1e-9 s leaves round-off of K sums.
  EXPECT_NEAR(ev.back().t, t_K, 1e-9);
  EXPECT_EQ(result.mode[0], ContactState::Stick);
  EXPECT_NEAR(sys.evaluate(result.mode, result.t, result.x).N[0], d.P, 1e-9 * d.P);
  const auto b = sys.energy_balance(result.x, 0.0);
  EXPECT_LE(b.relative_residual(), 1e-8);
  // The default landing height (1e-8 of the frame's size, 1e-9 m here) ends the bounces too,
  // at the impact the same series predicts.
  Drop by_default = d;
  by_default.options = System::Options{};
  System sys2 = by_default.make(g);
  State x2 = by_default.start(sys2);
  auto mode2 = sys2.requested_mode();
  ASSERT_TRUE(sys2.make_consistent(mode2, 0.0, x2));
  EXPECT_NEAR(sys2.landing_height(), 1e-9, 1e-24);  // the frame spans 0.1 m
  auto result2 = simulate(sys2, mode2, 0.0, x2, 2 * t_rest, tight(0));
  ASSERT_EQ(result2.status, Status::Success) << result2.message;
  EXPECT_EQ(result2.mode[0], ContactState::Stick);
  int K2 = 1;
  while (std::pow(d.e, 2 * K2) * d.g0 > sys2.landing_height()) ++K2;
  EXPECT_EQ(sys2.events().size(), static_cast<std::size_t>(K2));
  EXPECT_NEAR(sys2.events().back().t, t_rest - 2 * std::pow(d.e, K2) * t1 / (1 - d.e), 1e-9);
}

// The shaken wedge with a slider on the left platform (MixedContacts' scene) at 30 N: the
// platform throws the wedge off a face and it lands grazing and sliding. A face that lands
// while sliding closes slipping along its sliding velocity after the impact (a stuck face would
// have that velocity projected away and its landing repeat at one instant, up to the Zeno
// guard); the run goes through four periods and the energy audit closes.
TEST(LandingRule, ShakenWedgeRunsThroughItsGrazingLandings) {
  const Platforms p{8, 0.01};
  const Wedge w;
  WedgeFace<double> left{{p.tip_left()}, w.rl, w.al, 0.0}, right{{p.tip_right()}, w.rr, w.ar, 0.0};
  const auto wedge = wedge_damper<double>(0, w.mass, w.inertia, w.P, left, right, CoulombLaw<double>(0.25, 0.2));
  const double W = 0.6 * p.basis.omega()(0), T = 2 * kPi / W;
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(p.left, 0.125, LoadDirection::GlobalY, 30.0, W)};
  std::vector<AnyContact<double>> all(wedge.contacts.begin(), wedge.contacts.end());
  all.emplace_back(PointContact<double>::grounded({p.left, 0.0625}, PlaneDirection<double>::global_y(),
                                                  CoulombLaw<double>(0.35, 0.3), 20.0));
  Mixed sys(p.frame, p.basis, {wedge.body}, all, loads);
  auto x = static_state(sys, p, w);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  Samples rec;
  const auto result = simulate(sys, mode, 0.0, x, 4 * T, tight(T / 200), rec);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  int landings = 0;
  for (const auto& ev : sys.events()) landings += ev.from == ContactState::Separated ? 1 : 0;
  EXPECT_GE(landings, 1);
  const auto b = sys.energy_balance(result.x, sys.mechanical_energy(rec.x.front()));
  EXPECT_LE(b.relative_residual(), 1e-7) << b.residual << " of " << b.scale;
}

TEST(LandingRule, BadLandingHeightIsRefusedNamingTheParameter) {
  Drop d;
  d.options.landing_height = std::nan("");
  const Ground g;
  try {
    (void)d.make(g);
    FAIL() << "accepted a NaN landing height";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("landing_height"), std::string::npos) << ex.what();
  }
}

}  // namespace impulse_test

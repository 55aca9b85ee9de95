// ContactSystem with planar rigid bodies and unilateral body contacts (a wedge damper between two
// platforms), against references that do not come from the system: the wedge's statics by hand
// (force and moment balance with the face angles), the stuck system's frequencies from an
// independent eigen solve of the constrained linear system assembled by hand (the platforms'
// nodal rows, the body's point kinematics, the preload's rotational stiffness), the energy
// balance, a separating face checked by construction, and a bouncing body against the
// closed-form free flight with restitution.

#include "model/contact_samples.hpp"
#include "model/wedge_scene.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace body_contact_test {

using namespace stickslip;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using Vec2 = Eigen::Vector2d;
using System = ContactSystem<double, BodyContact<double>>;
using State = System::State;

using wedge_scene::Ground;
using wedge_scene::kPi;
using wedge_scene::kPlatform;
using wedge_scene::Platforms;
using wedge_scene::Wedge;
using wedge_scene::nodal_row;
using wedge_scene::static_deflection;
using wedge_scene::static_state;

using contact_samples::Samples;
using contact_samples::tight;

// The stuck wedge in static equilibrium: the platforms deflected by the hand normal forces, the
// damper at rest. The stuck solve is unique (its capacitance matrix is regular) and the hand
// forces (normal N_l, N_r, tangential 0) hold every coordinate at rest, so they are its result.
TEST(WedgeDamper, StaticNormalForcesFollowTheWedgesStatics) {
  const Platforms p(8);
  const Wedge w;
  const auto wedge = w.build(p);
  ASSERT_EQ(wedge.contacts.size(), 2u);
  EXPECT_NEAR(wedge.contacts[0].normal.x, w.nl.x(), 1e-15);  // the builder's face normals
  EXPECT_NEAR(wedge.contacts[1].normal.y, w.nr.y(), 1e-15);
  System sys(p.frame, p.basis, {wedge.body}, wedge.contacts);
  ASSERT_EQ(sys.num_coordinates(), 8 + 3);
  State x = static_state(sys, p, w);
  auto mode = sys.requested_mode();
  const auto& e = sys.evaluate(mode, 0.0, x);
  EXPECT_NEAR(e.gap[0], 0.0, 1e-15);  // closed where the platforms are
  EXPECT_NEAR(e.gap[1], 0.0, 1e-15);
  ASSERT_TRUE(e.finite);
  // Rounding in a solve of condition ~1e4 (modal and body entries): 1e-9 of the load.
  EXPECT_NEAR(e.N[0], w.Nl, 1e-9 * w.P);
  EXPECT_NEAR(e.N[1], w.Nr, 1e-9 * w.P);
  EXPECT_NEAR(e.f[0], 0.0, 1e-9 * w.P);
  EXPECT_NEAR(e.f[1], 0.0, 1e-9 * w.P);
  EXPECT_LE(e.qdd.tail(3).cwiseAbs().maxCoeff(), 1e-7 * w.P / w.mass);
  // With the right face's point elsewhere the normal forces alone leave a moment: the stuck
  // faces must hold it with tangential forces.
  Wedge tilted = w;
  tilted.rr = Vec2(2 * w.b, w.h);
  const auto wedge2 = tilted.build(p);
  System sys2(p.frame, p.basis, {wedge2.body}, wedge2.contacts);
  EXPECT_GT(std::abs(sys2.evaluate(mode, 0.0, x).f[0]), 1e-3 * w.P);
}

// Small oscillations of the stuck system about that equilibrium: the rates of the system's
// accelerations (central differences of evaluate()) against the constrained eigenproblem
// assembled by hand: M = diag(1, m, m, J), K = diag(omega^2, 0, 0, sum_k N_k n_k . r_k) (the
// preload's stiffness on theta: a force N n at R(theta) r has the moment N n . (k x R r), whose
// theta-derivative is -N n . r), four constraint rows g_k = [-d . Psi_tip, d, d . (k x r)].
TEST(WedgeDamper, StuckFrequenciesMatchTheConstrainedEigenSolve) {
  const Eigen::Index n = 8;
  const Platforms p(n);
  const Wedge w;
  const auto wedge = w.build(p);
  System sys(p.frame, p.basis, {wedge.body}, wedge.contacts);
  State x = static_state(sys, p, w);
  const auto mode = sys.requested_mode();
  const Eigen::Index m = n + 3;
  const std::vector<double> lam = wedge_scene::stuck_rates(sys, mode, x, m);
  const wedge_scene::HandSystem hand(p, w, 4);
  const Vector ref = hand.constrained_eigenvalues(4);
  ASSERT_EQ(ref.size(), m - 4);
  // The system's rates hold the 4 zero eigenvalues of the constrained directions, then the
  // m - 4 squared frequencies. Central differences of a solve linear in q and smooth in theta:
  // truncation ~ step^2 and rounding ~ 1e-16 |z''| / step ~ 1e-8 relative; 1e-6 leaves margin
  // and is far below the preload's rotational stiffness (about -1.4 N m/rad against the
  // platforms' ~1e2 N m/rad on theta through the contact arms).
  const double top = ref.maxCoeff();
  for (int k = 0; k < 4; ++k) EXPECT_LE(std::abs(lam[static_cast<std::size_t>(k)]), 1e-6 * top) << k;
  for (Eigen::Index k = 0; k < m - 4; ++k)
    EXPECT_NEAR(lam[static_cast<std::size_t>(k + 4)], ref(k), 1e-6 * ref(k)) << k;
}

// The wedge, stuck in its static equilibrium, with the left platform shaken vertically: the
// damper sticks, slips, turns, lifts off a face and lands again (plastic impacts); the energy
// audit closes, the impacts' losses booked in it.
TEST(WedgeDamper, StickSlipRunWithRotationClosesTheEnergyBalance) {
  const Eigen::Index n = 8;
  const Platforms p(n, 0.01);
  const Wedge w;
  WedgeFace<double> left{{p.tip_left()}, w.rl, w.al, 0.0}, right{{p.tip_right()}, w.rr, w.ar, 0.0};
  const auto wedge = wedge_damper<double>(0, w.mass, w.inertia, w.P, left, right, CoulombLaw<double>(0.25, 0.2));
  const double W = 0.6 * p.basis.omega()(0);
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(p.left, 0.125, LoadDirection::GlobalY, 30.0, W)};
  System sys(p.frame, p.basis, {wedge.body}, wedge.contacts, loads);
  State x = static_state(sys, p, w);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(x);
  Samples rec;
  const double T = 2 * kPi / W;
  auto result = simulate(sys, mode, 0.0, x, 4 * T, tight(T / 200), rec);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  EXPECT_GE(sys.events().size(), 4u);  // stick-slip: the faces switch repeatedly
  int landings = 0;
  for (const auto& ev : sys.events()) landings += ev.from == ContactState::Separated ? 1 : 0;
  EXPECT_GE(landings, 1);
  double theta = 0;
  for (const auto& xs : rec.x) theta = std::max(theta, std::abs(xs[n + 2]));
  EXPECT_GT(theta, 1e-6);  // the damper turns (rad)
  const auto b = sys.energy_balance(result.x, E0);
  EXPECT_GT(b.friction_dissipation, 0.0);
  // rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work; stuck
  // projections are booked exactly.
  EXPECT_LE(b.relative_residual(), 1e-7) << b.residual << " of " << b.scale;
}

// A lateral load H(t) growing from 0 pushes the damper towards the right platform and unloads
// the left face until it opens (without friction at H = P tan a_r, by the statics; stuck faces
// carry part of H tangentially, so later). Both faces' normals pass through the centre of mass,
// the right face's point is the centre of mass. The right face slides once
// |P sin a_r - H cos a_r| > mu (P cos a_r + H sin a_r) (H = 1.5 P for mu = 0.2). By construction,
// after the left face opens its normal force is 0 and its gap grows while the right face slides.
TEST(WedgeDamper, OneFaceSeparatesWhileTheOtherSlides) {
  const Eigen::Index n = 8;
  const Platforms p(n, 0.02);
  Wedge w;
  w.rl = 0.01 * Vec2(-w.nl.x(), -w.nl.y());  // on the normal line through the centre of mass
  w.rr = Vec2::Zero();
  WedgeFace<double> left{{p.tip_left()}, w.rl, w.al, 0.0}, right{{p.tip_right()}, w.rr, w.ar, 0.0};
  auto wedge = wedge_damper<double>(0, w.mass, w.inertia, w.P, left, right, CoulombLaw<double>(0.2, 0.2));
  const double rate = 2e4;  // H' [N/s]: H reaches P tan a_r = 100 N at 5 ms, many platform periods
  BodyLoad<double> lateral;
  lateral.direction = PlaneDirection<double>::global_x();
  lateral.time_function = [rate](double t) { return rate * t; };
  wedge.body.loads.push_back(lateral);
  System sys(p.frame, p.basis, {wedge.body}, wedge.contacts);
  State x = static_state(sys, p, w);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  ASSERT_EQ(mode[0], ContactState::Stick);
  ASSERT_EQ(mode[1], ContactState::Stick);
  Samples rec;
  const double t_open = w.P * std::tan(w.ar) / rate;
  auto result = simulate(sys, mode, 0.0, x, 2.5 * t_open, tight(t_open / 100), rec);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  double opened = -1;
  for (const auto& ev : sys.events())
    if (ev.contact == 0 && ev.to == ContactState::Separated && opened < 0) opened = ev.t;
  ASSERT_GT(opened, 0.0);
  ASSERT_LT(opened, 2.0 * t_open);  // leaves the checks below a stretch of sliding
  EXPECT_EQ(result.mode[0], ContactState::Separated);
  EXPECT_TRUE(is_slipping(result.mode[1]));
  double last_gap = 0;
  int checked = 0;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    if (rec.t[k] < opened + 0.05 * t_open) continue;
    const auto& e = sys.evaluate(result.mode, rec.t[k], rec.x[k]);
    if (rec.t[k] > 2.0 * t_open) {  // sliding on the right face: the left one open, unloaded, its gap growing
      EXPECT_EQ(e.N[0], 0.0);
      EXPECT_GT(e.gap[0], last_gap);
      EXPECT_GT(e.N[1], 0.0);
      ++checked;
    }
    last_gap = e.gap[0];
  }
  EXPECT_GE(checked, 10);
  // Once the left face is open, every force on the body acts through its centre of mass: its
  // rotation rate stays what it was (to the integration error).
  double omega0 = 0;
  bool first = true;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    if (rec.t[k] < opened + 0.05 * t_open) continue;
    const double omega = rec.x[k][sys.num_coordinates() + n + 2];
    if (first) omega0 = omega;
    first = false;
    EXPECT_NEAR(omega, omega0, 1e-8 * (1 + std::abs(omega0)));
  }
  const auto b = sys.energy_balance(result.x, sys.mechanical_energy(rec.x.front()));
  EXPECT_LE(b.relative_residual(), 1e-7) << b.residual << " of " << b.scale;
}

// A body of 0.2 kg and 1e-4 kg m^2, without springs or loads.
RigidBody<double> small_body() {
  RigidBody<double> body;
  body.mass = 0.2;
  body.inertia = 1e-4;
  return body;
}

// A body released at a gap g0 above ground, pressed towards it by P: free flight with
// acceleration a = P / m lands at t1 = sqrt(2 g0 / a) with v = -a t1, leaves with e a t1 and
// lands again after 2 e t1; each impact removes (1 - e^2) m v^2 / 2, booked in the audit.
TEST(BodyContactLanding, BouncesWithRestitutionAsTheClosedFormFlight) {
  const Ground ground;  // a structure the body never touches
  RigidBody<double> body = small_body();
  const double P = 4.0, g0 = 1e-3, e = 0.5;
  body.loads.push_back({PlaneDirection<double>::global_y(), -P, {}});
  auto contact = BodyContact<double>::on_ground({0, Vec2::Zero()}, PlaneDirection<double>::global_y(),
                                                CoulombLaw<double>(0.3, 0.3), e);
  contact.initial_gap = g0;
  contact.initial_state = ContactState::Separated;
  System sys(ground.frame, ground.basis, {body}, {contact});
  State x = sys.initial_state();
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double a = P / body.mass, t1 = std::sqrt(2 * g0 / a), t2 = t1 + 2 * e * t1;
  auto result = simulate(sys, mode, 0.0, x, 0.5 * (t2 + t2 + 2 * e * e * t1), tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  ASSERT_GE(sys.events().size(), 2u);
  // Events located to ~1e-12 s on a parabola; 1e-9 s fails for a restitution off by 1e-6.
  EXPECT_NEAR(sys.events()[0].t, t1, 1e-9);
  EXPECT_NEAR(sys.events()[1].t, t2, 1e-9);
  const double v_out = e * e * a * t1;  // after the second impact
  EXPECT_NEAR(result.x[sys.num_coordinates() + sys.body_offset(0) + 1], v_out - a * (result.t - t2), 1e-8 * a * t1);
  const double lost = 0.5 * body.mass * (1 - e * e) * (a * t1 * a * t1 + e * a * t1 * e * a * t1);
  const auto b = sys.energy_balance(result.x, 0.0);
  EXPECT_NEAR(b.friction_dissipation, lost, 1e-8 * lost);
  EXPECT_LE(b.relative_residual(), 1e-8);
}

// A body pressed on ground by P and pushed sideways by F, held at its centre of mass by stuck
// contacts there. One contact (two unknowns: f, N): statics give N = P, f = -F and the body at
// rest. Two or three contacts at that one point have dependent constraint rows (2, 4 or 6
// unknowns, slipping or stuck): the split of the forces is undetermined and the evaluation
// reports it as not finite, with z'' all NaN.
TEST(BodyContactSolve, OnePointHoldsTheStaticsAndRepeatedPointsAreNotFinite) {
  const Ground ground;  // a structure the body never touches
  RigidBody<double> body = small_body();
  const double P = 4.0, F = 0.5;
  body.loads.push_back({PlaneDirection<double>::global_y(), -P, {}});
  body.loads.push_back({PlaneDirection<double>::global_x(), F, {}});
  const auto contact = BodyContact<double>::on_ground({0, Vec2::Zero()}, PlaneDirection<double>::global_y(),
                                                      CoulombLaw<double>(0.3, 0.3));
  {
    System sys(ground.frame, ground.basis, {body}, {contact});
    const auto& e = sys.evaluate(sys.requested_mode(), 0.0, sys.initial_state());
    ASSERT_TRUE(e.finite);
    // A 2 x 2 solve of entries 1 / m: rounding of a few ulps of the loads.
    EXPECT_NEAR(e.N[0], P, 1e-13 * P);
    EXPECT_NEAR(e.f[0], -F, 1e-13 * P);  // t = (n_y, -n_x) = global x
    EXPECT_LE(e.qdd.tail(3).cwiseAbs().maxCoeff(), 1e-13 * P / body.mass);
  }
  for (const std::size_t copies : {2u, 3u}) {
    System sys(ground.frame, ground.basis, {body}, std::vector<BodyContact<double>>(copies, contact));
    for (const ContactState s : {ContactState::Stick, ContactState::SlipPositive}) {
      auto mode = sys.requested_mode();
      for (Eigen::Index i = 0; i < sys.num_contacts(); ++i) mode[i] = s;
      const auto& e = sys.evaluate(mode, 0.0, sys.initial_state());
      EXPECT_FALSE(e.finite) << copies << " contacts, state " << static_cast<int>(s);
      EXPECT_TRUE(e.qdd.array().isNaN().all()) << copies << " contacts, state " << static_cast<int>(s);
    }
  }
}

TEST(BodyContactInputs, BadBodiesAndContactsAreRefusedNamingTheParameter) {
  const Platforms p(4);
  RigidBody<double> ok;
  ok.mass = 0.1;
  ok.inertia = 1e-5;
  const auto contact = BodyContact<double>::on_structure({0, Vec2(0.0, 0.01)}, p.tip_left(),
                                                         PlaneDirection<double>::global_y(), CoulombLaw<double>(0.3, 0.3));
  auto expect_refused = [&](const RigidBody<double>& body, const BodyContact<double>& c, const char* what) {
    try {
      System sys(p.frame, p.basis, {body}, {c});
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  EXPECT_NO_THROW(System(p.frame, p.basis, {ok}, {contact}));
  auto body = ok;
  body.mass = -1;
  expect_refused(body, contact, "mass");
  body = ok;
  body.inertia = 0;
  expect_refused(body, contact, "inertia");
  body = ok;
  body.springs.push_back({Vec2::Zero(), {0.0, 0.0}, 1e3, 0.0});
  expect_refused(body, contact, "direction");
  body = ok;
  body.springs.push_back({Vec2::Zero(), PlaneDirection<double>::global_x(), -1e3, 0.0});
  expect_refused(body, contact, "stiffness");
  body = ok;
  body.loads.push_back({{2.0, 0.0}, 1.0, {}});
  expect_refused(body, contact, "direction");
  auto c = contact;
  c.normal = {0.6, 0.6};
  expect_refused(ok, c, "normal");
  c = contact;
  c.a.body = 1;
  expect_refused(ok, c, "a.body");
  c = contact;
  c.restitution = 1.5;
  expect_refused(ok, c, "restitution");
  c = contact;
  c.initial_gap = 1e-3;
  expect_refused(ok, c, "initial_gap");
  c = contact;
  c.b = StructurePoint<double>{p.left, 0.3};
  expect_refused(ok, c, "coordinate");
  try {
    wedge_damper<double>(0, 0.1, 1e-5, 10.0, {{}, Vec2::Zero(), 2.0, 0.0}, {}, CoulombLaw<double>(0.3, 0.3));
    ADD_FAILURE() << "accepted a face angle of 2 rad";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("left.angle"), std::string::npos) << e.what();
  }
}

}  // namespace body_contact_test

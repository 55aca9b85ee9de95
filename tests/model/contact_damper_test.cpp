// The paper's damper through ContactSystem (point_damper_body: a rigid body on its spring, pressed
// by its preload, on a contact whose side b moves along the platform) against FrictionDampedSystem,
// an independent implementation of the same physics (paper eqs 10-29: its own state layout,
// contact coordinate, slope and convective terms, inertial normal solve): the blade scene of
// examples/blade_damper in its three regimes, run by the same integrator at a tight tolerance.
// Also the moving contact on its own: its member-end stop and its checks.

#include "blade_damper/blade_scene.hpp"
#include "model/contact_samples.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/model/point_damper_body.hpp>
#include <stickslip/stickslip.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace contact_damper_test {

using namespace stickslip;
using Bodies = ContactSystem<double, BodyContact<double>>;
using System = blade::BladeScene::System;

/// The blade scene's dampers as bodies and contacts of a ContactSystem on the same frame, modes
/// and load.
struct BodyScene {
  std::vector<RigidBody<double>> bodies;
  std::vector<BodyContact<double>> contacts;
  explicit BodyScene(const blade::BladeScene& s) {
    for (std::size_t i = 0; i < s.system->dampers().size(); ++i) {
      const auto part =
          point_damper_body(s.frame, static_cast<Eigen::Index>(i), s.system->dampers()[i], s.system->options());
      bodies.push_back(part.body);
      contacts.push_back(part.contact);
    }
  }
};

/// Records the tip displacement at the output samples.
struct Tip : NullObserver {
  Eigen::VectorXd shape;
  std::vector<double> t, tip;
  template <class S, class X, class M>
  bool on_sample(S time, const X& x, const M&) {
    t.push_back(time);
    tip.push_back(shape.dot(x.head(shape.size())));
    return true;
  }
};

/// Dormand-Prince at rtol 1e-11, atol 1e-15 (the modal coordinates are ~1e-5, the contact
/// coordinates ~1e-2), samples every `interval`.
RunOptions<double> very_tight(double interval) {
  RunOptions<double> run;
  run.stepper.rtol = 1e-11;
  run.stepper.atol = 1e-15;
  run.stepper.output_interval = interval;
  return run;
}

/// How a run of both ends: both complete, or both stop (at a lift-off or a member end) at the
/// same time.
enum class Ending { Completes, LiftOff, LeavesMember };

/// One regime: FrictionDampedSystem and the body scene over `duration` from rest, the blade's
/// parameters `p` (with its modelling and contact choices).
void compare(const blade::BladeParameters& p, double duration, std::size_t min_events, Ending ending = Ending::Completes) {
  blade::BladeScene scene = blade::make_blade_scene(p);
  auto& fds = *scene.system;
  const BodyScene parts(scene);
  Bodies sys(scene.frame, scene.basis, parts.bodies, parts.contacts, fds.loads());
  ASSERT_EQ(sys.num_moving(), p.model.moving_contact ? 2 : 0);
  const double interval = 2e-4;

  auto xa = fds.initial_state();
  auto ma = fds.requested_mode();
  ASSERT_TRUE(fds.make_consistent(ma, 0.0, xa));
  const double Ea = fds.mechanical_energy(ma, 0.0, xa);
  Tip ta;
  ta.shape = scene.tip_shape;
  const auto ra = simulate(fds, ma, 0.0, xa, duration, very_tight(interval), ta);
  if (ending == Ending::Completes) ASSERT_EQ(ra.status, Status::Success) << ra.message;
  else ASSERT_EQ(fds.stop_reason(), ending == Ending::LiftOff ? System::StopReason::LiftOff
                                                              : System::StopReason::LeftMember) << ra.message;

  auto xb = sys.initial_state();
  auto mb = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mb, 0.0, xb));
  const double Eb = sys.mechanical_energy(xb);
  Tip tb;
  tb.shape = scene.tip_shape;
  const auto rb = simulate(sys, mb, 0.0, xb, duration, very_tight(interval), tb);
  ASSERT_EQ(rb.status, ra.status) << rb.message;
  if (ending != Ending::Completes) {
    EXPECT_NE(rb.message.find(ending == Ending::LiftOff ? "lifted off" : "left member"), std::string::npos)
        << rb.message;
    // The stop's time is located to the stepper's bracket (1e-12 s) on the same integration
    // error as the event times below.
    EXPECT_NEAR(rb.t, ra.t, 1e-10) << ra.message << " / " << rb.message;
  }

  // The same switches at the same times. The body's tangent is -u (t = (n_y, -n_x) with
  // n = -w), so its sliding velocity is -V: SlipPositive of one is SlipNegative of the other.
  auto mirrored = [](ContactState s) {
    return s == ContactState::SlipPositive ? ContactState::SlipNegative
           : s == ContactState::SlipNegative ? ContactState::SlipPositive
                                              : s;
  };
  const auto& ea = fds.events();
  const auto& eb = sys.events();
  ASSERT_GE(ea.size(), min_events);
  ASSERT_EQ(ea.size(), eb.size());
  double worst = 0;
  for (std::size_t k = 0; k < ea.size(); ++k) {
    EXPECT_EQ(ea[k].damper, eb[k].contact) << k;
    EXPECT_EQ(mirrored(ea[k].from), eb[k].from) << k;
    EXPECT_EQ(mirrored(ea[k].to), eb[k].to) << k;
    worst = std::max(worst, std::abs(ea[k].t - eb[k].t));
  }
  // Both integrate the same equations at rtol 1e-11 with their own arithmetic and states
  // (element-space products against full shape vectors, an N solve against a capacitance LU, the
  // damper's y slaved against the body's y held at the velocity level): the event times differ by
  // the integration and location error (measured 1.1e-12 s at most over these runs, the location
  // bracket 1e-12 s); 1e-10 s leaves a factor 100. Without the moving contact's convective terms
  // (contact_system_moving.hpp) the slipping runs differ by 4.6e-6 s and 1.2e-6 s (tip 2.9e-3 and
  // 2.8e-4 relative); the stuck run does not see them (X' = 0).
  EXPECT_LE(worst, 1e-10) << "largest event-time difference";
  // Tip displacement at every sample to 1e-8 of its amplitude (measured 1.5e-10: the same
  // integration error, growing through the stick-slip switches).
  ASSERT_EQ(ta.tip.size(), tb.tip.size());
  double amp = 0, diff = 0;
  for (std::size_t k = 0; k < ta.tip.size(); ++k) {
    amp = std::max(amp, std::abs(ta.tip[k]));
    diff = std::max(diff, std::abs(ta.tip[k] - tb.tip[k]));
  }
  EXPECT_LE(diff, 1e-8 * amp) << "tip displacement difference of " << amp;
  ::testing::Test::RecordProperty("events", static_cast<int>(ea.size()));
  char measured[96];
  std::snprintf(measured, sizeof measured, "%.3g s, %.3g", worst, diff / amp);
  ::testing::Test::RecordProperty("event_time_and_relative_tip_differences", measured);
  // Both energy audits close (rtol 1e-11: measured 5e-12 at most; 1e-10 leaves a factor 20).
  const auto ba = fds.energy_balance(ra.mode, ra.t, ra.x, Ea);
  const auto bb = sys.energy_balance(rb.x, Eb);
  EXPECT_LE(ba.relative_residual(), 1e-10);
  EXPECT_LE(bb.relative_residual(), 1e-10) << bb.residual << " of " << bb.scale;
}

// The paper's three regimes at the blade example's preloads (blade_regression_test's cases).
blade::BladeParameters at(double preload) {
  blade::BladeParameters p;
  p.preload = preload;
  return p;
}
TEST(PointDamperBody, GrossSlipRunsAsFrictionDampedSystem) { compare(at(2.0), 0.1, 4); }
TEST(PointDamperBody, StickSlipRunsAsFrictionDampedSystem) { compare(at(2.7), 0.1, 4); }
TEST(PointDamperBody, StickRunsAsFrictionDampedSystem) { compare(at(12.0), 0.1, 0); }

// A constant normal load (ModelOptions::normal_load = Constant): the contact's normal held at
// N0, the body free of the member along w. Stick-slip at 2.7 N. Without the held normal's force
// along n (on the body against its preload, on the member N0 psi_w(X), eq 25) the preload
// pushes the body through the member and the audit does not close (relative residual 1.0
// measured); the switch times alone move by less than 1e-10 s (the symmetric preloads barely
// load the modes the lateral excitation drives).
TEST(PointDamperBody, ConstantNormalLoadRunsAsFrictionDampedSystem) {
  blade::BladeParameters p = at(2.7);
  p.model.normal_load = NormalLoad::Constant;
  compare(p, 0.1, 4);
}

// The contact points fixed at X0 (ModelOptions::moving_contact = false).
TEST(PointDamperBody, FixedContactPointsRunAsFrictionDampedSystem) {
  blade::BladeParameters p = at(2.0);
  p.model.moving_contact = false;
  compare(p, 0.1, 4);
}

// The blade example's default ends (EndPolicy::Throw: a contact point at a platform end stops
// the run) at 1 N, where the dampers slide off the platform at 0.158 s (the regression record's
// leaves_platform_1N): both stop there.
TEST(PointDamperBody, LeavingThePlatformStopsAsFrictionDampedSystem) {
  compare(at(1.0), 0.2, 4, Ending::LeavesMember);
}

// Member ends that continue the end elements' shapes (EndPolicy::Extrapolate, --ends extend):
// at 1 N the dampers pass the platform end at 0.158 s and the run goes on.
TEST(PointDamperBody, ExtendedEndsRunAsFrictionDampedSystem) {
  blade::BladeParameters p = at(1.0);
  p.model.end_policy = EndPolicy::Extrapolate;
  compare(p, 0.2, 4);
}

// The paper's permanent contact broken (Separation::Stop, the blade example's default): under a
// 200 N load the platform's vertical acceleration at a contact exceeds r Omega^2 = 1150 m/s^2
// and N = N0 - s m y'' reaches zero; both stop there.
TEST(PointDamperBody, LiftOffStopsAsFrictionDampedSystem) {
  blade::BladeParameters p = at(2.0);
  p.force = 200.0;
  p.model.end_policy = EndPolicy::Extrapolate;  // else a contact point leaves the platform first (10.6 ms)
  compare(p, 0.1, 0, Ending::LiftOff);
}

// What the body form does not have is refused, naming the option.
TEST(PointDamperBody, ChoicesWithoutABodyFormAreRefusedNamingThem) {
  blade::BladeScene scene = blade::make_blade_scene(at(2.0));
  auto refused = [&](PointDamper<double> d, ModelOptions<double> o, const char* what) {
    try {
      (void)point_damper_body(scene.frame, 0, d, o);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const PointDamper<double> d = scene.system->dampers()[0];
  const ModelOptions<double> o;
  PointDamper<double> wall = d;
  wall.finish_end = MemberEnd::Wall;
  refused(wall, o, "finish_end = Wall");
  ModelOptions<double> clamp = o;
  clamp.end_policy = EndPolicy::Clamp;
  refused(d, clamp, "Clamp");
  ModelOptions<double> no_convective = o;
  no_convective.convective_terms = false;
  refused(d, no_convective, "convective_terms");
  ModelOptions<double> unwatched = o;
  unwatched.watch_lift_off = false;
  refused(d, unwatched, "watch_lift_off");
  PointDamper<double> unloaded = d;
  unloaded.preload = 0;
  unloaded.normal_load = NormalLoad::Constant;
  refused(unloaded, o, "preload");
  // A held normal cannot start open; the contact's own checks name the options.
  auto c = point_damper_body(scene.frame, 0, d, o).contact;
  c.normal_behaviour = ContactNormal::Held;
  c.held_normal_force = 1.0;
  c.initial_state = ContactState::Separated;
  EXPECT_THROW(c.validate("c"), std::invalid_argument);
  c.initial_state = ContactState::Stick;
  c.held_normal_force = 0.0;
  EXPECT_THROW(c.validate("c"), std::invalid_argument);
  c.held_normal_force = 1.0;
  c.start_end = MemberEnd::Wall;
  EXPECT_THROW(c.validate("c"), std::invalid_argument);
}

/// A horizontal beam (0.2 m, clamped at both ends) and a body pressed on it by P, pushed along it
/// by H > mu P: the body's contact point slides towards the end at x = 0.2 m.
struct Pushed {
  FrameModel<double> frame;
  MemberId beam = 0;
  ModalBasis<double> basis;
  RigidBody<double> body;
  BodyContact<double> contact;
  Pushed() {
    const NodeId a = frame.add_node(0.0, 0.0), b = frame.add_node(0.2, 0.0);
    beam = frame.add_member(a, b, SectionProperties<double>{2.06e11, 7800, 1e-4, 1e-8}, 6);
    frame.clamp(a);
    frame.clamp(b);
    ModalOptions<double> mo;
    mo.num_modes = 3;
    basis = compute_modes(frame.assemble(), mo);
    body.mass = 0.1;
    body.inertia = 1e-5;
    body.loads.push_back({PlaneDirection<double>::global_y(), -10.0, {}});
    body.loads.push_back({PlaneDirection<double>::global_x(), 5.0, {}});
    contact = BodyContact<double>::on_structure({0, Eigen::Vector2d::Zero()}, {beam, 0.19},
                                                PlaneDirection<double>::global_y(), CoulombLaw<double>(0.2, 0.2));
    contact.contact_point = ContactPoint::Moving;
  }
};

// The body slides (H = 5 N against mu P = 2 N: 30 m/s^2) from X0 = 0.19 m and reaches the member
// end after sqrt(2 * 0.01 / 30) = 26 ms: the run stops there, naming the contact and the member.
TEST(MovingContactPoint, LeavingTheMemberStopsTheRunNamingIt) {
  const Pushed s;
  Bodies sys(s.frame, s.basis, {s.body}, {s.contact});
  auto x = sys.initial_state();
  EXPECT_EQ(x[sys.contact_offset()], 0.19);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  contact_samples::Samples rec;
  const auto r = simulate(sys, mode, 0.0, x, 0.1, contact_samples::tight(0), rec);
  EXPECT_EQ(r.status, Status::StoppedBySystem);
  EXPECT_NE(r.message.find("contact 0 left member"), std::string::npos) << r.message;
  // Against the rigid-ground flight X = X0 + a t^2 / 2 (the beam's deflection under 10 N moves
  // the end time by far less than 1 ms).
  EXPECT_NEAR(r.t, std::sqrt(2 * 0.01 / 30.0), 1e-3);
  EXPECT_NEAR(r.x[sys.contact_offset()], 0.2, 1e-9);
}

// A moving contact point needs a side b on the structure, a start inside the member and a
// normal normal to it; the state's X must lie on the member.
TEST(MovingContactPoint, BadMovingContactsAreRefusedNamingTheParameter) {
  const Pushed s;
  auto refused = [&](const BodyContact<double>& c, const char* what) {
    try {
      Bodies sys(s.frame, s.basis, {s.body}, {c});
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  auto c = s.contact;
  c.b.reset();
  refused(c, "side b");
  c = s.contact;
  c.b->coordinate = 0.2;
  refused(c, "must start inside member");
  c = s.contact;
  c.normal = PlaneDirection<double>::at_angle(1.0);
  refused(c, "normal of a moving contact point");
  Bodies sys(s.frame, s.basis, {s.body}, {s.contact});
  auto x = sys.initial_state();
  x[sys.contact_offset()] = 0.3;
  EXPECT_THROW(sys.validate_state(sys.requested_mode(), x), std::invalid_argument);
}

}  // namespace contact_damper_test

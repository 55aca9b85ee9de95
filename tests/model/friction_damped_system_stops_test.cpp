// FrictionDampedSystem's named stops (lift-off, a contact leaving its member) and its caller
// errors (std::invalid_argument naming the parameter).
#include "model_test_scenes.hpp"

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace {
using namespace model_test;

RunOptions<double> default_run() {
  RunOptions<double> run;
  run.stepper.rtol = 1e-8;
  run.stepper.atol = 1e-14;
  return run;
}

// ---- 6. stops with a named status ----------------------------------------------------------------

TEST(Stops, LiftOffStopsWithNamedStatusAtZeroNormalForce) {
  const TScene s = make_t_frame();
  // Preload 1 mN on a 20 g damper: the contact holds while |y''| < N0 / m = 0.1 m/s^2, far below
  // the platform's vertical acceleration under a 200 N load.
  std::vector<PointDamper<double>> d;
  d.emplace_back(s.platform, 0.01, 0.04, 1e4, 1e-3, CoulombLaw<double>(0.35, 0.3), 0.5);
  System sys(s.frame, s.basis, d, paper_load(s, 200.0));
  Recorder rec;
  const auto r = run_from_rest(sys, 0.1, default_run(), rec);
  ASSERT_EQ(r.status, Status::StoppedBySystem) << r.message;
  EXPECT_EQ(sys.stop_reason(), System::StopReason::LiftOff);
  EXPECT_EQ(sys.stop_damper(), 0);
  EXPECT_NE(r.message.find("lift-off"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("t = " + detail::format_value(r.t)), std::string::npos) << r.message;
  EXPECT_GT(r.t, 0.0);
  EXPECT_LT(r.t, 0.1);
  // The stop is at the located zero of N: |N| is the guard's location error, |N'| x 1e-12 s.
  const auto& e = sys.evaluate(r.mode, r.t, r.x);
  EXPECT_LT(std::abs(e.N[0]), 1e-6 * 1e-3);
}

// A located event in a state that is finite but whose forces overflow (a blown-up run: modal
// coordinates of 1e305, omega^2 q = inf): the transition cannot choose contact states. It must
// neither throw (CoulombContact::decide rejects a non-finite N) nor change the mode; it proceeds,
// and the stepper's finiteness check after the transition ends the run with NonFiniteState.
TEST(Stops, TransitionInOverflowingStateLeavesTheModeToTheFinitenessCheck) {
  const TScene s = make_t_frame();
  System sys(s.frame, s.basis, paper_dampers(s, 12.0), paper_load(s));
  System::State x = sys.initial_state();
  x.head(sys.num_modes()).setConstant(1e305);  // omega^2 q overflows in every contact state
  DamperStates mode(2);
  mode[0] = ContactState::SlipPositive;
  mode[1] = ContactState::Stick;
  const DamperStates before = mode;
  ASSERT_TRUE(x.allFinite());
  ASSERT_FALSE(sys.evaluate(mode, 0.0, x).finite);  // the premise: finite state, overflowing forces
  TransitionAction action;
  EXPECT_NO_THROW(action = sys.transition(mode, TriggeredGuards{0}, 0.0, x));
  EXPECT_FALSE(action.stop);
  EXPECT_EQ(mode, before);
  EXPECT_TRUE(sys.events().empty());
}

// A trial stage of a blown-up run can carry a NaN or infinite contact coordinate. The evaluation
// must report it as non-finite (every output NaN, the derivative NaN), not throw from the shape
// evaluation at a coordinate off the member, in every contact state.
TEST(Stops, NonFiniteContactCoordinateGivesANonFiniteEvaluationNotAnException) {
  const TScene s = make_t_frame();
  System sys(s.frame, s.basis, paper_dampers(s, 12.0), paper_load(s));
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    for (const ContactState st : {ContactState::Stick, ContactState::SlipPositive}) {
      System::State x = sys.initial_state();
      x[sys.contact_offset() + 1] = bad;
      DamperStates mode(2);
      mode[0] = ContactState::Stick;
      mode[1] = st;
      bool finite = true;
      EXPECT_NO_THROW(finite = sys.evaluate(mode, 0.0, x).finite);
      EXPECT_FALSE(finite);
      EXPECT_TRUE(sys.evaluate(mode, 0.0, x).qdd.array().isNaN().all());
      System::State dx;
      EXPECT_NO_THROW(sys.rhs(mode, 0.0, x, dx));
      EXPECT_TRUE(dx.array().isNaN().all());
    }
}

// Dampers 0.1 mm from either end of the platform, with low friction so that they slide: one of
// the contacts reaches an end.
std::vector<PointDamper<double>> near_ends(const TScene& s) {
  std::vector<PointDamper<double>> d;
  d.emplace_back(s.platform, 1e-4, 0.02, 1e3, 5.0, CoulombLaw<double>(0.05, 0.05), 0.5);
  d.emplace_back(s.platform, 0.04 - 1e-4, 0.02, 1e3, 5.0, CoulombLaw<double>(0.05, 0.05), 0.5);
  return d;
}

// Constant normal load: under the 100 N load an inertial normal force would lift off (first).
ModelOptions<double> near_ends_options() {
  ModelOptions<double> opt;
  opt.normal_load = NormalLoad::Constant;
  return opt;
}

TEST(Stops, ContactLeavingItsMemberStopsWithNamedStatus) {
  const TScene s = make_t_frame();
  System sys(s.frame, s.basis, near_ends(s), paper_load(s, 100.0), near_ends_options());
  Recorder rec;
  const auto r = run_from_rest(sys, 0.2, default_run(), rec);
  ASSERT_EQ(r.status, Status::StoppedBySystem) << r.message;
  EXPECT_EQ(sys.stop_reason(), System::StopReason::LeftMember);
  const Index i = sys.stop_damper();
  ASSERT_TRUE(i == 0 || i == 1);
  EXPECT_NE(r.message.find("member " + std::to_string(s.platform)), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("damper " + std::to_string(i)), std::string::npos) << r.message;
  // Stopped at the located end: X = 0 or X = L to the event location error.
  const double X = r.x[sys.contact_offset() + i];
  EXPECT_LT(std::min(std::abs(X), std::abs(X - 0.04)), 1e-9) << "X = " << X;
}

TEST(Stops, ExtrapolatePolicyContinuesPastTheMemberEnd) {
  const TScene s = make_t_frame();
  ModelOptions<double> opt = near_ends_options();
  opt.end_policy = EndPolicy::Extrapolate;
  System sys(s.frame, s.basis, near_ends(s), paper_load(s, 100.0), opt);
  Recorder rec;
  RunOptions<double> run = default_run();
  run.stepper.output_interval = 1e-4;
  const auto r = run_from_rest(sys, 0.2, run, rec);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(sys.stop_reason(), System::StopReason::None);
  double outside = 0;
  for (const auto& x : rec.x)
    for (Index i = 0; i < 2; ++i) {
      const double X = x[sys.contact_offset() + i];
      outside = std::max({outside, -X, X - 0.04});
    }
  EXPECT_GT(outside, 0.0) << "the contact must have passed an end and the run continued";
}

// The energy audit says where it cannot close: a moving contact that may go on past a member end
// (MemberEnd::Extend, here by Default) under EndPolicy::Clamp keeps the end's slope and curvature
// there, which do work its potential does not see (docs/howto/forces_events_energy.md). Under
// Throw (the ends stop the run), Extrapolate (one smooth interpolant) or with both ends explicit
// walls, it applies.
TEST(Stops, EnergyAuditSaysItDoesNotApplyPastAClampedEnd) {
  const TScene s = make_t_frame();
  auto applies = [&](EndPolicy policy, MemberEnd end) {
    ModelOptions<double> opt;
    opt.end_policy = policy;
    auto dampers = near_ends(s);
    for (auto& d : dampers) d.start_end = d.finish_end = end;
    System sys(s.frame, s.basis, dampers, paper_load(s, 100.0), opt);
    const System::State x0 = sys.initial_state();
    const DamperStates mode = sys.requested_mode();
    return sys.energy_balance(mode, 0.0, x0, 0.0).applies;
  };
  EXPECT_FALSE(applies(EndPolicy::Clamp, MemberEnd::Default));
  EXPECT_FALSE(applies(EndPolicy::Clamp, MemberEnd::Extend));
  EXPECT_TRUE(applies(EndPolicy::Clamp, MemberEnd::Wall));
  EXPECT_TRUE(applies(EndPolicy::Extrapolate, MemberEnd::Default));
  EXPECT_TRUE(applies(EndPolicy::Throw, MemberEnd::Default));
}

// ---- 7. caller errors ----------------------------------------------------------------------------

void expect_invalid(const std::function<void()>& build, const std::string& parameter) {
  try {
    build();
    ADD_FAILURE() << "no exception; expected one naming " << parameter;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(parameter), std::string::npos) << e.what();
  }
}

TEST(InvalidInput, ThrowsNamingTheParameter) {
  const TScene s = make_t_frame();
  auto with = [&](const std::function<void(std::vector<PointDamper<double>>&, std::vector<PointLoad<double>>&)>& edit) {
    return [&s, edit] {
      auto d = paper_dampers(s, 12.0);
      auto l = paper_load(s);
      edit(d, l);
      System sys(s.frame, s.basis, d, l);
    };
  };
  using D = std::vector<PointDamper<double>>;
  using L = std::vector<PointLoad<double>>;
  // The unmodified scene builds.
  EXPECT_NO_THROW(with([](D&, L&) {})());
  expect_invalid(with([](D& d, L&) { d[1].mass = -0.1; }), "mass");
  expect_invalid(with([](D& d, L&) { d[0].preload = std::nan(""); }), "preload");
  expect_invalid(with([](D& d, L&) { d[0].preload = INFINITY; }), "preload");
  expect_invalid(with([](D& d, L&) { d[0].share = 1.5; }), "share");
  expect_invalid(with([](D& d, L&) { d[1].contact_coordinate = 0.05; }), "contact_coordinate");
  expect_invalid(with([](D& d, L&) { d[0].contact_coordinate = -1e-6; }), "contact_coordinate");
  expect_invalid(with([](D&, L& l) { l[0].coordinate = 0.25; }), "coordinate");
  expect_invalid(with([](D& d, L&) { d[0].member = 7; }), "member");
  expect_invalid(with([](D&, L& l) { l[0].member = -1; }), "member");
  expect_invalid(with([](D& d, L&) { d[1].side = 0.5; }), "side");
  // Separation and member ends: coefficients of restitution in [0, 1], landing speed >= 0.
  expect_invalid(with([](D& d, L&) { d[0].restitution = -0.1; }), "restitution");
  expect_invalid(with([](D& d, L&) { d[0].restitution = 1.5; }), "restitution");
  expect_invalid(with([](D& d, L&) { d[1].restitution = std::nan(""); }), "restitution");
  expect_invalid(with([](D& d, L&) { d[1].wall_restitution = 2.0; }), "wall_restitution");
  expect_invalid(with([](D& d, L&) { d[0].landing_speed = -1e-3; }), "landing_speed");
  // Messages name the offending object too.
  expect_invalid(with([](D& d, L&) { d[1].mass = -0.1; }), "PointDamper[1]");
  expect_invalid(with([](D&, L& l) { l[0].coordinate = 0.25; }), "PointLoad");
}

}  // namespace

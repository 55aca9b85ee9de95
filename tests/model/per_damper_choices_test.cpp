// Per-damper modelling choices: PointDamper::contact_point (Moving / Fixed)
// beside the scene-wide ModelOptions::moving_contact, on the paper's T-frame with two dampers.
// References: the scene-wide fixed-contact model (every damper Fixed must be that model, bitwise);
// a stuck damper's contact cannot move (X' = V = 0), so a scene whose only moving damper never
// slips is the fixed-contact scene up to the integration error; and the energy balance, which
// closes only if the fixed damper's X rows, slope work and kinetic energy are all consistent.
#include "contact/contact_test_util.hpp"
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace per_damper_choices_test {

using namespace model_test;
using contact_test::expect_invalid_argument;

RunOptions<double> tight(double rtol = 1e-11) {
  RunOptions<double> run;
  run.stepper.rtol = rtol;
  run.stepper.atol = 1e-4 * rtol * 1e-3;
  run.stepper.output_interval = 1e-4;
  return run;
}

double tip_max_difference(const Recorder& a, const Recorder& b, double& scale) {
  double diff = 0;
  scale = 0;
  for (std::size_t k = 0; k < std::min(a.t.size(), b.t.size()); ++k) {
    diff = std::max(diff, (a.x[k].head(6) - b.x[k].head(6)).cwiseAbs().maxCoeff());
    scale = std::max(scale, a.x[k].head(6).cwiseAbs().maxCoeff());
  }
  return diff;
}

// ContactState::Separated (the contact component) is not a state of this model: a
// damper cannot start in it and a mode holding it is rejected before any solve (before, the model
// would have read a separated damper as slipping with no slip direction).
TEST(PerDamperInitialState, LiftOffAndSeparatedAreRejectedAndSoIsASeparatedMode) {
  const TScene s = make_t_frame(4, 6, 2);
  for (ContactState bad : {ContactState::LiftOff, ContactState::Separated}) {
    auto dampers = paper_dampers(s, 10.0);
    dampers[1].initial_state = bad;
    expect_invalid_argument([&] { System sys(s.frame, s.basis, dampers, paper_load(s)); },
                            {"PointDamper[1]", "initial_state", stickslip::to_string(bad)});
  }
  System sys(s.frame, s.basis, paper_dampers(s, 10.0), paper_load(s));
  DamperStates mode = sys.requested_mode();
  mode[0] = ContactState::Separated;
  System::State x = sys.initial_state(), dxdt;
  expect_invalid_argument([&] { sys.rhs(mode, 0.0, x, dxdt); },
                          {"FrictionDampedSystem::evaluate", "mode[0]", "separated"});
  expect_invalid_argument([&] { sys.make_consistent(mode, 0.0, x); },
                          {"FrictionDampedSystem::make_consistent", "mode[0]", "separated"});
}

TEST(PerDamperContactPoint, EveryDamperFixedIsTheSceneWideFixedContactModelBitwise) {
  const TScene s = make_t_frame(6);
  ModelOptions<double> fixed_scene;
  fixed_scene.moving_contact = false;
  System scene_wide(s.frame, s.basis, paper_dampers(s, 2.0), paper_load(s), fixed_scene);
  auto dampers = paper_dampers(s, 2.0);
  for (auto& d : dampers) d.contact_point = ContactPoint::Fixed;
  System per_damper(s.frame, s.basis, dampers, paper_load(s));
  EXPECT_FALSE(per_damper.options().moving_contact);  // no contact moves: no X in the state
  EXPECT_FALSE(per_damper.options().convective_terms);
  ASSERT_EQ(per_damper.state_size(), scene_wide.state_size());
  EXPECT_EQ(per_damper.contact_offset(), -1);
  Recorder a, b;
  const auto ra = run_from_rest(scene_wide, 0.05, tight(1e-8), a);
  const auto rb = run_from_rest(per_damper, 0.05, tight(1e-8), b);
  ASSERT_TRUE(ra.ok()) << ra.message;
  ASSERT_TRUE(rb.ok()) << rb.message;
  ASSERT_GT(ra.stats.events, 0);  // 2 N: the dampers slip, so the runs switch
  EXPECT_EQ(ra.stats.events, rb.stats.events);
  EXPECT_EQ(ra.stats.rhs_evaluations, rb.stats.rhs_evaluations);
  ASSERT_EQ(a.x.size(), b.x.size());
  for (std::size_t k = 0; k < a.x.size(); ++k) ASSERT_EQ(a.x[k], b.x[k]) << "sample " << k;
}

TEST(PerDamperContactPoint, FixedDamperKeepsItsPointWhileTheOtherSlidesAndTheAuditCloses) {
  const TScene s = make_t_frame(6);
  auto dampers = paper_dampers(s, 2.0);
  dampers[0].contact_point = ContactPoint::Fixed;  // damper 1 keeps the default, Moving
  System sys(s.frame, s.basis, dampers, paper_load(s));
  ASSERT_TRUE(sys.options().moving_contact);
  ASSERT_GE(sys.contact_offset(), 0);
  Recorder rec;
  double E0 = 0;
  const auto r = run_from_rest(sys, 0.1, tight(1e-10), rec, &E0);
  ASSERT_TRUE(r.ok()) << r.message;
  const Index X = sys.contact_offset();
  double moved0 = 0, moved1 = 0, residual = 0, scale = 0;
  bool slipped0 = false;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    moved0 = std::max(moved0, std::abs(rec.x[k][X] - 0.01));
    moved1 = std::max(moved1, std::abs(rec.x[k][X + 1] - 0.03));
    slipped0 = slipped0 || rec.mode[k][0] != ContactState::Stick;
    const auto b = sys.energy_balance(rec.mode[k], rec.t[k], rec.x[k], E0);
    residual = std::max(residual, std::abs(b.residual));
    scale = std::max({scale, std::abs(b.external_work), b.friction_dissipation});
    // The fixed damper's contact is where the model evaluates its forces.
    EXPECT_EQ(sys.evaluate(rec.mode[k], rec.t[k], rec.x[k]).X[0], 0.01);
  }
  ASSERT_TRUE(slipped0);          // the fixed damper does slip (X' = 0 is not trivial)
  EXPECT_EQ(moved0, 0.0);         // X' = 0 exactly: the state's X of the fixed damper never changes
  EXPECT_GT(moved1, 1e-7);        // the moving one slides (2 N: gross slip of ~1e-5 m amplitude)
  // The audit integrates the rates of the same equations: at rtol 1e-10 its residual is at the
  // integration error, 1e-7 of the largest term leaves three orders for the stepper's error.
  EXPECT_LT(residual, 1e-7 * scale) << residual << " of " << scale;
}

TEST(PerDamperContactPoint, AMovingDamperThatNeverSlipsIsTheFixedContactScene) {
  // Damper 1 pressed hard (60 N) never slips; damper 0 (2 N) slips, at a fixed contact in both
  // scenes. Only damper 1's contact point differs - Moving in one, Fixed in the other - and a
  // stuck contact does not move, so the two scenes are the same equations.
  const TScene s = make_t_frame(6);
  auto dampers = paper_dampers(s, 2.0);
  dampers[1] = paper_dampers(s, 60.0)[1];
  dampers[0].contact_point = ContactPoint::Fixed;
  System mixed(s.frame, s.basis, dampers, paper_load(s));
  dampers[1].contact_point = ContactPoint::Fixed;
  System fixed(s.frame, s.basis, dampers, paper_load(s));
  Recorder a, b;
  const auto ra = run_from_rest(mixed, 0.1, tight(), a);
  const auto rb = run_from_rest(fixed, 0.1, tight(), b);
  ASSERT_TRUE(ra.ok()) << ra.message;
  ASSERT_TRUE(rb.ok()) << rb.message;
  ASSERT_GT(ra.stats.events, 0);
  EXPECT_EQ(ra.stats.events, rb.stats.events);
  for (const auto& m : a.mode) ASSERT_EQ(m[1], ContactState::Stick);
  double scale = 0;
  const double diff = tip_max_difference(a, b, scale);
  // Two integrations of the same equations at rtol 1e-11 with different step sequences (the
  // mixed state has two more components in the error norm): they agree to the integration error,
  // here bounded by 1e-8 of the largest modal amplitude (three orders above rtol for ~60 periods
  // of the top mode and the event relocations).
  EXPECT_LT(diff, 1e-8 * scale) << diff << " of " << scale;
}

}  // namespace per_damper_choices_test

// FrictionDampedSystem::events() against the stepper's HybridStats::events.
// The system logs one ContactEvent per damper whose state a resolution changed, in transition()
// and in make_consistent(); the stepper counts one event per transition() call, however many
// dampers it switched (several, one, or none when it stops the run). The reference for each run
// is the stepper's own account of the same events (the observer's EventRecord from/to modes),
// not the system's log, plus the closed counts each scene implies: mirror dampers switch
// together (2 ContactEvents per stepper event), an impossible requested stick at t0 is one
// logged switch with no stepper event, a lift-off is a stepper event with no logged switch.
// All comparisons are of integer counts and of times copied, not computed: they are exact.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace event_log_test {

using namespace model_test;

/// Number of dampers whose state differs between `from` and `to`.
std::size_t switched(const DamperStates& from, const DamperStates& to) {
  std::size_t count = 0;
  for (Index i = 0; i < from.size(); ++i) count += from[i] != to[i] ? 1 : 0;
  return count;
}

/// Sum of switched(from, to) over the stepper's event records.
std::size_t switched_in_records(const Recorder& rec) {
  std::size_t total = 0;
  for (const auto& ev : rec.events) total += switched(ev.from, ev.to);
  return total;
}

RunOptions<double> event_run() {
  RunOptions<double> run;
  run.stepper.rtol = 1e-8;
  run.stepper.atol = 1e-14;  // modal coordinates ~1e-5
  run.stepper.output_interval = 1e-2;
  return run;
}

// The mirror scene of MirrorDampersSwitchTogether (model_test): dampers at mirror points of the
// platform, the second pressing from the other face, with a fixed contact. Both see the same
// forces, so every transition switches both: the log holds exactly two ContactEvents per
// stepper event, at the stepper event's time, for damper 0 and damper 1.
TEST(EventLog, MirrorDampersLogTwoContactEventsPerStepperEvent) {
  const TScene s = make_t_frame();
  auto dampers = paper_dampers(s, 3.0);
  dampers[1].side = -1.0;
  ModelOptions<double> opt;
  opt.moving_contact = false;
  System sys(s.frame, s.basis, dampers, paper_load(s), opt);
  Recorder rec;
  const auto r = run_from_rest(sys, 0.1, event_run(), rec);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.stats.events, 10) << "the scene must switch";
  ASSERT_EQ(static_cast<long>(rec.events.size()), r.stats.events);  // one record per transition
  EXPECT_EQ(sys.events().size(), 2 * static_cast<std::size_t>(r.stats.events));
  EXPECT_EQ(sys.events().size(), switched_in_records(rec));
  for (std::size_t k = 0; k < rec.events.size() && 2 * k + 1 < sys.events().size(); ++k) {
    const auto& first = sys.events()[2 * k];
    const auto& second = sys.events()[2 * k + 1];
    EXPECT_EQ(first.t, rec.events[k].t);
    EXPECT_EQ(second.t, rec.events[k].t);
    EXPECT_EQ(first.damper, 0);
    EXPECT_EQ(second.damper, 1);
    EXPECT_EQ(first.from, rec.events[k].from[0]);
    EXPECT_EQ(first.to, rec.events[k].to[0]);
    EXPECT_EQ(second.to, rec.events[k].to[1]);
  }
}

// make_consistent() logs its switches too, and no stepper counts them: a damper requested stuck
// whose spring already pulls harder than mu_s N0 (x = 1 mm: k_i x = 0.5 x 1e4 x 1e-3 = 5 N against
// mu_s N0 = 0.35 x 3 = 1.05 N) slips at t0. The log then holds that switch (at t0, Stick -> slip)
// followed by the switches of the run's transitions.
TEST(EventLog, MakeConsistentSwitchesAreLoggedButAreNoStepperEvents) {
  const TScene s = make_t_frame();
  System sys(s.frame, s.basis, paper_dampers(s, 3.0), paper_load(s));
  System::State x0 = sys.initial_state();
  x0[sys.x_offset()] = 1e-3;
  DamperStates mode = sys.requested_mode();
  ASSERT_EQ(mode[0], ContactState::Stick);
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
  ASSERT_EQ(sys.events().size(), 1u);
  EXPECT_EQ(sys.events()[0].t, 0.0);
  EXPECT_EQ(sys.events()[0].damper, 0);
  EXPECT_EQ(sys.events()[0].from, ContactState::Stick);
  // The spring pulls the damper back (force -k x along u): it slides the negative way.
  EXPECT_EQ(sys.events()[0].to, ContactState::SlipNegative);
  Recorder rec;
  const auto r = simulate(sys, mode, 0.0, x0, 0.05, event_run(), rec);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(r.stats.events, 2);
  EXPECT_EQ(sys.events().size(), 1 + switched_in_records(rec));
  for (std::size_t k = 1; k < sys.events().size(); ++k) EXPECT_GT(sys.events()[k].t, 0.0);
}

// A transition that stops the run is a stepper event that switches no damper: it counts in
// stats.events and logs nothing. The scene of LiftOffStopsWithNamedStatusAtZeroNormalForce
// (model_test): one 40 g damper pressed by 1 mN holds contact while |y''| < N0 / (s m) =
// 0.05 m/s^2, far below the platform's vertical acceleration under a 200 N load.
TEST(EventLog, StoppingTransitionCountsAsStepperEventWithoutContactEvent) {
  const TScene s = make_t_frame();
  auto dampers = paper_dampers(s, 1e-3);
  dampers.pop_back();
  dampers[0].mass = 0.04;
  System sys(s.frame, s.basis, dampers, paper_load(s, 200.0));
  Recorder rec;
  const auto r = run_from_rest(sys, 0.1, event_run(), rec);
  ASSERT_EQ(r.status, Status::StoppedBySystem) << r.message;
  ASSERT_EQ(sys.stop_reason(), System::StopReason::LiftOff);
  ASSERT_FALSE(rec.events.empty());
  EXPECT_EQ(static_cast<long>(rec.events.size()), r.stats.events);
  EXPECT_EQ(switched(rec.events.back().from, rec.events.back().to), 0u);  // the stop: mode kept
  EXPECT_EQ(rec.events.back().t, r.t);
  EXPECT_EQ(sys.events().size(), switched_in_records(rec));
  for (const auto& ce : sys.events()) EXPECT_LT(ce.t, r.t);  // nothing logged at the stop
}

}  // namespace event_log_test

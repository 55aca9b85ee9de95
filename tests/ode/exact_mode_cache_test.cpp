// ExactLinearStepper's mode cache (set_mode_cache_size): a stick-slip run alternates between a
// few modes, whose propagators are kept and reused when a mode comes back. Reference: the same
// run with the cache switched off (the cache must not change the solution).

#include <stickslip/ode/exact_linear_stepper.hpp>

#include "contact/belt_cycle.hpp"
#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ode_exact_mode_cache_test {  // named: the exact-stepper tests share a TU
namespace {

using S = stickslip::ContactState;
using Law = stickslip::CoulombLaw<double>;
using Oscillator = contact_test::SingleDofOscillator<Law>;

struct BeltRun {
  contact_test::EventLog log;
  std::vector<Eigen::Vector4d> samples;
  stickslip::HybridResult<double, Eigen::Vector4d, S> result;
  stickslip::ExactStepperStats work;
};

struct SampleLog : contact_test::EventLog {
  std::vector<Eigen::Vector4d> x;
  bool on_sample(double, const Eigen::Vector4d& xs, const S&) {
    x.push_back(xs);
    return true;
  }
};

BeltRun belt_run(std::size_t cache_entries) {
  contact_test::SingleDofParameters p;
  p.mass = 1.0;
  p.stiffness = 100.0;
  p.normal_force = 10.0;
  p.belt_speed = 0.1;
  const contact_test::BeltCycle ref(p.mass, p.stiffness, p.normal_force, {0.5, 0.3, 0.1});
  Oscillator sys(p, stickslip::CoulombContact<Law>(Law(0.5, 0.3)));
  stickslip::StepperOptions<double> opt;
  opt.output_interval = 0.01;
  stickslip::ExactLinearStepper<Oscillator> stepper(sys, opt);
  stepper.set_mode_cache_size(cache_entries);
  SampleLog log;
  const Eigen::Vector4d x0(ref.x_k - ref.d, p.belt_speed, 0, 0);
  BeltRun run;
  run.result = stepper.integrate(S::Stick, 0.0, x0, 8 * (ref.t_stick + ref.t_slip), log);
  run.log.events = log.events;
  run.samples = log.x;
  run.work = stepper.work();
  return run;
}

// The belt's stick-slip cycle alternates two modes, Stick and SlipNegative (8 slip phases). A
// stuck mass on the belt has no oscillation (crossed in one step, no ladder to keep); the slip
// mode has, and with the cache every slip phase after the first restores it: 7 hits and one
// slip set-up instead of 8 (Padé exponentials). The propagators restored are the ones computed
// for the same Â, so the solution is bitwise that of the run without the cache: events (times,
// modes, states), samples and final state compared with EXPECT_EQ.
TEST(ExactLinearStepperModeCache, BeltCycleReusesTwoModesWithTheSameSolutionBitwise) {
  const BeltRun off = belt_run(0);
  const BeltRun on = belt_run(8);
  ASSERT_TRUE(off.result.ok()) << off.result.message;
  ASSERT_TRUE(on.result.ok()) << on.result.message;
  ASSERT_EQ(off.log.events.size(), 15u);  // 8 cycles, the last event at the end is not reached
  EXPECT_EQ(off.work.mode_cache_hits, 0);
  long slips = 0;
  for (const auto& e : off.log.events) slips += e.to == S::SlipNegative ? 1 : 0;
  EXPECT_EQ(slips, 8);
  EXPECT_EQ(on.work.mode_cache_hits, slips - 1);
  EXPECT_LT(on.work.propagator_exponentials * 4, off.work.propagator_exponentials);
  ASSERT_EQ(on.log.events.size(), off.log.events.size());
  for (std::size_t i = 0; i < on.log.events.size(); ++i) {
    EXPECT_EQ(on.log.events[i].t, off.log.events[i].t) << "event " << i;
    EXPECT_EQ(on.log.events[i].to, off.log.events[i].to) << "event " << i;
    EXPECT_EQ(on.log.events[i].x, off.log.events[i].x) << "event " << i;
  }
  ASSERT_EQ(on.samples.size(), off.samples.size());
  for (std::size_t i = 0; i < on.samples.size(); ++i)
    EXPECT_EQ(on.samples[i], off.samples[i]) << "sample " << i;
  EXPECT_EQ(on.result.x, off.result.x);
}

}  // namespace
}  // namespace ode_exact_mode_cache_test

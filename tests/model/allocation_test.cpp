// No heap allocation per right-hand side of the composed model: every path of the acceleration
// solve (docs/model.md) - no unknowns, the fixed 4 x 4 capacitance system, the dynamic
// capacitance system and the mode-space system - runs on the workspace the constructor
// allocated. Global operator new is counted in this executable only.

#include <stickslip/stickslip.hpp>

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "allocation_counter.hpp"

using stickslip_test::g_allocations;

namespace {

using namespace stickslip;
using System = FrictionDampedSystem<double>;
using Index = Eigen::Index;

struct Scene {
  FrameModel<double> frame;
  Index platform = 0, blade = 0;
  ModalBasis<double> basis;
};

// The paper's T-frame (blade 0.2 m, platform 0.04 m centred on the tip) with `modes` modes.
Scene t_frame(int modes) {
  Scene s;
  const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  const Index root = s.frame.add_node(0.0, 0.0);
  const Index left = s.frame.add_node(-0.02, 0.2), right = s.frame.add_node(0.02, 0.2);
  s.platform = s.frame.add_member(left, right, sec, 8);
  const Index tip = s.frame.member(s.platform).nodes[4];
  s.blade = s.frame.add_member(root, tip, sec, 20);
  s.frame.clamp(root);
  ModalOptions<double> mo;
  mo.num_modes = modes;
  s.basis = compute_modes(s.frame.assemble(), mo);
  return s;
}

// Counts the allocations of `calls` right-hand sides in every combination of stick / slip+ /
// slip- that `pattern` generates (damper i in state (pattern + i) mod 3), at new times so that
// the evaluation cache never hits.
long allocations_of_rhs(int modes, int dampers, NormalLoad normal_load, bool moving) {
  Scene s = t_frame(modes);
  std::vector<PointDamper<double>> d;
  for (int i = 0; i < dampers; ++i) {
    const double X = 0.04 * (i + 0.5) / dampers;
    d.emplace_back(s.platform, X, 0.02, 1e4, 10.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  }
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(s.blade, 0.05, LoadDirection::GlobalX, 20.0, 200.0)};
  ModelOptions<double> opt;
  opt.normal_load = normal_load;
  opt.moving_contact = moving;
  System sys(s.frame, s.basis, d, loads, opt);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  System::State x = sys.initial_state();
  for (Index j = 0; j < 2 * modes; ++j) x[j] = 1e-4 * u(rng);
  for (Index i = 0; i < dampers; ++i) {
    x[sys.x_offset() + i] = 1e-5 * u(rng);
    x[sys.xd_offset() + i] = 1e-2 * u(rng);
  }
  std::vector<System::Mode> patterns;
  for (int p = 0; p < 3; ++p) {
    System::Mode mode = sys.requested_mode();
    for (Index i = 0; i < dampers; ++i) {
      const int k = static_cast<int>((p + i) % 3);
      mode[i] = k == 0 ? ContactState::Stick : (k == 1 ? ContactState::SlipPositive : ContactState::SlipNegative);
    }
    patterns.push_back(mode);
  }
  System::Mode all_stuck = sys.requested_mode(), all_slipping = sys.requested_mode();
  for (Index i = 0; i < dampers; ++i) {
    all_stuck[i] = ContactState::Stick;
    all_slipping[i] = ContactState::SlipPositive;
  }
  patterns.push_back(all_stuck);
  patterns.push_back(all_slipping);

  System::State dx(x.size());
  double t = 0;
  // A mode's first solve may allocate its exact-size factorisation (transition() and
  // make_consistent() do it when a run enters the mode, outside any step); every later call
  // must not allocate.
  for (const auto& mode : patterns) sys.rhs(mode, t, x, dx);
  const long before = g_allocations.load();
  for (int rep = 0; rep < 20; ++rep)
    for (const auto& mode : patterns) {
      t += 1e-6;
      sys.rhs(mode, t, x, dx);
    }
  const long count = g_allocations.load() - before;
  EXPECT_TRUE(dx.allFinite());
  return count;
}

TEST(ModelAllocation, CounterSeesAllocations) {
  // Control: the counter works (a vector that escapes through a volatile pointer).
  const long before = g_allocations.load();
  static std::vector<double>* volatile sink = nullptr;
  sink = new std::vector<double>(16, 1.0);
  delete sink;
  EXPECT_GE(g_allocations.load() - before, 2);
}

// Blade size: at most four unknowns, the fixed 4 x 4 capacitance system.
TEST(ModelAllocation, TwoDampersSixModes) {
  EXPECT_EQ(allocations_of_rhs(6, 2, NormalLoad::Inertial, true), 0);
  EXPECT_EQ(allocations_of_rhs(6, 2, NormalLoad::Inertial, false), 0);
}

// Constant normal load: all-slipping patterns have no unknowns at all.
TEST(ModelAllocation, ConstantNormalLoad) {
  EXPECT_EQ(allocations_of_rhs(6, 2, NormalLoad::Constant, true), 0);
  EXPECT_EQ(allocations_of_rhs(6, 8, NormalLoad::Constant, true), 0);
}

// Eight dampers on six modes: up to 16 unknowns on 6 modes, the mode-space system.
TEST(ModelAllocation, EightDampersSixModesModeSpace) {
  EXPECT_EQ(allocations_of_rhs(6, 8, NormalLoad::Inertial, true), 0);
}

// Eight dampers on 24 modes: the dynamic (padded 2D x 2D) capacitance system.
TEST(ModelAllocation, EightDampersTwentyFourModesCapacitance) {
  EXPECT_EQ(allocations_of_rhs(24, 8, NormalLoad::Inertial, true), 0);
}

// A whole run: eight dampers on 24 modes (the exact-size capacitance LUs) switching between
// stick and slip. The stepper calls rhs through a forwarding system that counts the allocations
// made inside rhs only; no mode is warmed up first, so this shows that the transitions allocate
// each new mode's factorisation before any step evaluates it.
struct RhsAllocationCounter {
  using Scalar = System::Scalar;
  using State = System::State;
  using Mode = System::Mode;
  System& sys;
  long allocations = 0;
  void rhs(const Mode& m, double t, const State& x, State& dxdt) {
    const long before = g_allocations.load();
    sys.rhs(m, t, x, dxdt);
    allocations += g_allocations.load() - before;
  }
  Index num_guards(const Mode& m) const { return sys.num_guards(m); }
  void guards(const Mode& m, double t, const State& x, Eigen::VectorXd& g) { sys.guards(m, t, x, g); }
  CrossingDirection guard_direction(const Mode& m, Index i) const { return sys.guard_direction(m, i); }
  TransitionAction transition(Mode& m, const TriggeredGuards& w, double t, State& x) {
    return sys.transition(m, w, t, x);
  }
};

TEST(ModelAllocation, RunThroughSwitchesAllocatesNothingInsideRhs) {
  Scene s = t_frame(24);
  std::vector<PointDamper<double>> d;
  for (int i = 0; i < 8; ++i)
    d.emplace_back(s.platform, 0.004 * (i + 0.5), 0.004, 1e4, 2.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(s.blade, 0.05, LoadDirection::GlobalX, 20.0, 200.0)};
  System sys(s.frame, s.basis, d, loads);
  System::State x = sys.initial_state();
  System::Mode mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  RhsAllocationCounter counting{sys};
  StepperOptions<double> opt;
  opt.rtol = 1e-6;
  opt.atol = 1e-10;
  HybridStepper<RhsAllocationCounter, DormandPrince54> stepper(counting, opt);
  const auto r = stepper.integrate(mode, 0.0, x, 0.05);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GT(r.stats.events, 8) << "the scene must switch for the test to mean anything";
  EXPECT_EQ(counting.allocations, 0) << "over " << r.stats.rhs_evaluations << " rhs calls";
}

}  // namespace

namespace linear_part_allocation {

using namespace stickslip;
using System = FrictionDampedSystem<double>;
using Index = Eigen::Index;

// FrictionDampedSystem::linear_part allocates nothing once the LinearPart has the
// mode's sizes: in an exact mode (both dampers stuck, moving contact) at new states, at a moved
// X (a new key: the probes run again) and repeated (the kept result is copied), and in a mode that
// is not exact (one damper slipping at a moving contact: probes and the remainder correction at
// every call). Two loads at distinct frequencies, so that the harmonic columns exist.
TEST(ModelAllocation, LinearPartAllocatesNothingOnceSized) {
  Scene s = t_frame(6);
  std::vector<PointDamper<double>> d;
  d.emplace_back(s.platform, 0.01, 0.02, 1e4, 10.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  d.emplace_back(s.platform, 0.03, 0.02, 1e4, 10.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  std::vector<PointLoad<double>> loads{
      PointLoad<double>::harmonic(s.blade, 0.05, LoadDirection::GlobalX, 20.0, 200.0),
      PointLoad<double>::harmonic(s.blade, 0.15, LoadDirection::GlobalX, 5.0, 310.0, 0.3)};
  System sys(s.frame, s.basis, d, loads);
  System::Mode stuck(2, ContactState::Stick), slipping(2, ContactState::Stick);
  slipping[0] = ContactState::SlipPositive;
  System::State x = sys.initial_state();
  LinearPart<double> lp_stuck, lp_slip;
  ASSERT_TRUE(sys.linear_part(stuck, 0.0, x, lp_stuck));   // sizes the system's probe vectors
  ASSERT_TRUE(sys.linear_part(slipping, 0.0, x, lp_slip));  // and each LinearPart
  const long before = g_allocations.load();
  for (int rep = 0; rep < 10; ++rep) {
    x[rep % 4] += 1e-6;
    const double t = 1e-4 * rep;
    ASSERT_TRUE(sys.linear_part(stuck, t, x, lp_stuck));    // same key: the kept result
    x[sys.contact_offset() + 1] += 1e-5;
    ASSERT_TRUE(sys.linear_part(stuck, t, x, lp_stuck));    // new key: probes
    ASSERT_TRUE(sys.linear_part(slipping, t, x, lp_slip));  // not exact: probes + correction
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_TRUE(lp_stuck.exact);
  EXPECT_FALSE(lp_slip.exact);
}

}  // namespace linear_part_allocation

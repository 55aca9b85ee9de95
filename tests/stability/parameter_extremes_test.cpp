// Stability at the extremes of the physical parameters (docs/stability.md): damper spring and
// mass, preload, excitation amplitude, friction coefficients, contacts at member ends,
// simultaneous switches, lift-off. Each run either succeeds with finite results that pass the
// model's own checks or stops with the named status and the time in its message.
#include "stability/stability_support.hpp"

#include <cstdio>

namespace parameter_extremes {  // named: both stability files may share one (unity) translation unit
namespace {
using namespace stability;

// The checks every successful run must pass (measured by the Checker observer, independently of
// the model's own bookkeeping). Tolerances:
//  * energy residual / energy scale <= 1e-6: the residual is the global error of the integrated
//    work terms; with rtol 1e-8 over a few thousand steps it stays orders of magnitude below.
//  * stuck |V| <= 1e-10 m/s: x' and q'^T psi_u are integrated from the same accelerations
//    (x'' = psi_u^T q''), so they differ by round-off only: velocities <= ~1 m/s times 2.2e-16
//    per step over <= 1e5 steps is <= 2e-11; any real drift would be of order the slip speeds.
//  * capacity |f| - mu_s N <= 1e-7 N: an event is located within 1e-12 s, so the state handed to
//    the transition has crossed |f| = mu_s N by at most the force rate (<= 1e5 N/s here: 200 N
//    at 200 rad/s plus inertial terms) times 1e-12 s, plus the local error of the step that
//    lands on it (rtol 1e-8 x ~10 N).
//  * wrong-sign slip speed <= 10 * 1e-12 s * max |V'| + 1e-15 m/s: the same argument for V at a
//    located V = 0 crossing.
void expect_checks_pass(const Outcome& o, double relative_residual = 1e-6) {
  SCOPED_TRACE(describe(o));
  EXPECT_FALSE(o.threw);
  EXPECT_TRUE(o.consistent_start);
  ASSERT_EQ(o.status, Status::Success);
  EXPECT_TRUE(o.message.empty());
  EXPECT_TRUE(o.finite);
  EXPECT_LE(o.relative_residual(), relative_residual);
  EXPECT_LE(o.max_stuck_V, 1e-10);
  EXPECT_LE(o.max_capacity_excess, capacity_excess_bound(o));
  EXPECT_LE(o.max_wrong_slip_V, 1e-11 * o.max_slip_Vdot + 1e-15);
}

// A stopped run: the status, the system's stop reason, a message naming the cause and the time.
void expect_stopped(const Outcome& o, System::StopReason reason, const std::string& cause) {
  SCOPED_TRACE(describe(o));
  EXPECT_FALSE(o.threw);
  ASSERT_EQ(o.status, Status::StoppedBySystem);
  EXPECT_EQ(o.stop_reason, reason);
  EXPECT_NE(o.message.find(cause), std::string::npos);
  EXPECT_TRUE(o.finite);
  EXPECT_NEAR(time_in_message(o.message), o.t, 1e-9 * std::max(1.0, o.t));
  // Up to the stop the run passed the same checks as a successful one. A run stopped within its
  // first steps has a tiny energy scale, where the event state's own error (within atol = 1e-12
  // per audit integral: the dense output at the event, EventState::Checked) sets the residual:
  // 1e-6 of the scale or 10 atol, whichever is larger.
  EXPECT_LE(o.max_energy_residual, std::max(1e-6 * o.energy_scale, 10 * 1e-12));
  EXPECT_LE(o.max_stuck_V, 1e-10);
  EXPECT_LE(o.max_capacity_excess, capacity_excess_bound(o));
}

// Coarse T-frame with 4 modes (cheap); dampers under the platform; the paper's excitation
// point, 200 N at 200 rad/s (near the first mode, 194 rad/s): the dampers first slip after
// ~3.4 ms and slide off the 40 mm platform after ~10 ms, so 8 ms runs see stick and slip.
struct Scene {
  TScene s = make_t_frame(4, 6, 4);
  ModelOptions<double> model{};
  std::vector<PointLoad<double>> loads = paper_load(s, 200.0);
  std::unique_ptr<System> sys;

  System& build(std::vector<PointDamper<double>> dampers) {
    sys = std::make_unique<System>(s.frame, s.basis, std::move(dampers), loads, model);
    return *sys;
  }
  Outcome run(std::vector<PointDamper<double>> dampers, double t_end = 0.008,
              const RunOptions<double>& o = options_for(Integrator::DormandPrince54)) {
    build(std::move(dampers));
    return stability::run(*sys, s.frame, s.basis, t_end, o);
  }
};

constexpr double kMass = 0.0209;   // the paper's damper mass for N0 = 12 N [kg]
constexpr double kLength = 0.04;   // platform length [m]

std::vector<PointDamper<double>> two_dampers(Index member, double m, double k, double N0,
                                             double mu_s = 0.35, double mu_k = 0.3) {
  return {damper(member, 0.01, m, k, N0, mu_s, mu_k), damper(member, 0.03, m, k, N0, mu_s, mu_k)};
}

// ---- damper spring k from 1 to 1e9 N/m ---------------------------------------------------------
class DamperSpring : public ::testing::TestWithParam<double> {};

TEST_P(DamperSpring, FinishesWithBalancedEnergyAndConsistentStates) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, GetParam(), 12.0));
  expect_checks_pass(o);
  EXPECT_GE(o.contact_events, 1);  // the run does switch
}
INSTANTIATE_TEST_SUITE_P(Stability, DamperSpring, ::testing::Values(1.0, 1e3, 1e6, 1e9));

// ---- damper mass from 1e-6 to 10 kg ------------------------------------------------------------
// With the paper's centrifugal preload N0 = s m r Omega^2 the preload scales with the mass.
class DamperMass : public ::testing::TestWithParam<double> {};

TEST_P(DamperMass, CentrifugalPreloadFinishesWithBalancedEnergy) {
  Scene sc;
  const double m = GetParam();
  const auto law = CoulombLaw<double>(0.35, 0.3);
  // share 1/2: the paper's damper shared by two blades (as two_dampers() above).
  const Outcome o = sc.run({PointDamper<double>::centrifugal(sc.s.platform, 0.01, m, 1e4, 0.46, 50.0, law, 0.5),
                            PointDamper<double>::centrifugal(sc.s.platform, 0.03, m, 1e4, 0.46, 50.0, law, 0.5)});
  expect_checks_pass(o);
}
INSTANTIATE_TEST_SUITE_P(Stability, DamperMass, ::testing::Values(1e-6, 1e-3, 1.0, 10.0));

// A heavy damper with a small fixed preload: its vertical inertia m y'' exceeds N0 as soon as the
// platform accelerates by N0 / (s m) = 2.4 m/s^2 -> the model's permanent-contact assumption
// breaks and the run says so.
TEST(DamperMassFixedPreload, HeavyDamperLiftsOff) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, 10.0, 1e4, 12.0));
  expect_stopped(o, System::StopReason::LiftOff, "lift-off: the normal force of damper");
  EXPECT_LT(o.t, 0.008);
}

// ---- preload N0 -> 0 and N0 = 1e6 N -------------------------------------------------------------
TEST(Preload, ZeroWithInertialNormalLoadIsLiftOffAtStart) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 0.0));
  EXPECT_FALSE(o.consistent_start);  // make_consistent reports it ...
  // ... and a user who runs anyway gets the lift-off status at once.
  expect_stopped(o, System::StopReason::LiftOff, "lift-off");
  EXPECT_LT(o.t, 1e-9);
}

// Regression test of "model: fix a constant zero preload ending in a Zeno guard": with a
// constant normal load N0 = 0 an exact-law damper is never pressed; make_consistent used to
// accept it and every step then fired an immediate stick guard (ZenoGuard, cause not named).
TEST(Preload, ZeroWithConstantNormalLoadIsReportedByMakeConsistent) {
  Scene sc;
  sc.model.normal_load = NormalLoad::Constant;
  System& sys = sc.build(two_dampers(sc.s.platform, kMass, 1e4, 0.0));
  System::State x = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  EXPECT_FALSE(sys.make_consistent(mode, 0.0, x));
  EXPECT_EQ(sys.stop_reason(), System::StopReason::LiftOff);
}

TEST(Preload, TinyIsLiftOffAtOnce) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 1e-6));
  EXPECT_TRUE(o.consistent_start);
  expect_stopped(o, System::StopReason::LiftOff, "lift-off");
  EXPECT_LT(o.t, 1e-6);
}

TEST(Preload, HugeKeepsDampersStuck) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 1e6));
  expect_checks_pass(o);
  EXPECT_EQ(o.contact_events, 0);
  EXPECT_GT(o.min_N, 0.99e6);
  // Stuck all along: the contact coordinates never moved (V = 0 exactly in stick).
  EXPECT_EQ(o.x[sc.sys->contact_offset()], 0.01);
  EXPECT_EQ(o.x[sc.sys->contact_offset() + 1], 0.03);
}

// ---- excitation amplitude 0 and very large ------------------------------------------------------
TEST(Amplitude, ZeroLeavesOnlyThePreloadsStepResponse) {
  // No excitation: the preloads are step loads on the platform; the frame vibrates, nothing slips.
  Scene sc;
  sc.loads = paper_load(sc.s, 0.0);
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 12.0));
  expect_checks_pass(o);
  EXPECT_EQ(o.contact_events, 0);
  EXPECT_EQ(o.x[sc.sys->contact_offset()], 0.01);
  EXPECT_EQ(o.x[sc.sys->energy_offset()], 0.0);  // no external work
}

TEST(Amplitude, ZeroResidualIsIntegrationErrorThatConverges) {
  // One damper, no excitation: the residual must shrink with the tolerance (an integration
  // error), not stay (a model inconsistency). DormandPrince54's global error scales ~ rtol:
  // 1e3 x tighter must give > 10 x smaller.
  Scene sc;
  sc.loads = paper_load(sc.s, 0.0);
  const Outcome loose = sc.run({damper(sc.s.platform, 0.01, kMass, 1e4, 12.0)}, 0.008,
                               options_for(Integrator::DormandPrince54, 1e-7, 1e-11));
  const Outcome tight = sc.run({damper(sc.s.platform, 0.01, kMass, 1e4, 12.0)}, 0.008,
                               options_for(Integrator::DormandPrince54, 1e-10, 1e-14));
  expect_checks_pass(loose, 1e-5);
  expect_checks_pass(tight);
  EXPECT_LT(tight.max_energy_residual, 0.1 * loose.max_energy_residual)
      << describe(loose) << "\n" << describe(tight);
}

TEST(Amplitude, VeryLargeWithInertialNormalLoadLiftsOff) {
  Scene sc;
  sc.loads = paper_load(sc.s, 1e6);
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 12.0));
  expect_stopped(o, System::StopReason::LiftOff, "lift-off");
}

TEST(Amplitude, VeryLargeWithConstantNormalLoadSlidesOffTheMember) {
  Scene sc;
  sc.model.normal_load = NormalLoad::Constant;
  sc.loads = paper_load(sc.s, 1e6);
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 12.0));
  expect_stopped(o, System::StopReason::LeftMember, "left member: the contact point of damper");
  const double X = o.x[sc.sys->contact_offset() + sc.sys->stop_damper()];
  EXPECT_LT(std::min(std::abs(X), std::abs(X - kLength)), 1e-9) << X;
}

// ---- friction coefficients ----------------------------------------------------------------------
struct MuCase {
  double mu_s, mu_k;
};
class Friction : public ::testing::TestWithParam<MuCase> {};
TEST_P(Friction, FinishesWithBalancedEnergyAndConsistentStates) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 12.0, GetParam().mu_s, GetParam().mu_k));
  expect_checks_pass(o);
  const double D_fric = o.x[sc.sys->energy_offset() + 2];
  if (GetParam().mu_k == 0.0) {
    EXPECT_EQ(D_fric, 0.0);  // no kinetic friction, no dissipation
  }
  EXPECT_GE(D_fric, 0.0);
}
INSTANTIATE_TEST_SUITE_P(Stability, Friction,
                         ::testing::Values(MuCase{0.3, 0.3}, MuCase{0.35, 0.0}, MuCase{5.0, 0.01}));

// ---- contact at a member end, sliding off -------------------------------------------------------
TEST(MemberEnd, StuckContactsAtBothEndsRunNormally) {
  Scene sc;
  sc.loads = paper_load(sc.s, 20.0);  // stays stuck for the run
  const Outcome o = sc.run({damper(sc.s.platform, 0.0, kMass, 1e4, 12.0), damper(sc.s.platform, kLength, kMass, 1e4, 12.0)});
  expect_checks_pass(o);
  EXPECT_EQ(o.contact_events, 0);
}

TEST(MemberEnd, ContactAtAnEndSlidingOutwardsStopsWithLeftMember) {
  Scene sc;
  const Outcome o = sc.run({damper(sc.s.platform, 0.0, kMass, 1e4, 12.0), damper(sc.s.platform, kLength, kMass, 1e4, 12.0)});
  expect_stopped(o, System::StopReason::LeftMember, "left member");
  EXPECT_LE(std::abs(o.x[sc.sys->contact_offset() + sc.sys->stop_damper()] -
                     (sc.sys->stop_damper() == 0 ? 0.0 : kLength)), 1e-9);
}

TEST(MemberEnd, SlidingOffStopsWithLeftMemberAtTheEnd) {
  // Damper 0 starts 1 um from the end, sliding outwards at 5 cm/s with little friction: it
  // reaches the end after ~1e-6 / 0.05 = 2e-5 s.
  Scene sc;
  sc.loads = paper_load(sc.s, 0.0);
  System& sys = sc.build({damper(sc.s.platform, 1e-6, kMass, 1e4, 12.0, 0.05, 0.04),
                          damper(sc.s.platform, 0.03, kMass, 1e4, 12.0)});
  System::State x0 = sys.initial_state();
  x0[sys.xd_offset()] = -0.05;
  DamperStates mode = sys.requested_mode();
  mode[0] = ContactState::SlipNegative;
  const Outcome o = stability::run(sys, sc.s.frame, sc.s.basis, 0.008, options_for(Integrator::DormandPrince54), x0, mode);
  expect_stopped(o, System::StopReason::LeftMember, "left member: the contact point of damper 0");
  EXPECT_EQ(sys.stop_damper(), 0);
  EXPECT_NEAR(o.t, 2e-5, 1e-7);  // the slip barely decelerates over 20 us
  EXPECT_LE(std::abs(o.x[sys.contact_offset()]), 1e-12);  // located at X = 0
}

// ---- both dampers switching in the same instant -------------------------------------------------
// Two identical dampers at the same point are one damper of twice the mass, spring and preload:
// their switches must come in pairs at the same instant, and the structure must move exactly
// as with the single equivalent damper (an independent run).
TEST(SimultaneousSwitching, CoincidentDampersSwitchTogetherAndMatchTheirSum) {
  Scene sc;
  const Outcome o = sc.run({damper(sc.s.platform, 0.01, kMass, 1e4, 12.0), damper(sc.s.platform, 0.01, kMass, 1e4, 12.0)});
  expect_checks_pass(o);
  const auto& ev = sc.sys->events();
  ASSERT_GE(ev.size(), 2u);
  ASSERT_EQ(ev.size() % 2, 0u);
  for (std::size_t k = 0; k < ev.size(); k += 2) {
    EXPECT_EQ(ev[k].t, ev[k + 1].t);  // the same event, not two located ones
    EXPECT_NE(ev[k].damper, ev[k + 1].damper);
    EXPECT_EQ(ev[k].to, ev[k + 1].to);
  }
  EXPECT_EQ(o.mode[0], o.mode[1]);

  Scene one;
  const Outcome o1 = one.run({damper(one.s.platform, 0.01, 2 * kMass, 2e4, 24.0)});
  expect_checks_pass(o1);
  EXPECT_EQ(static_cast<std::size_t>(o1.contact_events) * 2, ev.size());
  const Index n = sc.sys->num_modes();
  // Same equations, same event times to the event tolerance; the integrations differ by rtol
  // 1e-8 per step: 1e-6 relative.
  EXPECT_LE((o.x.head(2 * n) - o1.x.head(2 * n)).norm(), 1e-6 * o1.x.head(2 * n).norm());
}

// ---- lift-off -----------------------------------------------------------------------------------
TEST(LiftOff, NormalForceReachingZeroStopsTheRunAtZero) {
  Scene sc;
  const Outcome o = sc.run(two_dampers(sc.s.platform, kMass, 1e4, 0.1));
  expect_stopped(o, System::StopReason::LiftOff, "lift-off: the normal force of damper");
  const auto& e = sc.sys->evaluate(o.mode, o.t, o.x);
  const Index i = sc.sys->stop_damper();
  // Located within 1e-12 s of N = 0: |N| <= N' * 1e-12 << N0 = 0.1 N.
  EXPECT_LE(std::abs(e.N[i]), 1e-6);
  EXPECT_LE(e.N[i], 0.0);
  EXPECT_GE(o.min_N, -1e-6);  // never visibly negative before the stop
}

}  // namespace
}  // namespace parameter_extremes

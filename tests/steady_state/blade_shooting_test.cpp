// Shooting on the blade-damper scene (examples/blade_damper/blade_scene.hpp, a
// FrictionDampedSystem) with 5 % modal damping at three preloads: the orbit equals the end of a
// long transient (HybridStepper alone) to what the transient has settled. With this damping (a
// probe of 60-period transients): N0 = 1 N and 2 N stick-slip (6-8 events per period, each
// damper sticking twice), N0 >= 4 N stuck all period (the paper's 12 N is stuck too; 0.2 N
// slides most of the period).

#include "blade_damper/blade_mirror.hpp"
#include "blade_damper/blade_scene.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace steady_state_blade_test {
namespace {

using System = blade::BladeScene::System;
constexpr double kPi = 3.14159265358979323846;

// Under the sanitizers (STICKSLIP_SANITIZED, set by STICKSLIP_SANITIZE) only the 26 N orbit runs:
// it keeps the variational monodromy on the model (VariationalSystem over the blade's dynamic
// sizes) under ASan + UBSan, while the finite-difference monodromy of the slipping orbits is
// plain model runs, which the other sanitizer tests cover (with 0.2 and 1 N the test took 140 s
// there, with 1 N 70 s).
// There the transient is also a third as long at three times the damping (20 periods at 15 %
// instead of 60 at 5 %: the same decay exp(-zeta w1 t) ~ 1e-9 of the start amplitude, and the
// 26 N orbit stays stuck all period, a fortiori with less response): the transient was about half
// of the test's 37 s there.
#if defined(STICKSLIP_SANITIZED)
constexpr double kPreloads[] = {26.0};
constexpr double kDampingRatio = 0.15;
constexpr int kTransientPeriods = 20;
#else
constexpr double kPreloads[] = {0.2, 1.0, 26.0};
constexpr double kDampingRatio = 0.05;
constexpr int kTransientPeriods = 60;
#endif

TEST(SteadyStateBlade, OrbitEqualsTheLongTransientAtThreePreloads) {
  for (double preload : kPreloads) {
    SCOPED_TRACE(::testing::Message() << "N0 " << preload);
    blade::BladeParameters p;
    p.preload = preload;
    p.damping_ratio = kDampingRatio;
    blade::BladeScene scene = blade::make_blade_scene(p);
    System& sys = *scene.system;
    const double T = 2 * kPi / p.force_omega;
    System::State x0 = sys.initial_state();
    System::Mode mode = sys.requested_mode();
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
    // The transient: 60 periods (1.9 s); the slowest mode decays as exp(-zeta w1 t), w1 ~ 230 rad/s:
    // ~1e-9 of the start amplitude left (under the sanitizers see kTransientPeriods).
    // (simulate(): DOPRI as compiled in stickslip::compiled, no stepper instantiated here)
    stickslip::RunOptions<double> tight;
    tight.stepper = stickslip::ShootingOptions<double>::tight_stepper();
    const double t_a = kTransientPeriods * T;
    const auto transient = stickslip::simulate(sys, mode, 0.0, x0, t_a, tight);
    ASSERT_TRUE(transient.ok()) << transient.message;
    const auto next = stickslip::simulate(sys, transient.mode, t_a, transient.x, t_a + T, tight);
    ASSERT_TRUE(next.ok()) << next.message;

    // Periodic: q, q', x_d, x_d'. The contact coordinates X are a neutral direction (a contact
    // point shifted along the member gives a neighbouring orbit: a multiplier 1 to within the
    // change of the shapes, which makes M - I singular), so they keep the transient's values;
    // the audit integrals are quadratures.
    // The variational monodromy (the model's jacobian: A_m where stuck, the tangent of the solve
    // where a contact slides; Phi on the plain run's steps, as the example takes it): ~3x cheaper
    // than the finite-difference one here (2n plain periods) and exact where the differences are
    // not (below). Stuck all period the family's multipliers 1 are exact, while the differences
    // carry ~rtol / fd_step = 1e-4 of noise, and the singular directions are lost in it.
    const bool stuck_all_period = preload > 4;
    stickslip::ShootingOptions<double> opt;
    opt.control_sensitivities = false;
    opt.periodic = stickslip::ShootingOptions<double>::first(sys.contact_offset());
    System::State guess = transient.x;
    guess.tail(sys.state_size() - sys.linear_size()).setZero();  // the audit integrals restart
    // Where the dampers slide, start 2 % off the settled state (Newton has to work); where they
    // stay stuck the orbits form a family (see below) and a wrong guess would pick another member.
    if (!stuck_all_period) guess.head(2 * sys.num_modes()) *= 1.02;
    stickslip::Shooting<System> shooting(sys, opt);
    const auto orbit = shooting.forced(transient.mode, t_a, guess, T);
    ASSERT_TRUE(orbit.ok()) << orbit.message;
    EXPECT_EQ(orbit.events.empty(), stuck_all_period);
    if (!stuck_all_period) {
      EXPECT_GE(orbit.iterations, 2);
    }
    const Eigen::Index n = sys.contact_offset();
    const double scale = transient.x.head(n).cwiseAbs().maxCoeff();
    const double settled = (next.x.head(n) - transient.x.head(n)).cwiseAbs().maxCoeff();
    std::printf("N0 %g: %zu events per period, %d runs, transient settled to %.2e of %.2e, orbit vs transient %.2e, max |mu| %.3f\n",
                preload, orbit.events.size(), orbit.iterations, settled, scale,
                (orbit.x0.head(n) - transient.x.head(n)).cwiseAbs().maxCoeff(), orbit.floquet.max_modulus);
    // The transient repeats itself to `settled`. Along the contracting directions (|mu| <=
    // mu_c) the orbit is within settled / (1 - mu_c) of it; along a family (a damper stuck all
    // period: multipliers 1, any stuck offset repeats) the minimum-norm Newton step moves by
    // ~settled. The Newton tolerance adds tolerance max(1, |x|) / (1 - mu_c). Factor 10 for the
    // non-normal M; plus the runs' error ~1e-9 of the scale.
    double mu_c = 0;
    for (Eigen::Index k = 0; k < orbit.floquet.multipliers.size(); ++k) {
      const double a = std::abs(orbit.floquet.multipliers[k]);
      if (a < 1 - 1e-3) mu_c = std::max(mu_c, a);
    }
    const double tol = 10 * (settled + opt.tolerance * std::max(1.0, scale)) / (1 - mu_c) + 1e-8 * scale;
    EXPECT_LE((orbit.x0.head(n) - transient.x.head(n)).cwiseAbs().maxCoeff(), tol);
    EXPECT_TRUE(orbit.floquet.stable);
    if (stuck_all_period) continue;
    // An independent monodromy of the sliding orbit: finite differences of plain periods at
    // fd_step 1e-9 (h = 1e-9 absolute, ~1e-5 of q ~ 1e-4). Measured against the variational one
    // (periodic block, relative to max(1, |M|) ~ 5e3): 0.15 / 1e-2 / 5e-3 / 2e-6 at fd_step
    // 1e-6 / 1e-7 / 1e-8 / 1e-9 at 0.2 N and 0.7 / 4e-3 / 1e-4 / 5e-5 at 1 N: the differences
    // converge to it, their noise ~ the runs' error / h ~ 1e-5. Bound 1e-3: 20x that; a wrong
    // term of the jacobian (or a saltation matrix) moves M at O(1).
    stickslip::ShootingOptions<double> fd = opt;
    fd.monodromy = stickslip::MonodromyMethod::FiniteDifference;
    fd.fd_step = 1e-9;
    const auto by_fd = stickslip::run_period(sys, orbit.mode, t_a, orbit.x0, T, fd, true);
    ASSERT_TRUE(by_fd.ok()) << by_fd.message;
    const Eigen::Index P = static_cast<Eigen::Index>(opt.periodic.size());
    const auto M = orbit.monodromy.topLeftCorner(P, P), Mfd = by_fd.monodromy.topLeftCorner(P, P);
    const double msize = std::max(1.0, Mfd.cwiseAbs().maxCoeff());
    EXPECT_LE((M - Mfd).cwiseAbs().maxCoeff() / msize, 1e-3) << "max |M| " << msize;
  }
}

// The blade's mirror with a half-period shift (blade_mirror.hpp): on the states and modes of a
// stick-slip run (2 N, both dampers sticking and slipping in turn), the right-hand side of the
// mirrored state half a period later is the mirrored right-hand side, f(m', t + T/2, c + S (x - c))
// = S f(m, t, x), to the round-off of the coupled solve (1e-9 of max |f|; a wrong sign or a
// swapped pair is O(1)); S and the mode image are involutions.
TEST(SteadyStateBlade, MirrorMapsTheEquationsOntoThemselvesHalfAPeriodLater) {
  blade::BladeParameters p;
  p.preload = 2.0;
  blade::BladeScene scene = blade::make_blade_scene(p);
  System& sys = *scene.system;
  const auto sym = blade::blade_half_period_symmetry(scene, sys);
  const Eigen::Index N = sys.state_size(), audit = sys.energy_offset();
  EXPECT_LE((sym.S * sym.S - Eigen::MatrixXd::Identity(N, N)).cwiseAbs().maxCoeff(), 1e-12);
  struct Samples : stickslip::NullObserver {
    std::vector<double> t;
    std::vector<System::State> x;
    std::vector<System::Mode> m;
    bool on_sample(double tt, const System::State& xx, const System::Mode& mm) {
      t.push_back(tt), x.push_back(xx), m.push_back(mm);
      return true;
    }
  } rec;
  stickslip::RunOptions<double> ro;
  ro.integrator = stickslip::Integrator::DormandPrince54;
  ro.stepper.output_interval = 0.0037;
  System::Mode mode = sys.requested_mode();
  const auto run = stickslip::simulate(sys, mode, 0.0, sys.initial_state(), 0.3, ro, rec);
  ASSERT_TRUE(run.ok()) << run.message;
  ASSERT_GT(run.stats.events, 10);
  const double T = 2 * kPi / p.force_omega;
  int slipping = 0;
  double scale = 0;  // max |f| over the run (at rest f = 0)
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    System::State f(N);
    sys.rhs(rec.m[k], rec.t[k], rec.x[k], f);
    scale = std::max(scale, f.head(audit).cwiseAbs().maxCoeff());
  }
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const System::Mode image = sym.mirror_mode(rec.m[k]);
    EXPECT_TRUE(sym.mirror_mode(image) == rec.m[k]);
    slipping += rec.m[k][0] != stickslip::ContactState::Stick ? 1 : 0;
    System::State f(N), g(N);
    sys.rhs(rec.m[k], rec.t[k], rec.x[k], f);
    sys.rhs(image, rec.t[k] + T / 2, sym.mirror(rec.x[k]), g);
    const System::State d = (sym.S * f - g).head(audit);  // the audit's rates: power, not mirrored
    EXPECT_LE(d.cwiseAbs().maxCoeff(), 1e-9 * scale) << "t " << rec.t[k];
  }
  EXPECT_GT(slipping, 0);
}

// Shooting on the half period with the mirror finds the stick-slip orbit that full-period
// shooting finds (1 N, 5 % damping, from a 60-period transient): the same state to the Newton
// tolerances, the same multipliers from M = H^2 (over the whole state: the contact coordinates,
// not periodic, carry perturbations from one half period into the other). Not under the sanitizers (two
// stick-slip orbits with finite-difference monodromies: see kPreloads).
#if !defined(STICKSLIP_SANITIZED)
TEST(SteadyStateBlade, HalfPeriodShootingWithTheMirrorFindsTheFullPeriodsOrbit) {
  blade::BladeParameters p;
  p.preload = 1.0;
  p.damping_ratio = 0.05;
  blade::BladeScene scene = blade::make_blade_scene(p);
  System& sys = *scene.system;
  const double T = 2 * kPi / p.force_omega;
  stickslip::RunOptions<double> tight;
  tight.stepper = stickslip::ShootingOptions<double>::tight_stepper();
  System::Mode mode = sys.requested_mode();
  const auto transient = stickslip::simulate(sys, mode, 0.0, sys.initial_state(), 60 * T, tight);
  ASSERT_TRUE(transient.ok()) << transient.message;
  stickslip::ShootingOptions<double> opt;
  opt.control_sensitivities = false;
  opt.periodic = stickslip::ShootingOptions<double>::first(sys.contact_offset());
  System::State guess = transient.x;
  guess.tail(sys.state_size() - sys.linear_size()).setZero();
  stickslip::Shooting<System> full(sys, opt);
  const auto orbit = full.forced(transient.mode, 60 * T, guess, T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  ASSERT_FALSE(orbit.events.empty());
  stickslip::Shooting<System> half(sys, opt);
  half.half_period_symmetry(blade::blade_half_period_symmetry(scene, sys));
  const auto h = half.forced(transient.mode, 60 * T, guess, T);
  ASSERT_TRUE(h.ok()) << h.message;
  const Eigen::Index n = sys.contact_offset();
  const double scale = std::max(1.0, orbit.x0.head(n).cwiseAbs().maxCoeff());
  // Both within their Newton tolerance (1e-9 of the scale) of the orbit, along its contracting
  // directions amplified by at most 1 / (1 - max |mu|) (max |mu| ~ 0.6 here): 1e-7 leaves margin.
  EXPECT_LE((h.x0.head(n) - orbit.x0.head(n)).cwiseAbs().maxCoeff(), 1e-7 * scale);
  ASSERT_EQ(h.floquet.multipliers.size(), orbit.floquet.multipliers.size());
  // Both variational on the plain runs' steps (~1e-4 of |M| ~ 1 apart, as the test above measures
  // against finite differences); squaring H's periodic block alone gave 0.654 against 0.641.
  EXPECT_NEAR(h.floquet.max_modulus, orbit.floquet.max_modulus, 1e-3);
  EXPECT_EQ(h.events.size(), orbit.events.size());
}
#endif

}  // namespace
}  // namespace steady_state_blade_test

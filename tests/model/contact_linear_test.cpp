// ContactSystem::linear_part: the matrix and load terms against central differences of rhs in
// each mode (rhs is affine in x in an exact mode, so the differences are exact to round-off),
// the affine guards against guards(), the exponential run of the grounded-slider cantilever
// against a tight Dormand-Prince run of the same scene, and Den Hartog's closed-form orbit of a
// one-mode slider run by the exact method.

#include "contact/den_hartog_orbit.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace contact_linear_test {

using namespace stickslip;
using System = ContactSystem<double>;
using State = System::State;
using Vector = Eigen::VectorXd;
constexpr double kPi = 3.14159265358979323846;

/// The grounded_slider example's scene: a clamped cantilever (0.2 m, `elements` elements) with
/// a grounded slider at mid-span along X and a harmonic tip force F0 sin(W t + phase).
struct Slider {
  FrameModel<double> frame;
  MemberId beam = 0;
  ModalBasis<double> basis;
  double length = 0.2;
  explicit Slider(int elements = 20, Eigen::Index modes = 6) {
    const NodeId root = frame.add_node(0, 0), tip = frame.add_node(0, length);
    beam = frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, elements);
    frame.clamp(root);
    ModalOptions<double> mo;
    mo.num_modes = modes;
    mo.solver = ModalSolver::Dense;
    basis = compute_modes(frame.assemble(), mo).with_modal_damping(Vector::Constant(modes, 0.01));
  }
  System system(FrictionLawVariant<double> law, double N, double F0, double W, double phase = 0.0,
                bool audit = true, int sliders = 1) const {
    std::vector<PointContact<double>> contacts;
    for (int s = 0; s < sliders; ++s)
      contacts.push_back(PointContact<double>::grounded({beam, length * (0.5 - 0.25 * s)},
                                                        PlaneDirection<double>::global_x(), law, N));
    std::vector<PointLoad<double>> loads{
        PointLoad<double>::harmonic(beam, length, LoadDirection::GlobalX, F0, W, phase)};
    ContactSystemOptions<double> o;
    o.energy_audit = audit;
    return System(frame, basis, contacts, loads, o);
  }
};

/// max |a - b| / max(|b|, floor) over the entries.
double relative_gap(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), floor);
}

/// Checks linear_part in `mode` against rhs and guards at random states and times.
void expect_linear_part_matches_rhs(System& sys, const System::Mode& mode, bool exact) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Index m = sys.num_coordinates(), P = 2 * m;
  State x = sys.initial_state();
  for (Eigen::Index k = 0; k < P; ++k) x[k] = 1e-4 * u(rng) * (k < m ? 1.0 : 300.0);
  const double t = 0.0123;
  LinearPart<double> lp;
  ASSERT_TRUE(sys.linear_part(mode, t, x, lp));
  EXPECT_EQ(lp.exact, exact);
  ASSERT_EQ(lp.size(), P);
  // Central differences of rhs along each linear component: an affine rhs makes them exact up
  // to round-off, eps |f| / h with |f| up to omega_6^2 |q| ~ 1e6 here and h = 1e-3: ~1e-7 of a
  // column whose scale is omega_6^2 ~ 2e10. 1e-9 relative fails for any wrong coupling term
  // (the projection of the stuck mode changes entries by O(1) relative).
  State f_plus, f_minus, f;
  Eigen::MatrixXd A(P, P);
  const double h = 1e-3;
  for (Eigen::Index j = 0; j < P; ++j) {
    State xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    sys.rhs(mode, t, xp, f_plus);
    sys.rhs(mode, t, xm, f_minus);
    A.col(j) = (f_plus - f_minus).head(P) / (2 * h);
  }
  if (exact) {
    EXPECT_LE(relative_gap(lp.A, A, 1.0), 1e-9);
  }
  // A x + b(t) reproduces rhs at the call's (t, x) in every mode (an inexact mode's b0 absorbs
  // the rest there); in an exact mode also at other times and states. Round-off of the sums:
  // eps times the largest term A_ij x_j ~ 2e10 * 1e-4 = 2e6, so 1e-8 of the scale.
  Vector b(P);
  auto expect_rhs_at = [&](double time, const State& at) {
    sys.rhs(mode, time, at, f);
    lp.load(time, b);
    const Vector affine = lp.A * at.head(P) + b;
    const double scale = (lp.A * at.head(P)).cwiseAbs().maxCoeff();
    EXPECT_LE((affine - f.head(P)).cwiseAbs().maxCoeff(), 1e-12 * scale + 1e-12) << "t = " << time;
  };
  expect_rhs_at(t, x);
  if (!exact) return;
  State y = x;
  for (Eigen::Index k = 0; k < P; ++k) y[k] = 2e-4 * u(rng) * (k < m ? 1.0 : 300.0);
  expect_rhs_at(0.0371, y);
  // The affine guards against guards() at (t', y): g = Gx y + g0 + gc cos + gs sin.
  ASSERT_TRUE(lp.has_affine_guards());
  System::GuardVector g;
  sys.guards(mode, 0.0371, y, g);
  ASSERT_EQ(lp.Gx.rows(), g.size());
  Vector ga = lp.Gx * y.head(P) + lp.g0;
  for (std::size_t k = 0; k < lp.omega.size(); ++k) {
    const double wt = lp.omega[k] * 0.0371;
    ga += std::cos(wt) * lp.gc.col(static_cast<Eigen::Index>(k)) + std::sin(wt) * lp.gs.col(static_cast<Eigen::Index>(k));
  }
  // Stick guards mu_s N -/+ lambda with lambda ~ |w| omega^2 |q| ~ 1e2..1e6: round-off 1e-10
  // of that; the slip guard is v ~ 1e-2.
  EXPECT_LE((ga - g).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, g.cwiseAbs().maxCoeff())) << ga.transpose() << "\n"
                                                                                              << g.transpose();
}

TEST(ContactLinearPart, MatrixLoadsAndGuardsMatchTheRhsInStickAndSlip) {
  const Slider s(10, 4);
  System sys = s.system(CoulombLaw<double>(0.35, 0.3), 10.0, 2.0, 300.0, 0.4, true, 2);
  System::Mode mode = sys.requested_mode();
  mode[0] = ContactState::Stick;
  mode[1] = ContactState::Stick;
  expect_linear_part_matches_rhs(sys, mode, true);
  mode[0] = ContactState::SlipPositive;
  expect_linear_part_matches_rhs(sys, mode, true);
  mode[1] = ContactState::SlipNegative;
  expect_linear_part_matches_rhs(sys, mode, true);
  mode[0] = ContactState::Stick;
  EXPECT_TRUE(sys.exact_mode(mode));
  // A Stribeck law's slip force depends on |v|: inexact, b0 corrected at the call's state.
  System stribeck = s.system(StribeckLaw<double>(0.35, 0.3, 0.05), 10.0, 2.0, 300.0);
  System::Mode slip = stribeck.requested_mode();
  slip[0] = ContactState::SlipPositive;
  EXPECT_FALSE(stribeck.exact_mode(slip));
  expect_linear_part_matches_rhs(stribeck, slip, false);
  slip[0] = ContactState::Stick;  // stuck, the law's slip force does not enter
  EXPECT_TRUE(stribeck.exact_mode(slip));
}

/// Event times and end state of a run of `sys` from rest over `periods` forcing periods.
struct RunRecord {
  std::vector<double> event_t;
  std::vector<ContactState> event_to;
  State x;
};
RunRecord run_from_rest(System sys, double W, double periods, Integrator method) {
  State x = sys.initial_state();
  auto mode = sys.requested_mode();
  EXPECT_TRUE(sys.make_consistent(mode, 0.0, x));
  sys.clear_events();
  RunOptions<double> o;
  o.integrator = method;
  o.stepper.rtol = 1e-12;
  o.stepper.atol = 1e-16;
  const auto r = simulate(sys, mode, 0.0, x, periods * 2 * kPi / W, o);
  EXPECT_EQ(r.status, Status::Success) << r.message;
  RunRecord out;
  for (const auto& e : sys.events()) {
    out.event_t.push_back(e.t);
    out.event_to.push_back(e.to);
  }
  out.x = r.x;
  return out;
}

TEST(ContactLinearPart, ExponentialRunOfTheGroundedSliderEqualsDormandPrince) {
  // The grounded_slider example's scene near its first resonance: stick-slip from rest, with
  // the sixth mode (22 kHz) ringing after every stick event.
  const Slider s;
  const double W = 1.1 * s.basis.omega()(0);
  const System sys = s.system(CoulombLaw<double>(0.35, 0.3), 10.0, 2.0, W);
  const RunRecord dp = run_from_rest(sys, W, 3.0, Integrator::DormandPrince54);
  const RunRecord ex = run_from_rest(sys, W, 3.0, Integrator::Exponential);
  ASSERT_GE(dp.event_t.size(), 6u);  // stick-slip: several switches per period
  ASSERT_EQ(ex.event_t.size(), dp.event_t.size());
  // Dormand-Prince at rtol 1e-12 carries a global error of ~1e-10 of the state; an event time
  // moves by that over |g'| / |g| ~ 1/omega_1 (~5e-3 s): ~1e-12 s, located to 1e-12 s by both.
  // 1e-9 s (3e-8 of the period) leaves margin and fails for a friction force off by 1e-7.
  for (std::size_t k = 0; k < dp.event_t.size(); ++k) {
    EXPECT_NEAR(ex.event_t[k], dp.event_t[k], 1e-9) << "event " << k;
    EXPECT_EQ(ex.event_to[k], dp.event_to[k]) << "event " << k;
  }
  // The end states (z, z', audit integrals) to 1e-7 of each block's scale (the exact method's
  // round-off and the DOPRI run's global error ~1e-10 amplified over the stick-slip history).
  const Eigen::Index m = sys.num_coordinates();
  for (Eigen::Index o : {Eigen::Index(0), m}) {
    const double scale = dp.x.segment(o, m).cwiseAbs().maxCoeff();
    EXPECT_LE((ex.x.segment(o, m) - dp.x.segment(o, m)).cwiseAbs().maxCoeff(), 1e-7 * scale);
  }
  const double audit = dp.x.tail(3).cwiseAbs().maxCoeff();
  EXPECT_LE((ex.x.tail(3) - dp.x.tail(3)).cwiseAbs().maxCoeff(), 1e-7 * audit);
}

TEST(ContactLinearPart, OneModeSliderFollowsDenHartogsOrbitByTheExactMethod) {
  // One retained mode: the tip slider is a single-DOF Coulomb oscillator with m = 1/phi^2,
  // k = omega^2/phi^2; its continuous-sliding orbit in closed form (Den Hartog).
  Slider s(10, 1);
  s.basis = s.basis.with_modal_damping(Vector::Zero(1));
  const NodeId tip = s.frame.member(s.beam).nodes.back();
  const double phi = s.basis.nodal(tip, Dof::X)(0);
  const double wn = s.basis.omega()(0), m = 1 / (phi * phi), k = wn * wn * m;
  const double W = 0.6 * wn, F0 = 20.0, mu = 0.3, N = 15.0;
  const contact_test::DenHartogOrbit orbit(m, k, F0, W, mu * N, mu * N);
  ASSERT_TRUE(orbit.valid);
  std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
      {s.beam, s.length}, PlaneDirection<double>::global_x(), CoulombLaw<double>(mu, mu), N)};
  std::vector<PointLoad<double>> loads{
      PointLoad<double>::harmonic(s.beam, s.length, LoadDirection::GlobalX, F0, W, kPi / 2)};  // F0 cos(W t)
  System sys(s.frame, s.basis, contacts, loads);
  State x = sys.initial_state();
  x[0] = -orbit.X / phi;  // the lower stop, at rest, at t1
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, orbit.t1, x));
  ASSERT_EQ(mode[0], ContactState::SlipPositive);
  LinearPart<double> lp;
  ASSERT_TRUE(sys.linear_part(mode, orbit.t1, x, lp));
  EXPECT_TRUE(lp.exact);
  struct Samples : NullObserver {
    std::vector<double> t, q;
    bool on_sample(double time, const State& state, const System::Mode&) {
      t.push_back(time);
      q.push_back(state[0]);
      return true;
    }
  } rec;
  RunOptions<double> o;
  o.integrator = Integrator::Exponential;
  o.stepper.output_interval = orbit.T / 50;
  const double E0 = sys.mechanical_energy(x);
  const auto r = simulate(sys, mode, orbit.t1, x, orbit.t1 + 3.75 * orbit.T, o, rec);
  ASSERT_EQ(r.status, Status::Success) << r.message;
  ASSERT_GE(rec.t.size(), 180u);
  double worst = 0;
  for (std::size_t j = 0; j < rec.t.size(); ++j) {
    double xe, ve;
    orbit.state(rec.t[j], xe, ve);
    worst = std::max(worst, std::abs(phi * rec.q[j] - xe));
  }
  // Exact propagation between events located to 1e-12 s: round-off ~1e-13 X per period plus
  // the event-time error times the speed; 1e-9 X fails for mu N off by 1e-8 relative.
  EXPECT_LE(worst, 1e-9 * orbit.X);
  // The start (stuck -> sliding up), then a slip reversal every half period: 7 in 3.75 periods.
  EXPECT_EQ(sys.events().size(), 1u + 7u);
  for (const auto& ev : sys.events()) EXPECT_NE(ev.to, ContactState::Stick);
  const auto b = sys.energy_balance(r.x, E0);
  EXPECT_LE(b.relative_residual(), 1e-9);  // Gauss-Legendre quadratures on the exact state
}

TEST(ContactLinearPart, ShootingByTheExactMethodFindsTheSliderOrbitOfATransient) {
  // The one-mode slider of the test above with 2 % damping: its orbit by shooting with
  // exponential runs from a guess 2 % off.
  Slider s(10, 1);
  s.basis = s.basis.with_modal_damping(Vector::Constant(1, 0.02));  // an isolated orbit
  const double wn = s.basis.omega()(0), W = 0.6 * wn, F0 = 20.0, mu = 0.3, N = 15.0;
  // With damping the reference is a long Dormand-Prince transient (independent of the exact
  // method and of shooting) rather than Den Hartog's undamped closed form.
  std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
      {s.beam, s.length}, PlaneDirection<double>::global_x(), CoulombLaw<double>(mu, mu), N)};
  std::vector<PointLoad<double>> loads{
      PointLoad<double>::harmonic(s.beam, s.length, LoadDirection::GlobalX, F0, W)};
  ContactSystemOptions<double> o;
  o.energy_audit = false;
  System sys(s.frame, s.basis, contacts, loads, o);
  const double T = 2 * kPi / W;
  State x = sys.initial_state();
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  RunOptions<double> tight;
  tight.stepper.rtol = 1e-12;
  tight.stepper.atol = 1e-16;
  // 2 % damping of the one mode: the transient decays as exp(-0.02 wn t), 1e-12 after ~36
  // periods at W = 0.6 wn; 60 periods.
  const auto reference = simulate(sys, mode, 0.0, x, 60 * T, tight);
  ASSERT_EQ(reference.status, Status::Success) << reference.message;
  ASSERT_TRUE(is_slipping(reference.mode[0]));  // continuous sliding: no stick at t = 60 T
  ShootingOptions<double> so;
  so.integrator = OrbitIntegrator::Exponential;
  Shooting<System> shooting(sys, so);
  State guess = reference.x;
  guess *= 1.02;
  const auto orbit = shooting.forced(reference.mode, 60 * T, guess, T);
  ASSERT_EQ(orbit.status, ShootingStatus::Converged) << orbit.message;
  // Newton tolerance 1e-9 of max(1, |x|) and the reference's error ~1e-10 of the state.
  EXPECT_LE((orbit.x0 - reference.x).cwiseAbs().maxCoeff(), 1e-8 * reference.x.cwiseAbs().maxCoeff());
  EXPECT_TRUE(orbit.floquet.stable);
}

}  // namespace contact_linear_test

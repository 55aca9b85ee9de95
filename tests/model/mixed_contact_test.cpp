// ContactSystem with contacts of both kinds in one scene (AnyContact): a wedge damper between two
// platforms (BodyContact) and a grounded slider on the left platform (PointContact). References
// that do not come from the system: the stuck scene's frequencies from an independent eigen
// solve of the constrained linear system assembled by hand (the wedge's four rows and the
// slider's nodal row), the energy balance of a stick-slip run, and the single-kind systems
// (ContactSystem<double, BodyContact>, ContactSystem<double>), whose runs a mixed system holding
// one kind must repeat.

#include "model/contact_samples.hpp"
#include "model/wedge_scene.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace mixed_contact_test {

using namespace stickslip;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using Vec2 = Eigen::Vector2d;
using Mixed = ContactSystem<double, AnyContact<double>>;
using contact_samples::Samples;
using contact_samples::tight;
using wedge_scene::kPi;
using wedge_scene::nodal_row;
using wedge_scene::Platforms;
using wedge_scene::static_state;
using wedge_scene::Wedge;

/// The left platform's middle node (coordinate 0.0625 of 0.125, node 2 of its 4 elements).
NodeId middle_node(const Platforms& p) { return p.frame.member(p.left).nodes[2]; }

/// A grounded slider at the left platform's middle, along global Y (the platform's transverse).
PointContact<double> slider(const Platforms& p, double N, double mu_s = 0.35, double mu_k = 0.3) {
  return PointContact<double>::grounded({p.left, 0.0625}, PlaneDirection<double>::global_y(),
                                        CoulombLaw<double>(mu_s, mu_k), N);
}

/// The wedge's contacts and the slider as one list.
std::vector<AnyContact<double>> mixed_contacts(const WedgeDamper<double>& wedge, const PointContact<double>& s) {
  std::vector<AnyContact<double>> all(wedge.contacts.begin(), wedge.contacts.end());
  all.emplace_back(s);
  return all;
}

// The stuck scene about the wedge's static equilibrium (the slider, at rest there, carries no
// force): the rates of the system's accelerations (central differences of evaluate()) against the
// constrained eigenproblem assembled by hand, M = diag(1, m, m, J), K = diag(omega^2, 0, 0,
// sum_k N_k n_k . r_k), with the wedge's four rows and the slider's row [Psi_Y(middle), 0, 0, 0].
TEST(MixedContacts, StuckFrequenciesMatchTheConstrainedEigenSolve) {
  const Eigen::Index n = 8, m = n + 3;
  const Platforms p(n);
  const Wedge w;
  const auto wedge = w.build(p);
  Mixed sys(p.frame, p.basis, {wedge.body}, mixed_contacts(wedge, slider(p, 1e3)));
  ASSERT_EQ(sys.num_contacts(), 3);
  const Mixed::State x = static_state(sys, p, w);
  const auto mode = sys.requested_mode();
  const auto& e0 = sys.evaluate(mode, 0.0, x);
  ASSERT_TRUE(e0.finite);
  EXPECT_NEAR(e0.N[2], 1e3, 1e-12);       // the slider's held normal
  EXPECT_NEAR(e0.f[2], 0.0, 1e-9 * w.P);  // nothing for it to hold at the wedge's equilibrium
  EXPECT_NEAR(e0.N[0], w.Nl, 1e-9 * w.P);
  const std::vector<double> lam = wedge_scene::stuck_rates(sys, mode, x, m);
  wedge_scene::HandSystem hand(p, w, 5);  // the wedge's four rows and the slider's
  hand.G.row(4).head(n) = nodal_row(p, middle_node(p), Vec2(0, 1)).transpose();
  const Vector ref = hand.constrained_eigenvalues(5);
  ASSERT_EQ(ref.size(), m - 5);
  // Five zero rates (the constrained directions), then the m - 5 squared frequencies. Tolerance
  // as WedgeDamper.StuckFrequenciesMatchTheConstrainedEigenSolve: central differences of a solve
  // linear in q and smooth in theta, truncation ~ step^2, rounding ~ 1e-8 relative.
  const double top = ref.maxCoeff();
  for (int k = 0; k < 5; ++k) EXPECT_LE(std::abs(lam[static_cast<std::size_t>(k)]), 1e-6 * top) << k;
  for (Eigen::Index k = 0; k < m - 5; ++k)
    EXPECT_NEAR(lam[static_cast<std::size_t>(k + 5)], ref(k), 1e-6 * ref(k)) << k;
  // The wedge's rows alone give a lower first frequency (by more than the tolerance): the
  // comparison sees the slider's row.
  EXPECT_GT(ref(0), 1.01 * hand.constrained_eigenvalues(4)(0));
}

/// The last `count` switches of a system's log, for a failure's message.
template <class System>
std::string last_events(const System& sys, std::size_t count = 12) {
  std::string out;
  const auto& ev = sys.events();
  for (std::size_t k = ev.size() > count ? ev.size() - count : 0; k < ev.size(); ++k)
    out += "\n  t = " + std::to_string(ev[k].t) + " contact " + std::to_string(ev[k].contact) + ": " +
           std::to_string(static_cast<int>(ev[k].from)) + " -> " + std::to_string(static_cast<int>(ev[k].to));
  return out;
}

/// The shaken scene of WedgeDamper.StickSlipRunWithRotationClosesTheEnergyBalance: the wedge
/// stuck in its static equilibrium, the left platform's tip shaken vertically at 0.6 of the first
/// frequency by `force` [N].
struct Shaken {
  static constexpr Eigen::Index n = 8;
  Platforms p{n, 0.01};
  Wedge w;
  WedgeDamper<double> wedge;
  double W = 0, T = 0;
  std::vector<PointLoad<double>> loads;
  explicit Shaken(double force = 30.0) {
    WedgeFace<double> left{{p.tip_left()}, w.rl, w.al, 0.0}, right{{p.tip_right()}, w.rr, w.ar, 0.0};
    wedge = wedge_damper<double>(0, w.mass, w.inertia, w.P, left, right, CoulombLaw<double>(0.25, 0.2));
    W = 0.6 * p.basis.omega()(0);
    T = 2 * kPi / W;
    loads = {PointLoad<double>::harmonic(p.left, 0.125, LoadDirection::GlobalY, force, W)};
  }
  /// Runs `sys` from the static state over `periods` periods.
  template <class System>
  SimulationResult<System> run(System& sys, double periods, Samples& rec) const {
    typename System::State x = static_state(sys, p, w);
    auto mode = sys.requested_mode();
    EXPECT_TRUE(sys.make_consistent(mode, 0.0, x));
    return simulate(sys, mode, 0.0, x, periods * T, tight(T / 200), rec);
  }
};

// The shaken wedge (20 N) with a slider on the left platform whose capacity mu_s N = 7 N is a
// fraction of the shaking force: both kinds stick and slip, the wedge turns and lifts off; the
// energy audit (impacts and stuck projections booked) closes. (At 30 N the wedge lands grazing:
// LandingRule.ShakenWedgeRunsThroughItsGrazingLandings.)
TEST(MixedContacts, StickSlipRunWithBothKindsClosesTheEnergyBalance) {
  const Shaken s(20.0);
  Mixed sys(s.p.frame, s.p.basis, {s.wedge.body}, mixed_contacts(s.wedge, slider(s.p, 20.0)), s.loads);
  Samples rec;
  const auto result = s.run(sys, 4, rec);
  ASSERT_EQ(result.status, Status::Success) << result.message << last_events(sys);
  int wedge_switches = 0, slider_switches = 0;
  for (const auto& ev : sys.events()) (ev.contact == 2 ? slider_switches : wedge_switches) += 1;
  EXPECT_GE(wedge_switches, 4);
  EXPECT_GE(slider_switches, 4);  // the slider sticks and slips too
  const auto b = sys.energy_balance(result.x, sys.mechanical_energy(rec.x.front()));
  EXPECT_GT(b.friction_dissipation, 0.0);
  // rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work.
  EXPECT_LE(b.relative_residual(), 1e-7) << b.residual << " of " << b.scale;
}

/// Expects the two event logs to hold the same switches at the same times.
template <class A, class B>
void expect_same_events(const A& a, const B& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k].t, b[k].t, 1e-12) << k;
    EXPECT_EQ(a[k].contact, b[k].contact) << k;
    EXPECT_EQ(a[k].from, b[k].from) << k;
    EXPECT_EQ(a[k].to, b[k].to) << k;
  }
}

// A mixed system holding one kind runs as the single-kind system: the same switches at the same
// times (to 1e-12 s, the event location's bracket; the same arithmetic gives them bitwise) and
// the same final state.
TEST(MixedContacts, OneKindRunsAsTheSingleKindSystem) {
  const Shaken s;
  {  // the wedge alone
    ContactSystem<double, BodyContact<double>> body(s.p.frame, s.p.basis, {s.wedge.body}, s.wedge.contacts, s.loads);
    Mixed mixed(s.p.frame, s.p.basis, {s.wedge.body},
                std::vector<AnyContact<double>>(s.wedge.contacts.begin(), s.wedge.contacts.end()), s.loads);
    Samples ra, rb;
    const auto a = s.run(body, 2, ra);
    const auto b = s.run(mixed, 2, rb);
    ASSERT_EQ(a.status, Status::Success) << a.message;
    ASSERT_EQ(b.status, Status::Success) << b.message;
    EXPECT_GE(body.events().size(), 4u);
    expect_same_events(body.events(), mixed.events());
    EXPECT_LE((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12 * a.x.cwiseAbs().maxCoeff());
  }
  {  // two sliders alone (no bodies)
    const std::vector<PointContact<double>> sliders{slider(s.p, 20.0),
                                                    PointContact<double>::grounded(
                                                        s.p.tip_right(), PlaneDirection<double>::global_y(),
                                                        CoulombLaw<double>(0.3, 0.25), 5.0)};
    ContactSystem<double> point(s.p.frame, s.p.basis, sliders, s.loads);
    Mixed mixed(s.p.frame, s.p.basis, std::vector<RigidBody<double>>{},
                std::vector<AnyContact<double>>(sliders.begin(), sliders.end()), s.loads);
    Samples ra, rb;
    auto xa = point.initial_state();
    auto xb = mixed.initial_state();
    auto ma = point.requested_mode(), mb = mixed.requested_mode();
    ASSERT_TRUE(point.make_consistent(ma, 0.0, xa));
    ASSERT_TRUE(mixed.make_consistent(mb, 0.0, xb));
    const auto a = simulate(point, ma, 0.0, xa, 2 * s.T, tight(0), ra);
    const auto b = simulate(mixed, mb, 0.0, xb, 2 * s.T, tight(0), rb);
    ASSERT_EQ(a.status, Status::Success) << a.message;
    ASSERT_EQ(b.status, Status::Success) << b.message;
    EXPECT_GE(point.events().size(), 4u);
    expect_same_events(point.events(), mixed.events());
    EXPECT_LE((a.x - b.x).cwiseAbs().maxCoeff(), 1e-12 * a.x.cwiseAbs().maxCoeff());
  }
}

// A mixed list is refused as each kind is: the body side's checks name the contact and the
// parameter, and a held normal stays a held normal (Separated is not a state of the slider).
TEST(MixedContacts, EachKindKeepsItsChecks) {
  const Platforms p(4);
  const Wedge w;
  const auto wedge = w.build(p);
  auto contacts = mixed_contacts(wedge, slider(p, 10.0));
  std::get<BodyContact<double>>(contacts[1].kind).a.body = 3;
  try {
    Mixed sys(p.frame, p.basis, {wedge.body}, contacts);
    ADD_FAILURE() << "accepted a contact on body 3 of 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("contact 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a.body"), std::string::npos) << e.what();
  }
  Mixed sys(p.frame, p.basis, {wedge.body}, mixed_contacts(wedge, slider(p, 10.0)));
  auto mode = sys.requested_mode();
  mode[0] = ContactState::Separated;  // a body contact may open
  EXPECT_NO_THROW(sys.validate_state(mode, sys.initial_state()));
  mode[2] = ContactState::Separated;  // the slider's normal is held
  EXPECT_THROW(sys.validate_state(mode, sys.initial_state()), std::invalid_argument);
}

}  // namespace mixed_contact_test

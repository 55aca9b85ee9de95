// ContactSystem: grounded sliders and point-to-point friction joints on a modal structure,
// against references that do not come from the system: Den Hartog's closed-form orbit, the
// eigenpairs of the frame with the contact's DOFs tied (an independent dense eigen solve of the
// FE matrices), the stuck system's frequency response by a direct complex solve with a Lagrange
// multiplier (no time integration, no contact logic), and the energy balance.

#include "contact/den_hartog_orbit.hpp"
#include "model/contact_samples.hpp"

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

namespace contact_system_test {

using namespace stickslip;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using System = ContactSystem<double>;
using State = System::State;

constexpr double kPi = 3.14159265358979323846;
const SectionProperties<double> kSteel{2.06e11, 7800, 6e-5, 2e-11};

/// A clamped vertical cantilever of `elements` elements along Y, length 0.2 m.
struct Cantilever {
  FrameModel<double> frame;
  MemberId member = 0;
  NodeId root = 0, tip = 0;
  double length = 0.2;
  explicit Cantilever(int elements, double x = 0.0) { add(elements, x); }
  Cantilever() = default;
  MemberId add(int elements, double x) {
    root = frame.add_node(x, 0.0);
    tip = frame.add_node(x, length);
    member = frame.add_member(root, tip, kSteel, elements);
    frame.clamp(root);
    return member;
  }
};

ModalBasis<double> modes_of(const FrameModel<double>& frame, Eigen::Index count) {
  ModalOptions<double> mo;
  mo.num_modes = count;
  mo.solver = ModalSolver::Dense;
  return compute_modes(frame.assemble(), mo);
}

using contact_samples::Samples;
using contact_samples::tight;

/// Eigenpairs of the FE frame with the free DOFs `a` and `b` tied, u_a = u_b (b < 0: u_a = 0),
/// by a dense generalised eigen solve of T^T K T, T^T M T (T: the constraint's null space).
struct TiedModes {
  Vector omega;
  Matrix u;  // columns: mode shapes over the frame's free DOFs
};
TiedModes tied_modes(const AssembledFrame<double>& fe, Eigen::Index a, Eigen::Index b) {
  const Matrix K(fe.stiffness), M(fe.mass);
  const Eigen::Index nf = K.rows();
  Matrix T = Matrix::Zero(nf, nf - 1);
  for (Eigen::Index i = 0, c = 0; i < nf; ++i) {
    if (i == a) continue;
    T(i, c) = 1;
    if (i == b) T(a, c) = 1;  // u_a = u_b
    ++c;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> es(T.transpose() * K * T, T.transpose() * M * T);
  return {es.eigenvalues().cwiseSqrt(), T * es.eigenvectors()};
}

/// Modal coordinates and tip history of a run from q0 at rest in a tied mode: q(t) = q0 cos(w t).
void expect_standing_mode(System& sys, const Vector& q0, double omega, const Vector& probe, double periods) {
  State x = sys.initial_state();
  x.head(sys.num_modes()) = q0;
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double T = 2 * kPi / omega;
  Samples rec;
  auto result = simulate(sys, mode, 0.0, x, periods * T, tight(T / 40), rec);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  const double amplitude = std::abs(probe.dot(q0));
  double worst = 0;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const double expected = probe.dot(q0) * std::cos(omega * rec.t[k]);
    worst = std::max(worst, std::abs(probe.dot(rec.x[k].head(sys.num_modes())) - expected));
  }
  // rtol 1e-10 over a few periods: a global error ~1e-8 of the amplitude; 1e-6 leaves margin and
  // still fails for a frequency off by 1e-7 relative (phase error 2 pi periods 1e-7 ~ 2e-6).
  EXPECT_LE(worst, 1e-6 * amplitude);
}

// ---------------------------------------------------------------------------------------------
// Grounded slider

// One retained mode: the tip is a single-DOF oscillator with m = 1/phi^2, k = omega^2/phi^2
// (x = phi q); a grounded Coulomb slider at the tip gives Den Hartog's continuous-sliding orbit.
TEST(GroundedSlider, OneModeFollowsDenHartogsClosedFormOrbit) {
  Cantilever c(10);
  const auto basis = modes_of(c.frame, 1);
  const double phi = basis.nodal(c.tip, Dof::X)(0);
  const double wn = basis.omega()(0), m = 1 / (phi * phi), k = wn * wn * m;
  const double w = 0.6 * wn, F0 = 20.0, mu = 0.3, N = 15.0;
  const contact_test::DenHartogOrbit orbit(m, k, F0, w, mu * N, mu * N);
  ASSERT_TRUE(orbit.valid);
  std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
      {c.member, c.length}, PlaneDirection<double>::global_x(), CoulombLaw<double>(mu, mu), N)};
  // F0 cos(w t) = F0 sin(w t + pi/2).
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(c.member, c.length, LoadDirection::GlobalX, F0, w, kPi / 2)};
  System sys(c.frame, basis, contacts, loads);
  EXPECT_NEAR(sys.contact_row(0)(0), phi, 1e-12 * std::abs(phi));  // MemberShapes at the tip node = the nodal row

  // Start on the orbit at its lower stop x = -X, v = 0 (time t1): the slider starts sliding up.
  State x = sys.initial_state();
  x[0] = -orbit.X / phi;
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, orbit.t1, x));
  EXPECT_EQ(mode[0], ContactState::SlipPositive);
  const double E0 = sys.mechanical_energy(x);
  Samples rec;
  auto result = simulate(sys, mode, orbit.t1, x, orbit.t1 + 4 * orbit.T, tight(orbit.T / 50), rec);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  double worst = 0;
  for (std::size_t s = 0; s < rec.t.size(); ++s) {
    double xe, ve;
    orbit.state(rec.t[s], xe, ve);
    worst = std::max(worst, std::abs(phi * rec.x[s][0] - xe));
  }
  // rtol 1e-10 and event times located to ~1e-12 s: errors ~1e-9 X; 1e-7 X fails for a friction
  // force off by 1e-6 relative (dX/d(mu N) ~ X / F0 scale).
  EXPECT_LE(worst, 1e-7 * orbit.X);
  // The start (stuck -> sliding up), then two stops per period, each a slip reversal (no stick,
  // mu_s = mu_k): 7 inside (t1, t1 + 4T). The eighth falls on the run's end, where whether it is
  // located depends on the method's last step (Integrator::Auto runs this exactly linear scene
  // by the exponential method): only the switches before the end are counted.
  const double t_end = orbit.t1 + 4 * orbit.T;
  const auto before_end = std::count_if(sys.events().begin(), sys.events().end(),
                                        [&](const auto& ev) { return ev.t < t_end - 1e-6 * orbit.T; });
  EXPECT_EQ(before_end, 1 + 7);
  for (const auto& ev : sys.events()) EXPECT_NE(ev.to, ContactState::Stick);
  const auto b = sys.energy_balance(result.x, E0);
  EXPECT_LE(b.relative_residual(), 1e-7);  // the audit closes to the integration error
  EXPECT_GT(b.friction_dissipation, 0);
}

/// The stuck response of a damped cantilever with its node `node` held along X, forced at the
/// tip by F0 sin(W t): q(t) = Im(Q e^{iWt}), lambda(t) = Im(L e^{iWt}) from the direct complex
/// solve [diag(w^2 - W^2 + i W c), -w; w^T, 0] [Q; L] = [phi_F F0; 0] (w, phi_F: nodal rows).
struct StuckResponse {
  Eigen::VectorXcd Q;
  std::complex<double> L;
};
StuckResponse stuck_response(const ModalBasis<double>& basis, const Vector& w, const Vector& phiF, double F0, double W) {
  const Eigen::Index n = basis.size();
  Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(n + 1, n + 1);
  Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(n + 1);
  for (Eigen::Index j = 0; j < n; ++j)
    A(j, j) = std::complex<double>(basis.omega()(j) * basis.omega()(j) - W * W, W * basis.damping_coefficients()(j));
  A.block(0, n, n, 1) = -w.cast<std::complex<double>>();
  A.block(n, 0, 1, n) = w.transpose().cast<std::complex<double>>();
  rhs.head(n) = (phiF * F0).cast<std::complex<double>>();
  const Eigen::VectorXcd sol = A.fullPivLu().solve(rhs);
  return {sol.head(n), sol(n)};
}

struct SliderScene {
  Cantilever c{10};
  ModalBasis<double> basis;
  NodeId node = 0;  // mid-span node
  Vector w, phiF;
  double F0 = 5.0, W = 0;
  SliderScene() {
    basis = modes_of(c.frame, 6).with_modal_damping(Vector::Constant(6, 0.02));
    node = c.frame.member(c.member).nodes[5];
    w = basis.nodal(node, Dof::X).transpose();
    phiF = basis.nodal(c.tip, Dof::X).transpose();
    W = 0.7 * basis.omega()(0);
  }
  System system(double mu_s_N) const {
    std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
        {c.member, c.length / 2}, PlaneDirection<double>::global_x(), CoulombLaw<double>(0.3, 0.25), mu_s_N / 0.3)};
    std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(c.member, c.length, LoadDirection::GlobalX, F0, W)};
    return System(c.frame, basis, contacts, loads);
  }
};

// Started on the stuck steady state with mu_s N 2 % above the reaction's amplitude |L|, the
// slider never slips and the response is the direct solve's; 2 % below, it slips first where
// |lambda(t)| = |Im(L e^{iWt})| reaches mu_s N.
TEST(GroundedSlider, SlipsFirstWhereTheStuckReactionReachesMuSN) {
  const SliderScene s;
  const StuckResponse ref = stuck_response(s.basis, s.w, s.phiF, s.F0, s.W);
  const double R = std::abs(ref.L);
  const Eigen::Index n = s.basis.size();
  auto start = [&](System& sys) {
    State x = sys.initial_state();
    x.head(n) = ref.Q.imag();
    x.segment(n, n) = s.W * ref.Q.real();
    return x;
  };
  const double T = 2 * kPi / s.W;
  {
    System sys = s.system(1.02 * R);
    EXPECT_NEAR(sys.contact_row(0).dot(s.w) / s.w.squaredNorm(), 1.0, 1e-12);  // node: nodal row
    State x = start(sys);
    auto mode = sys.requested_mode();
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
    Samples rec;
    auto result = simulate(sys, mode, 0.0, x, 3 * T, tight(T / 40), rec);
    ASSERT_EQ(result.status, Status::Success) << result.message;
    EXPECT_TRUE(sys.events().empty());
    double worst = 0;
    for (std::size_t k = 0; k < rec.t.size(); ++k) {
      const std::complex<double> e = std::exp(std::complex<double>(0, s.W * rec.t[k]));
      worst = std::max(worst, std::abs(s.phiF.dot(rec.x[k].head(n)) - (s.phiF.cast<std::complex<double>>().dot(ref.Q) * e).imag()));
    }
    // rtol 1e-10: 1e-7 of the tip amplitude; a modal damping or load row off by 1e-5 fails.
    EXPECT_LE(worst, 1e-7 * std::abs(s.phiF.cast<std::complex<double>>().dot(ref.Q)));
  }
  {
    System sys = s.system(0.98 * R);
    State x = start(sys);
    auto mode = sys.requested_mode();
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
    ASSERT_EQ(mode[0], ContactState::Stick);  // |lambda(0)| below mu_s N for this phase
    Samples rec;
    auto result = simulate(sys, mode, 0.0, x, T, tight(T / 40), rec);
    ASSERT_EQ(result.status, Status::Success) << result.message;
    ASSERT_FALSE(sys.events().empty());
    // First t > 0 with |Im(L e^{iWt})| = 0.98 |L|: W t + arg L = asin(+-0.98) (mod pi).
    double t_first = 1e300;
    for (double target : {std::asin(0.98), kPi - std::asin(0.98)})
      for (int k = -2; k < 4; ++k) {
        const double t = (target + k * kPi - std::arg(ref.L)) / s.W;
        if (t > 0) t_first = std::min(t_first, t);
      }
    // Events located to ~1e-12 s; the stuck response is exact to ~1e-10 relative.
    EXPECT_NEAR(sys.events()[0].t, t_first, 1e-8);
    EXPECT_EQ(sys.events()[0].from, ContactState::Stick);
  }
}

/// A cantilever of 4 elements (all modes retained) whose DOF `dof` at its third node is held by
/// the contact make(node) with a friction limit far above the load: free vibrations in the first
/// two modes of the frame with that DOF fixed (independent eigen solve) stand as cos(w t), and
/// the contact never slips.
template <class MakeContact>
void expect_pins_dof(Dof dof, MakeContact make) {
  Cantilever c(4);
  const auto fe = c.frame.assemble();
  const auto basis = modes_of(c.frame, fe.dofs.num_free());
  const NodeId node = c.frame.member(c.member).nodes[2];
  const TiedModes tied = tied_modes(fe, fe.dofs.free_index(node, dof), -1);
  System sys(c.frame, basis, {make(c, node)});
  EXPECT_EQ(sys.contact_row(0), Vector(basis.nodal(node, dof).transpose()));
  const Matrix M(fe.mass);
  const Vector probe = basis.nodal(c.tip, Dof::X).transpose();
  for (int k : {0, 1}) {
    const Vector q0 = basis.phi().transpose() * M * tied.u.col(k) * (1e-3 / tied.u.col(k).cwiseAbs().maxCoeff());
    expect_standing_mode(sys, q0, tied.omega(k), probe, 3);
    EXPECT_TRUE(sys.events().empty());
  }
}

// Stuck with a friction limit far above the load: the slider at mid-span pins its node's X.
TEST(GroundedSlider, FarAboveTheLoadItPinsItsNodeAsTheFrameWithTheDofFixed) {
  expect_pins_dof(Dof::X, [](const Cantilever& c, NodeId) {
    return PointContact<double>::grounded({c.member, c.length / 2}, PlaneDirection<double>::global_x(),
                                          CoulombLaw<double>(0.3, 0.3), 1e12);
  });
}

// A relation of one's own (PointContact::with_row): a rotational friction hinge to ground at the
// node, w = the node's rotation row, pins the rotation.
TEST(RowContact, RotationalHingeFarAboveTheLoadPinsTheRotationAsTheFrameWithTheDofFixed) {
  expect_pins_dof(Dof::Rz, [](const Cantilever&, NodeId node) {
    return PointContact<double>::with_row(
        [node](const FrameModel<double>&, const ModalBasis<double>& b) { return Vector(b.nodal(node, Dof::Rz).transpose()); },
        CoulombLaw<double>(0.3, 0.3), 1e12);
  });
}

// The same relation as a grounded slider at a node, given as a row: the same run, bit for bit.
TEST(RowContact, ANodesRowGivenAsARowRunsAsTheGroundedSliderThere) {
  const SliderScene s;
  const auto point = s.system(0.5 * std::abs(stuck_response(s.basis, s.w, s.phiF, s.F0, s.W).L));
  auto contacts = point.contacts();
  const Vector w = point.contact_row(0);
  contacts[0] = PointContact<double>::with_row([w](const FrameModel<double>&, const ModalBasis<double>&) { return w; },
                                               contacts[0].friction, contacts[0].normal.value);
  System as_row(s.c.frame, s.basis, contacts, point.loads());
  System as_point = point;
  const double T = 2 * kPi / s.W;
  auto run = [&](System& sys) {
    State x = sys.initial_state();
    auto mode = sys.requested_mode();
    Samples rec;
    auto result = simulate(sys, mode, 0.0, x, 3 * T, tight(T / 40), rec);
    EXPECT_EQ(result.status, Status::Success) << result.message;
    return std::make_pair(result.x, sys.events().size());
  };
  const auto a = run(as_point), b = run(as_row);
  EXPECT_GT(a.second, 2u);
  EXPECT_EQ(a.second, b.second);
  EXPECT_EQ(a.first, b.first);
}

// ---------------------------------------------------------------------------------------------
// Friction joint between two members

struct TwoCantilevers {
  Cantilever c;
  MemberId a = 0, b = 0;
  TwoCantilevers() {
    a = c.add(4, 0.0);
    b = c.add(3, 0.05);  // another mesh: other frequencies
  }
};

TEST(FrictionJoint, FarAboveTheLoadItTiesTheTipsAsTheFrameWithTheDofsJoined) {
  TwoCantilevers s;
  const auto fe = s.c.frame.assemble();
  const auto basis = modes_of(s.c.frame, fe.dofs.num_free());
  const NodeId tip_a = s.c.frame.member(s.a).nodes.back(), tip_b = s.c.frame.member(s.b).nodes.back();
  const TiedModes tied = tied_modes(fe, fe.dofs.free_index(tip_a, Dof::X), fe.dofs.free_index(tip_b, Dof::X));
  std::vector<PointContact<double>> contacts{PointContact<double>::joint(
      {s.a, 0.2}, {s.b, 0.2}, PlaneDirection<double>::global_x(), CoulombLaw<double>(0.3, 0.3), 1e12)};
  System sys(s.c.frame, basis, contacts);
  const Matrix M(fe.mass);
  const Vector probe = basis.nodal(tip_b, Dof::X).transpose();
  const Vector q0 = basis.phi().transpose() * M * tied.u.col(0) * (1e-3 / tied.u.col(0).cwiseAbs().maxCoeff());
  expect_standing_mode(sys, q0, tied.omega(0), probe, 3);
  EXPECT_TRUE(sys.events().empty());
}

TEST(FrictionJoint, WithAVanishingNormalForceTheMembersMoveIndependently) {
  TwoCantilevers s;
  const auto fe = s.c.frame.assemble();
  const auto basis = modes_of(s.c.frame, fe.dofs.num_free());
  const NodeId tip_a = s.c.frame.member(s.a).nodes.back(), tip_b = s.c.frame.member(s.b).nodes.back();
  std::vector<PointContact<double>> contacts{PointContact<double>::joint(
      {s.a, 0.2}, {s.b, 0.2}, PlaneDirection<double>::global_x(), CoulombLaw<double>(0.3, 0.3), 1e-9)};
  System sys(s.c.frame, basis, contacts);
  // Member a alone in its first mode: the modal coordinates of the frame's mode that moves a only.
  Eigen::Index j = 0;
  while (std::abs(basis.nodal(tip_a, Dof::X)(j)) < 1e-12) ++j;
  Vector q0 = Vector::Zero(basis.size());
  q0(j) = 1e-3 / std::abs(basis.nodal(tip_a, Dof::X)(j));
  const Vector probe_a = basis.nodal(tip_a, Dof::X).transpose(), probe_b = basis.nodal(tip_b, Dof::X).transpose();
  expect_standing_mode(sys, q0, basis.omega()(j), probe_a, 2);
  EXPECT_FALSE(sys.events().empty());  // the joint slips, reversing with the relative velocity
  // b feels at most mu N = 3e-10 N: its static deflection under that is ~1e-13 m.
  State x = sys.initial_state();
  x.head(basis.size()) = q0;
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  auto result = simulate(sys, mode, 0.0, x, 0.05, tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  EXPECT_LE(std::abs(probe_b.dot(result.x.head(basis.size()))), 1e-11);
}

// ---------------------------------------------------------------------------------------------
// Energy audit and inputs

TEST(ContactSystemAudit, StickSlipRunWithTwoSlidersClosesTheEnergyBalance) {
  const SliderScene s;
  const StuckResponse ref = stuck_response(s.basis, s.w, s.phiF, s.F0, s.W);
  std::vector<PointContact<double>> contacts{
      PointContact<double>::grounded({s.c.member, s.c.length / 2}, PlaneDirection<double>::global_x(),
                                     CoulombLaw<double>(0.35, 0.3), 0.5 * std::abs(ref.L) / 0.35),
      PointContact<double>::grounded({s.c.member, s.c.length}, PlaneDirection<double>::at_angle(0.3),
                                     StribeckLaw<double>(0.4, 0.3, 0.01), 0.5)};
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(s.c.member, s.c.length, LoadDirection::GlobalX, s.F0, s.W)};
  System sys(s.c.frame, s.basis, contacts, loads);
  State x = sys.initial_state();
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  auto result = simulate(sys, mode, 0.0, x, 0.3, tight(0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  EXPECT_GE(sys.events().size(), 10u);  // stick-slip: both contacts switch repeatedly
  const auto b = sys.energy_balance(result.x, 0.0);
  EXPECT_GT(b.friction_dissipation, 0.1 * b.external_work);
  // rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work.
  EXPECT_LE(b.relative_residual(), 1e-7);
}

TEST(ContactSystemInputs, BadContactsAreRefusedNamingTheParameter) {
  Cantilever c(4);
  const auto basis = modes_of(c.frame, 4);
  auto expect_refused = [&](PointContact<double> contact, const char* what) {
    try {
      System sys(c.frame, basis, {contact});
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const auto ok = PointContact<double>::grounded({c.member, 0.1}, PlaneDirection<double>::global_x(),
                                                 CoulombLaw<double>(0.3, 0.3), 1.0);
  auto bad = ok;
  bad.normal.value = -1;
  expect_refused(bad, "normal.value");
  bad = ok;
  bad.a.coordinate = 0.3;
  expect_refused(bad, "coordinate");
  bad = ok;
  bad.direction = {1.0, 1.0};
  expect_refused(bad, "direction");
  bad = ok;
  bad.initial_state = static_cast<ContactState>(7);
  expect_refused(bad, "initial_state");
  bad = ok;
  bad.a.coordinate = 0.0;  // the clamped root never moves
  expect_refused(bad, "zero row");
  bad = PointContact<double>::joint({c.member, 0.1}, {c.member, 0.1}, PlaneDirection<double>::global_x(),
                                    CoulombLaw<double>(0.3, 0.3), 1.0);
  expect_refused(bad, "side b");
  const auto rows = [](Eigen::Index n, double value) {
    return [n, value](const FrameModel<double>&, const ModalBasis<double>&) { return Vector(Vector::Constant(n, value)); };
  };
  expect_refused(PointContact<double>::with_row(rows(3, 1.0), CoulombLaw<double>(0.3, 0.3), 1.0),
                 "row must return one value per retained mode");
  expect_refused(PointContact<double>::with_row(rows(4, std::nan("")), CoulombLaw<double>(0.3, 0.3), 1.0),
                 "row must return finite values");
}

}  // namespace contact_system_test

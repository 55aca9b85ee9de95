// Bladed disks with a rigid wedge damper between each pair of neighbouring platforms
// (neighbour_wedge_dampers), against references that do not come from the system: the stuck
// disk's small-amplitude frequencies from an independent eigen solve of the constrained linear
// system assembled by hand (the annulus' modal rows at the wings, each damper's point
// kinematics and its preload's rotational stiffness), and the energy audit of a stick-slip run
// under engine-order forcing.

#include "disk/disk_samples.hpp"
#include "model/contact_samples.hpp"
#include "contact/contact_test_util.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>


#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <numeric>
#include <vector>

namespace disk_damper_test {

using namespace disk_samples;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using Vec2 = Eigen::Vector2d;
using System = ContactSystem<double, BodyContact<double>>;

/// A tuned disk of N of the sample sectors, springs between the platforms' wings, the annulus'
/// modes from cyclic symmetry (whole families: the basis is closed under the blade shift), and
/// one wedge damper per pair of neighbours with faces at 30 and 45 degrees. The contact points
/// sit at different heights (h_l != h_r): the line between them is inclined, so the stuck
/// dampers hold the platforms' rotations as well as their axial stretch and the N stuck rows of
/// the ring stay independent with few modes. b (the right point's arm) is chosen by hand so that
/// the frictionless normal forces of the statics have no moment about the centre of mass.
struct DamperDisk {
  Eigen::Index N;
  Disk disk;
  ModalBasis<double> basis;
  double mass = 0.01, inertia = 2e-7, P = 50.0;
  double al = kPi / 6, ar = kPi / 4, a = 0.004, hl = 0.002, hr = 0.006, b = 0;
  double Nl = 0, Nr = 0;  // by hand: N_l sin a_l = N_r sin a_r, N_l cos a_l + N_r cos a_r = P
  Vec2 nl, nr, rl, rr;    // contact normals (platform -> damper) and points (body coordinates)
  NeighbourDampers<double> dampers;

  DamperDisk(Eigen::Index sectors, Eigen::Index modes_per_family, double damping, double mu)
      : N(sectors), disk(sectors, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0)) {
    CyclicModalOptions<double> o;
    o.num_modes = modes_per_family;
    const auto cm = compute_cyclic_modes(disk, o);
    basis = annulus_basis(disk, cm);
    if (damping > 0) basis = basis.with_modal_damping(Vector::Constant(basis.size(), damping));
    Nl = P * std::sin(ar) / std::sin(al + ar);
    Nr = P * std::sin(al) / std::sin(al + ar);
    nl = Vec2(std::sin(al), -std::cos(al));
    nr = Vec2(-std::sin(ar), -std::cos(ar));
    // r x N n summed over both faces = 0: N_l (a cos a_l - h_l sin a_l) + N_r (h_r sin a_r - b cos a_r) = 0.
    b = (Nl * (a * std::cos(al) - hl * std::sin(al)) + Nr * hr * std::sin(ar)) / (Nr * std::cos(ar));
    rl = Vec2(-a, hl);
    rr = Vec2(b, hr);
    NeighbourDamperSpec<double> spec;
    spec.mass = mass;
    spec.inertia = inertia;
    spec.preload = P;
    spec.left.point = rl;
    spec.left.angle = al;
    spec.right.point = rr;
    spec.right.angle = ar;
    spec.law = CoulombLaw<double>(mu, mu);
    dampers = neighbour_wedge_dampers(disk, right_wing(), left_wing(), spec);
  }
  static StructurePoint<double> right_wing() { return {kPlatformMember, kPlatform}; }
  static StructurePoint<double> left_wing() { return {kPlatformMember, 0.0}; }
  NodeId right_node(Eigen::Index k) const { return disk.node(k, 1); }          // sector node 1: right wing
  NodeId left_node(Eigen::Index k) const { return disk.node(k % N, 0); }       // sector node 0: left wing
  /// Structure part of a wing's displacement along d (hand: the nodal rows of the annulus' modes).
  Vector nodal_row(NodeId node, const Vec2& d) const {
    return (d.x() * basis.nodal(node, Dof::X) + d.y() * basis.nodal(node, Dof::Y)).transpose();
  }
  System system(std::vector<PointLoad<double>> loads = {}) const {
    return System(disk.frame(), basis, dampers.bodies, dampers.contacts, std::move(loads));
  }
  /// The static state: the platforms deflected by the hand normal forces -N n on the wings
  /// (omega^2 q = Phi^T F), each damper translated so that both gaps are zero (theta = 0), at rest.
  System::State static_state(const System& sys) const {
    const Eigen::Index n = basis.size();
    Vector F = Vector::Zero(n);
    for (Eigen::Index k = 0; k < N; ++k)
      F -= Nl * nodal_row(right_node(k), nl) + Nr * nodal_row(left_node(k + 1), nr);
    System::State x = sys.initial_state();
    x.head(n) = F.cwiseQuotient(basis.omega().cwiseAbs2());
    Eigen::Matrix2d A;
    A << nl.transpose(), nr.transpose();
    for (Eigen::Index k = 0; k < N; ++k) {
      const Eigen::Vector2d rhs(nodal_row(right_node(k), nl).dot(x.head(n)), nodal_row(left_node(k + 1), nr).dot(x.head(n)));
      x.segment<2>(sys.body_offset(k)) = A.inverse() * rhs;
    }
    return x;
  }
};

// Small oscillations of the stuck disk about its static equilibrium: the rates of the system's
// accelerations (central differences of evaluate()) against the constrained eigenproblem
// assembled by hand: M = diag(I, (m, m, J) per damper), K = diag(omega^2, (0, 0, sum_faces N n . r)
// per damper) (the preload's stiffness on theta: a force N n at R(theta) r has the moment
// N n . (k x R r), whose theta-derivative is -N n . r), four rows per damper
// g = [-d . Psi_wing, d, d . (k x r)] for d = n and t of each face.
TEST(DiskDampers, StuckFrequenciesMatchTheConstrainedEigenSolve) {
  const DamperDisk d(4, 3, 0.0, 0.5);
  ASSERT_EQ(d.dampers.bodies.size(), 4u);
  ASSERT_EQ(d.dampers.contacts.size(), 8u);
  ASSERT_EQ(d.dampers.contacts_per_damper, 2);
  System sys = d.system();
  const auto x = d.static_state(sys);
  const auto mode = sys.requested_mode();
  const Eigen::Index n = d.basis.size(), m = sys.num_coordinates(), rows = 4 * d.N;
  ASSERT_EQ(m, n + 3 * d.N);
  // The static state is an equilibrium of the stuck system (the hand normal forces hold it).
  const auto& e0 = sys.evaluate(mode, 0.0, x);
  ASSERT_TRUE(e0.finite);
  for (Eigen::Index k = 0; k < d.N; ++k) {
    // Rounding in a solve of condition ~1e5 (modal and body entries): 1e-8 of the load.
    EXPECT_NEAR(e0.N[2 * k], d.Nl, 1e-8 * d.P) << k;
    EXPECT_NEAR(e0.N[2 * k + 1], d.Nr, 1e-8 * d.P) << k;
  }
  Matrix A(m, m);
  const double step = 1e-8;
  for (Eigen::Index j = 0; j < m; ++j) {
    auto xp = x, xm = x;
    xp[j] += step;
    xm[j] -= step;
    const Vector ap = sys.evaluate(mode, 0.0, xp).qdd;
    const Vector am = sys.evaluate(mode, 0.0, xm).qdd;
    A.col(j) = (ap - am) / (2 * step);
  }
  Eigen::EigenSolver<Matrix> es(-A);
  std::vector<double> lam;
  for (Eigen::Index k = 0; k < m; ++k) lam.push_back(es.eigenvalues()(k).real());
  std::sort(lam.begin(), lam.end());

  // Hand assembly.
  Matrix M = Matrix::Identity(m, m), K = Matrix::Zero(m, m), G = Matrix::Zero(rows, m);
  K.topLeftCorner(n, n) = d.basis.omega().cwiseAbs2().asDiagonal();
  const Vec2 tl(d.nl.y(), -d.nl.x()), tr(d.nr.y(), -d.nr.x());
  for (Eigen::Index k = 0; k < d.N; ++k) {
    const Eigen::Index o = n + 3 * k;
    M(o, o) = M(o + 1, o + 1) = d.mass;
    M(o + 2, o + 2) = d.inertia;
    K(o + 2, o + 2) = d.Nl * d.nl.dot(d.rl) + d.Nr * d.nr.dot(d.rr);
    auto constraint = [&](Eigen::Index row, NodeId wing, const Vec2& dir, const Vec2& r) {
      G.row(row).head(n) = -d.nodal_row(wing, dir).transpose();
      G(row, o) = dir.x();
      G(row, o + 1) = dir.y();
      G(row, o + 2) = -dir.x() * r.y() + dir.y() * r.x();
    };
    constraint(4 * k + 0, d.right_node(k), d.nl, d.rl);
    constraint(4 * k + 1, d.right_node(k), tl, d.rl);
    constraint(4 * k + 2, d.left_node(k + 1), d.nr, d.rr);
    constraint(4 * k + 3, d.left_node(k + 1), tr, d.rr);
  }
  const Matrix T = G.fullPivLu().kernel();
  ASSERT_EQ(T.cols(), m - rows);
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> ref(T.transpose() * K * T, T.transpose() * M * T);
  // The system's rates hold the 4N zero eigenvalues of the constrained directions, then the
  // m - 4N squared frequencies. Central differences of a solve linear in q and smooth in theta:
  // truncation ~ step^2 and rounding ~ 1e-16 |z''| / step (measured: 1e-11 relative, zeros at
  // 1e-10 of the largest); 1e-6 leaves margin and is far below the preload's rotational
  // stiffness's share of the frequencies.
  const double top = ref.eigenvalues().maxCoeff();
  for (Eigen::Index k = 0; k < rows; ++k) EXPECT_LE(std::abs(lam[static_cast<std::size_t>(k)]), 1e-6 * top) << k;
  for (Eigen::Index k = 0; k < m - rows; ++k) {
    EXPECT_NEAR(lam[static_cast<std::size_t>(k + rows)], ref.eigenvalues()(k), 1e-6 * ref.eigenvalues()(k)) << k;
  }
  // The stuck dampers couple the blades: the lowest stuck frequency lies above the free disk's.
  EXPECT_GT(std::sqrt(ref.eigenvalues()(0)), d.basis.omega()(0));
}

// The stuck disk in static equilibrium, forced at engine order 1 near its resonance: the dampers
// stick and slip (and may lift a face off); the energy audit closes, the body loads' work and the
// stuck projections booked in it.
TEST(DiskDampers, StickSlipRunUnderEngineOrderForcingClosesTheEnergyAudit) {
  const DamperDisk d(4, 3, 0.01, 0.3);
  const double Omega = 1.5 * d.basis.omega()(0);
  const auto loads = engine_order_loads(d.disk, kBladeMember, kBlade, LoadDirection::GlobalX, 15.0, Omega, 1);
  System sys = d.system(loads);
  auto x = d.static_state(sys);
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(x);
  const auto result = simulate(sys, mode, 0.0, x, 3 * 2 * kPi / Omega, contact_samples::tight(0.0));
  ASSERT_EQ(result.status, Status::Success) << result.message;
  EXPECT_GE(sys.events().size(), 8u);  // the faces stick and slip
  const auto bal = sys.energy_balance(result.x, E0);
  EXPECT_GT(bal.friction_dissipation, 0.05 * bal.external_work);
  // rtol 1e-10: the audit integrals carry the integration error, ~1e-9 of the work.
  EXPECT_LE(bal.relative_residual(), 1e-7) << bal.residual << " of " << bal.scale;
}

}  // namespace disk_damper_test

// ---------------------------------------------------------------------------------------------
// Travelling waves

namespace disk_travelling_wave_test {

using namespace disk_samples;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

TEST(DiskTravellingWave, ShiftTimeAndSectorShiftFollowTheEngineOrder) {
  // F_k(t + tau) = F_{k + sigma}(t) checked on the loads themselves for every EO on 6 blades.
  const Disk disk(6, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  const double Omega = 300.0, T = 2 * kPi / Omega;
  for (Eigen::Index eo = -7; eo <= 13; ++eo) {
    const auto s = engine_order_symmetry(eo, 6);
    const auto loads = engine_order_loads(disk, kBladeMember, 0.1, LoadDirection::GlobalX, 1.0, Omega, eo);
    const double tau = T * s.period_fraction();
    EXPECT_EQ(s.shifts_per_period * (s.engine_order == 0 ? 6 : std::gcd(s.engine_order, Eigen::Index(6))), 6);
    for (Eigen::Index k = 0; k < 6; ++k)
      for (double t : {0.0, 0.3 * T, 0.71 * T})
        EXPECT_NEAR(loads[static_cast<std::size_t>(k)].value(t + tau),
                    loads[static_cast<std::size_t>((k + s.sector_shift) % 6)].value(t), 1e-12)
            << "EO = " << eo << ", k = " << k;
  }
}

/// The closed-form steady state [q, q'] at t of the linear disk (basis with modal damping) under
/// the loads F_k = F cos(Omega t + 2 pi EO k / N) at the blade tips along X:
/// q_r = Re(Q_r e^{i Omega t}), Q_r = phi_r^T Fhat / (omega_r^2 - Omega^2 + i c_r Omega).
Vector receptance_state(const Disk& disk, const ModalBasis<double>& basis, double F, double Omega, Eigen::Index eo,
                        double t) {
  const Eigen::Index n = basis.size(), N = disk.num_sectors();
  Eigen::VectorXcd Q(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    std::complex<double> g = 0;
    for (Eigen::Index k = 0; k < N; ++k)
      g += basis.nodal(disk.node(k, kTip), Dof::X)(r) * F * std::polar(1.0, 2 * kPi * double(eo * k) / double(N));
    const double w = basis.omega()(r);
    Q(r) = g / std::complex<double>(w * w - Omega * Omega, basis.damping_coefficients()(r) * Omega);
  }
  const Eigen::VectorXcd e = Q * std::polar(1.0, Omega * t);
  Vector x(2 * n);
  x << e.real(), (std::complex<double>(0, Omega) * e).real();
  return x;
}

// A linear disk (no contacts): the travelling wave at EO 2 on five blades, computed over
// tau = T / 5 only, against the closed-form modal receptance of the annulus (the orbit) and the
// closed-form multipliers of the full period, e^{s T} with s^2 + c s + omega^2 = 0 (modal
// equations uncoupled); the full-annulus check gives the same multipliers.
TEST(DiskTravellingWave, LinearDiskIsTheClosedFormModalReceptance) {
  const Eigen::Index N = 5, eo = 2;
  const Disk disk(N, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  CyclicModalOptions<double> co;
  co.num_modes = 2;
  const ModalBasis<double> basis = annulus_basis(disk, compute_cyclic_modes(disk, co)).with_modal_damping(Vector::Constant(2 * N, 0.02));
  const double Omega = 0.95 * basis.omega()(0), T = 2 * kPi / Omega, F = 2.0;
  const auto loads = engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, F, Omega, eo);
  ContactSystem<double> sys(disk.frame(), basis, {}, loads);
  const Eigen::Index n = basis.size();
  const double t0 = 0.1 * T;
  const Vector expected = receptance_state(disk, basis, F, Omega, eo, t0);

  const auto shift = travelling_wave_shift(disk, basis, sys, eo);
  EXPECT_EQ(shift.symmetry.shifts_per_period, 5);
  EXPECT_EQ(shift.symmetry.sector_shift, 3);  // 2 * 3 = 1 (mod 5)
  TravellingWaveOptions<double> opt;
  opt.full_annulus_check = true;
  TravellingWaveShooting<ContactSystem<double>> tw(sys, shift, opt);
  const auto orbit = tw.solve(sys.requested_mode(), t0, sys.initial_state(), T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  EXPECT_NEAR(orbit.shift_time, T / 5, 1e-15 * T);
  // Newton tolerance 1e-9 of max |x| on x(tau) - S x(0), and the runs' rtol 1e-10: the orbit
  // carries ~1e-9 of its size.
  EXPECT_LE((orbit.x0.head(2 * n) - expected).cwiseAbs().maxCoeff(), 1e-7 * expected.cwiseAbs().maxCoeff());
  // Full-period multipliers: |mu| = e^{-c_r T / 2} (underdamped modes), each twice (s, s*).
  std::vector<double> ref, mine, full;
  for (Eigen::Index r = 0; r < n; ++r)
    for (int twice = 0; twice < 2; ++twice) ref.push_back(std::exp(-basis.damping_coefficients()(r) * T / 2));
  for (Eigen::Index k = 0; k < orbit.floquet.multipliers.size(); ++k) mine.push_back(std::abs(orbit.floquet.multipliers(k)));
  ASSERT_EQ(orbit.check, FloquetCheck::FullAnnulus);
  for (Eigen::Index k = 0; k < orbit.full_floquet.multipliers.size(); ++k)
    full.push_back(std::abs(orbit.full_floquet.multipliers(k)));
  for (auto* v : {&ref, &mine, &full}) std::sort(v->begin(), v->end());
  ASSERT_EQ(mine.size(), ref.size());
  ASSERT_EQ(full.size(), ref.size());
  // The variational runs carry rtol 1e-10 over (a fifth of) the period; M_T = S^L A^L compounds
  // five of them: 1e-7 of the multipliers (all near 1).
  for (std::size_t k = 0; k < ref.size(); ++k) {
    EXPECT_NEAR(mine[k], ref[k], 1e-7) << k;
    EXPECT_NEAR(full[k], ref[k], 1e-7) << k;
  }
  EXPECT_TRUE(orbit.floquet.stable);
  EXPECT_LE(orbit.full_residual, 1e-8 * orbit.x0.cwiseAbs().maxCoeff());
  EXPECT_TRUE(orbit.full_mode_closes);
}

// The frequency sweep of the linear disk's travelling waves (secant predictor between points)
// against the closed-form receptance at every frequency, t0 = 0.
TEST(DiskTravellingWave, FrequencySweepFollowsTheClosedFormReceptance) {
  const Eigen::Index N = 4, eo = 1;
  const Disk disk(N, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  CyclicModalOptions<double> co;
  co.num_modes = 1;
  const ModalBasis<double> basis = annulus_basis(disk, compute_cyclic_modes(disk, co)).with_modal_damping(Vector::Constant(N, 0.02));
  const double F = 2.0, w1 = basis.omega()(1);
  using System = ContactSystem<double>;
  const std::function<System(double)> make = [&](double Omega) {
    return System(disk.frame(), basis, {}, engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, F, Omega, eo));
  };
  const std::function<TravellingWaveShift<double>(const System&)> shift = [&](const System& s) {
    return travelling_wave_shift(disk, basis, s, eo);
  };
  const std::vector<double> omegas{0.9 * w1, 0.95 * w1, 1.0 * w1, 1.05 * w1};
  const System first = make(omegas[0]);
  int calls = 0;
  const auto points = travelling_wave_sweep<System>(make, shift, omegas, first.requested_mode(), first.initial_state(), {},
                                                    [&](const TravellingWaveSweepPoint<System>&) { ++calls; });
  ASSERT_EQ(points.size(), omegas.size());
  EXPECT_EQ(calls, 4);
  for (const auto& p : points) {
    ASSERT_TRUE(p.orbit.ok()) << p.orbit.message;
    const Vector expected = receptance_state(disk, basis, F, p.omega, eo, 0.0);
    // As the single orbit: Newton tolerance 1e-9 and rtol 1e-10 of the state's size.
    EXPECT_LE((p.orbit.x0.head(2 * N) - expected).cwiseAbs().maxCoeff(), 1e-7 * expected.cwiseAbs().maxCoeff())
        << "Omega = " << p.omega;
  }
  // The secant predictor lands closer than the previous point: the last solves need fewer runs
  // than the first from rest would (a linear problem converges in one Newton step either way).
  EXPECT_LE(points.back().orbit.iterations, points.front().orbit.iterations);
}


// The travelling-wave shift of a disk with wedge dampers (bodies and contacts permuted with the
// blades): the system is equivariant, rhs(S m, t + tau, S x) = S rhs(m, t, x), at a state with
// every coordinate and rate set and a mode with every contact in another state; the solver's
// symmetry check refuses loads of another engine order.
TEST(DiskTravellingWave, WedgeDamperDiskIsEquivariantUnderTheShift) {
  using System = ContactSystem<double, BodyContact<double>>;
  const disk_damper_test::DamperDisk d(4, 2, 0.01, 0.3);
  const Eigen::Index eo = 3;  // on four blades: sigma = 3, tau = T / 4
  const double Omega = 1.1 * d.basis.omega()(0), T = 2 * kPi / Omega;
  System sys = d.system(engine_order_loads(d.disk, kBladeMember, kBlade, LoadDirection::GlobalX, 15.0, Omega, eo));
  const auto shift = travelling_wave_shift(d.disk, d.basis, sys, eo);
  EXPECT_EQ(shift.symmetry.sector_shift, 3);
  EXPECT_EQ(shift.symmetry.shifts_per_period, 4);
  auto x = d.static_state(sys);
  for (Eigen::Index i = 0; i < 2 * sys.num_coordinates(); ++i) x[i] += 1e-6 * std::sin(1.0 + 3.0 * double(i));
  auto mode = sys.requested_mode();
  const ContactState states[3] = {ContactState::Stick, ContactState::SlipPositive, ContactState::SlipNegative};
  for (Eigen::Index i = 0; i < sys.num_contacts(); ++i) mode[i] = states[i % 3];
  const double t = 0.3 * T;
  Vector a(sys.state_size()), b(sys.state_size());
  sys.rhs(mode, t, x, a);
  sys.rhs(shift.shifted(mode), t + T / 4, Vector(shift.state * x), b);
  const Vector expected = shift.state * a;
  // Round-off of the dense modal shift on the largest terms (omega^2 q): 1e-10 of them.
  EXPECT_LE((b - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
  // The body block is a permutation: body 0 takes body 3's place (k + sigma = 3).
  const Eigen::Index n = d.basis.size();
  EXPECT_EQ(shift.state(n + 0, n + 9), 1.0);
  EXPECT_EQ(shift.contact_source[0], 6);
  // Loads of EO 1 are not symmetric under the EO 3 shift: refused before any run.
  System other = d.system(engine_order_loads(d.disk, kBladeMember, kBlade, LoadDirection::GlobalX, 15.0, Omega, 1));
  TravellingWaveShooting<System> tw(other, shift);
  contact_test::expect_invalid_argument([&] { tw.solve(sys.requested_mode(), 0.0, d.static_state(other), T); },
                                        {"TravellingWaveShooting", "symmetry"});
}

/// Max |tip X displacement| of each blade over the samples of a run.
Vector tip_amplitudes(const Disk& disk, const ModalBasis<double>& basis, const contact_samples::Samples& rec) {
  Vector a = Vector::Zero(disk.num_sectors());
  for (const auto& x : rec.x)
    for (Eigen::Index k = 0; k < disk.num_sectors(); ++k)
      a(k) = std::max(a(k), std::abs(basis.nodal(disk.node(k, kTip), Dof::X).dot(x.head(basis.size()))));
  return a;
}

// Three blades with friction joints between the platforms that stick and slip under engine
// order 1: the travelling wave computed over tau = T / 3 against (a) the annulus shot over the
// full period by Shooting from the same guess (the same orbit to the Newton tolerance, the same
// leading multiplier, and the full-annulus check) and (b) a long transient of the annulus from
// rest (the tip amplitudes of every blade).
TEST(DiskTravellingWave, StickSlipWaveEqualsFullAnnulusShootingAndTheLongTransient) {
  using System = ContactSystem<double>;
  const Eigen::Index N = 3, eo = 1;
  const Disk disk(N, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  CyclicModalOptions<double> co;
  co.num_modes = 2;
  const auto cm = compute_cyclic_modes(disk, co);
  const ModalBasis<double> basis = annulus_basis(disk, cm).with_modal_damping(Vector::Constant(2 * N, 0.02));
  const double Omega = cm.families[1].omega(0), T = 2 * kPi / Omega;
  const auto loads = engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, 20.0, Omega, eo);
  const auto joints = neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0},
                                       PlaneDirection<double>::at_angle(0.6), CoulombLaw<double>(0.4, 0.3), 20.0);
  System sys(disk.frame(), basis, joints, loads);
  auto x = sys.initial_state();
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  // The orbit's leading multiplier is 0.90 per period: after K = 100 periods the transient is
  // 0.9^100 ~ 3e-5 of its start away from it.
  const int K = 100;
  const auto transient = simulate(sys, mode, 0.0, x, K * T, contact_samples::tight(0.0));
  ASSERT_EQ(transient.status, Status::Success) << transient.message;
  contact_samples::Samples last;
  const auto tail = simulate(sys, transient.mode, K * T, transient.x, (K + 1) * T, contact_samples::tight(T / 402), last);
  ASSERT_EQ(tail.status, Status::Success) << tail.message;
  const Vector transient_tips = tip_amplitudes(disk, basis, last);

  const auto shift = travelling_wave_shift(disk, basis, sys, eo);
  TravellingWaveOptions<double> opt;
  opt.full_annulus_check = true;
  TravellingWaveShooting<System> tw(sys, shift, opt);
  const auto orbit = tw.solve(transient.mode, K * T, transient.x, T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  EXPECT_GE(orbit.events.size(), 2u);  // the joints stick and slip within tau

  Shooting<System> full(sys, tw.options().shooting);
  const auto closed = full.forced(transient.mode, K * T, transient.x, T);
  ASSERT_TRUE(closed.ok()) << closed.message;
  const Eigen::Index p = 2 * sys.num_coordinates();
  const double scale = closed.x0.head(p).cwiseAbs().maxCoeff();
  // Two Newton solves to 1e-9 of max |x| on runs of rtol 1e-10: the orbits agree to a few times that.
  EXPECT_LE((orbit.x0.head(p) - closed.x0.head(p)).cwiseAbs().maxCoeff(), 1e-7 * scale);
  ASSERT_EQ(orbit.check, FloquetCheck::FullAnnulus);
  EXPECT_LE(orbit.full_residual, 1e-8 * scale);
  EXPECT_TRUE(orbit.full_mode_closes);
  EXPECT_EQ(orbit.floquet.stable, closed.floquet.stable);
  // The leading multiplier (0.90) from M_T = S^L A^L, from the full-annulus check and from
  // Shooting's own monodromy: variational runs at rtol 1e-10 with saltation matrices at the
  // events, ~1e-8 apart; 1e-6 leaves margin.
  EXPECT_NEAR(orbit.floquet.max_modulus, closed.floquet.max_modulus, 1e-6);
  EXPECT_NEAR(orbit.full_floquet.max_modulus, closed.floquet.max_modulus, 1e-6);
  EXPECT_LT(orbit.floquet.max_modulus, 0.99);

  contact_samples::Samples rec;
  System copy = sys;
  const auto one = simulate(copy, orbit.mode, orbit.t0, orbit.x0, orbit.t0 + T, contact_samples::tight(T / 402), rec);
  ASSERT_EQ(one.status, Status::Success) << one.message;
  const Vector tips = tip_amplitudes(disk, basis, rec);
  // The transient's distance from the orbit (~3e-5, above): 1e-3 of the amplitude.
  EXPECT_LE((tips - transient_tips).cwiseAbs().maxCoeff(), 1e-3 * tips.maxCoeff());
  // A travelling wave: every blade has the same amplitude. The samples every T / 402 put blade
  // k + 1's samples tau = 134 samples later on the same phases as blade k's, so the sampled
  // maxima agree to the orbit's closure (Newton tolerance 1e-9 of max |x|, velocities included).
  EXPECT_LE(tips.maxCoeff() - tips.minCoeff(), 1e-6 * tips.maxCoeff());
  // The orbit is the annulus' travelling wave and not a standing one: tau, not T.
  EXPECT_EQ(orbit.symmetry.shifts_per_period, 3);
}

}  // namespace disk_travelling_wave_test

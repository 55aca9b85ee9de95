// Bladed disks: the annulus assembly against the same disk built by hand, cyclic-symmetry modes
// against the full annulus' modes (compute_modes, a different solver on a different matrix),
// engine-order forcing against the closed-form modal receptance, the nodal-diameter content of
// the forced response by a discrete Fourier transform over the blades, bad input, and a
// frictional disk through simulate() with its energy audit.

#include <stickslip/disk.hpp>
#include <stickslip/stickslip.hpp>
#include "contact/contact_test_util.hpp"
#include "disk/disk_samples.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <utility>
#include <vector>

namespace bladed_disk_test {

using namespace stickslip;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using namespace disk_samples;

/// Springs between neighbouring platform wings of the order of the blade's tip stiffness
/// 3 EI / L^3 = 7.5e4 N/m, so that the families split clearly.
SectorCoupling<double> springs() { return SectorCoupling<double>::springs(5e4, 2e4, 50.0); }
SectorCoupling<double> ring() { return SectorCoupling<double>::ring_member(kSection); }

Vector sorted(Vector v) {
  std::sort(v.data(), v.data() + v.size());
  return v;
}

/// Every cyclic frequency with its multiplicity in the annulus (pairs twice), ascending.
Vector cyclic_spectrum(const CyclicModes<double>& cm) {
  std::vector<double> all;
  for (const auto& f : cm.families)
    for (Eigen::Index j = 0; j < f.omega.size(); ++j)
      for (int m = 0; m < (f.pairs ? 2 : 1); ++m) all.push_back(f.omega(j));
  return sorted(Eigen::Map<Vector>(all.data(), static_cast<Eigen::Index>(all.size())));
}

Vector annulus_omegas(const AssembledFrame<double>& fe) {
  ModalOptions<double> mo;
  mo.num_modes = fe.num_free();
  mo.solver = ModalSolver::Dense;
  return compute_modes(fe, mo).omega();
}

double max_relative_difference(const Vector& a, const Vector& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0;
  for (Eigen::Index i = 0; i < std::min(a.size(), b.size()); ++i)
    worst = std::max(worst, std::abs(a(i) - b(i)) / b(i));
  return worst;
}

CyclicModalOptions<double> all_modes() {
  CyclicModalOptions<double> o;
  o.num_modes = 1000;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Cyclic symmetry against the full annulus

TEST(DiskCyclicModes, FrequenciesAndPairsMatchTheFullAnnulus) {
  for (Eigen::Index N : {6, 7}) {
    for (const auto& coupling : {springs(), ring()}) {
      const Disk disk(N, kPitch, builder(), coupling);
      const auto cm = compute_cyclic_modes(disk, all_modes());
      ASSERT_EQ(cm.families.size(), static_cast<std::size_t>(N / 2 + 1));
      const Vector full = annulus_omegas(disk.assemble());
      // Every annulus mode is in exactly one family: the spectra agree with multiplicity. Both
      // are dense solves with eigenvalue errors ~eps lambda_max / lambda ~ 2e-11 (kSection).
      EXPECT_LE(max_relative_difference(cyclic_spectrum(cm), full), 1e-9) << "N = " << N;
      // Degenerate pairs: each frequency of 0 < h < N/2 occurs twice in the annulus.
      for (const auto& f : cm.families) {
        EXPECT_EQ(f.pairs, f.nodal_diameter > 0 && 2 * f.nodal_diameter < N);
        for (Eigen::Index j = 0; j < f.omega.size(); ++j) {
          const auto near = (((full.array() - f.omega(j)).abs() / f.omega(j)) <= 1e-9).count();
          EXPECT_GE(near, f.pairs ? 2 : 1) << "h = " << f.nodal_diameter << ", mode " << j;
        }
      }
    }
  }
}

TEST(DiskCyclicModes, ExpandedModesAreMassNormalisedEigenvectorsOfTheAnnulus) {
  const Disk disk(6, kPitch, builder(), ring());
  CyclicModalOptions<double> o;
  o.num_modes = 3;
  const auto cm = compute_cyclic_modes(disk, o);
  const ModalBasis<double> basis = annulus_basis(disk, cm);
  EXPECT_EQ(basis.size(), 3 * (2 + 2 * 2));  // h = 0, 3 single; h = 1, 2 pairs
  const auto fe = disk.assemble();
  const Matrix K(fe.stiffness), M(fe.mass), phi = basis.phi();
  // Phi^T M Phi = I and the residual K phi - omega^2 M phi against the annulus' own K and M,
  // relative to omega^2 (round-off of the dense solve and the expansion, ~1e-13).
  EXPECT_LE((phi.transpose() * M * phi - Matrix::Identity(phi.cols(), phi.cols())).cwiseAbs().maxCoeff(), 1e-10);
  for (Eigen::Index j = 0; j < basis.size(); ++j) {
    const double w2 = basis.omega()(j) * basis.omega()(j);
    const Vector r = K * phi.col(j) - w2 * M * phi.col(j);
    EXPECT_LE(r.norm() / (w2 * (M * phi.col(j)).norm()), 1e-9) << "mode " << j;
  }
  // The basis serves ContactSystem: its model id is the disk's frame's.
  EXPECT_EQ(basis.model_id(), disk.frame().id());
}

// ---------------------------------------------------------------------------------------------
// N = 2 and N = 3 against the disk built by hand

/// K and M of the N-sector disk built by hand: the sectors side by side in one frame, the ring
/// segments k -> k + 1 as ordinary one-element members, the wrap-around segment (its end lies
/// beyond the last sector in the unrolled plane) and the springs added to the assembled matrices.
std::pair<Matrix, Matrix> hand_built(int N, const SectorCoupling<double>& c) {
  FrameModel<double> f;
  for (int k = 0; k < N; ++k) build_sector(f, Vector2(k * kPitch, 0));
  const int P = 7;  // nodes per sector: left, right, mid, root and the blade's 3 interior nodes
  if (c.ring)
    for (int k = 0; k + 1 < N; ++k) f.add_member(NodeId(k * P + 1), NodeId((k + 1) * P + 0), *c.ring, 1);
  const auto fe = f.assemble();
  Matrix K(fe.stiffness), M(fe.mass);
  const auto scatter = [&](NodeId a, NodeId b, const Eigen::Matrix<double, 6, 6>& ke,
                           const Eigen::Matrix<double, 6, 6>& me) {
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) {
        const auto fr = fe.dofs.free_index(r < 3 ? a : b, static_cast<Dof>(r % 3));
        const auto fs = fe.dofs.free_index(s < 3 ? a : b, static_cast<Dof>(s % 3));
        K(fr, fs) += ke(r, s);
        M(fr, fs) += me(r, s);
      }
  };
  if (c.ring) {
    const FrameElement<double> wrap(kPitch - kPlatform, 1.0, 0.0, *c.ring);  // right wing -> next left wing
    scatter(NodeId((N - 1) * P + 1), NodeId(0), wrap.global_stiffness(), wrap.global_mass());
  }
  const double k[3] = {c.k_x, c.k_y, c.k_rz};
  for (int s = 0; s < N; ++s)
    for (int d = 0; d < 3; ++d) {
      const auto a = fe.dofs.free_index(NodeId(s * P + 1), static_cast<Dof>(d));
      const auto b = fe.dofs.free_index(NodeId(((s + 1) % N) * P + 0), static_cast<Dof>(d));
      K(a, a) += k[d];
      K(b, b) += k[d];
      K(a, b) -= k[d];
      K(b, a) -= k[d];
    }
  return {K, M};
}

TEST(DiskAssembly, TwoAndThreeSectorsEqualTheDiskBuiltByHand) {
  for (int N : {2, 3}) {
    SectorCoupling<double> both = springs();
    both.ring = kSection;
    for (const auto& coupling : {springs(), ring(), both}) {
      const Disk disk(N, kPitch, builder(), coupling);
      const auto fe = disk.assemble();
      const auto [K, M] = hand_built(N, coupling);
      // The same element matrices summed in another order: round-off of the largest entry.
      EXPECT_LE((Matrix(fe.stiffness) - K).cwiseAbs().maxCoeff(), 1e-13 * K.cwiseAbs().maxCoeff()) << "N = " << N;
      EXPECT_LE((Matrix(fe.mass) - M).cwiseAbs().maxCoeff(), 1e-13 * M.cwiseAbs().maxCoeff()) << "N = " << N;
      // Cyclic modes (N = 2: h = 0, 1, both real; N = 3: h = 0 and the pair h = 1) against the
      // hand-built disk's modes by a plain dense generalised eigen solve.
      const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> es(K, M, Eigen::EigenvaluesOnly);
      const Vector reference = es.eigenvalues().cwiseSqrt();
      EXPECT_LE(max_relative_difference(cyclic_spectrum(compute_cyclic_modes(disk, all_modes())), reference), 1e-9)
          << "N = " << N;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Engine-order forcing

/// Spatial DFT over the blades of a nodal vector (3 P entries per sector): the norm of each
/// harmonic h = 0 ... N - 1, sum_k u_k e^{-i 2 pi h k / N}.
Vector harmonic_norms(const Disk& disk, const Vector& nodal) {
  const Eigen::Index N = disk.num_sectors(), S = 3 * disk.nodes_per_sector();
  Vector out(N);
  for (Eigen::Index h = 0; h < N; ++h) {
    Eigen::VectorXcd sum = Eigen::VectorXcd::Zero(S);
    for (Eigen::Index k = 0; k < N; ++k)
      sum += nodal.segment(k * S, S).cast<std::complex<double>>() * std::polar(1.0, -2 * kPi * double(h * k) / double(N));
    out(h) = sum.norm();
  }
  return out;
}

TEST(DiskEngineOrder, ForcedResponseIsTheModalReceptanceInTheExcitedFamilyOnly) {
  const Eigen::Index N = 6;
  const Disk disk(N, kPitch, builder(), springs());
  ModalOptions<double> mo;
  mo.num_modes = disk.annulus_dofs().num_free();
  mo.solver = ModalSolver::Dense;
  const double zeta = 0.02;
  // All modes of the annulus, independently of the disk's own cyclic solver.
  const ModalBasis<double> basis = compute_modes(disk.assemble(), mo).with_modal_damping(Vector::Constant(mo.num_modes, zeta));
  const double F = 2.0;
  for (Eigen::Index eo : {2, 8, -4, 3}) {  // 8 and -4 alias to 2 on six blades; 3 = N/2
    const Eigen::Index h = engine_order_nodal_diameter(eo, N);
    // Near the first frequency of family h, where the forced response is largest.
    const auto cm = compute_cyclic_modes(disk);
    const double Omega = 0.97 * cm.families[static_cast<std::size_t>(h)].omega(0);
    const auto loads = engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, F, Omega, eo);
    ASSERT_EQ(loads.size(), static_cast<std::size_t>(N));
    // Closed form: F_k(t) = Re(F e^{i 2 pi EO k / N} e^{i Omega t}) at the blade tip's X, so
    // q_r = Re(Q_r e^{i Omega t}), Q_r = phi_r^T Fhat / (omega_r^2 - Omega^2 + i c_r Omega).
    Eigen::VectorXcd Q(basis.size());
    for (Eigen::Index r = 0; r < basis.size(); ++r) {
      std::complex<double> g = 0;
      for (Eigen::Index k = 0; k < N; ++k)
        g += basis.nodal(disk.node(k, kTip), Dof::X)(r) * F * std::polar(1.0, 2 * kPi * double(eo * k) / double(N));
      const double w = basis.omega()(r);
      Q(r) = g / std::complex<double>(w * w - Omega * Omega, basis.damping_coefficients()(r) * Omega);
    }
    const auto closed_form = [&](double t) {
      const Eigen::VectorXcd e = Q * std::polar(1.0, Omega * t);
      Vector x(2 * basis.size());
      x << e.real(), (std::complex<double>(0, Omega) * e).real();
      return x;
    };
    // The library's linear model driven by the loads, started on the closed-form orbit: it stays
    // on it only if every load has the closed form's phase and direction (a wrong one would start
    // a free vibration of the size of the response).
    ContactSystem<double> sys(disk.frame(), basis, {}, loads);
    ContactSystem<double>::State x0 = sys.initial_state();
    x0.head(2 * basis.size()) = closed_form(0.0);
    RunOptions<double> run;
    // Named: Integrator::Auto would pick the exponential method for this linear scene, whose
    // grid follows the annulus' highest retained mode (all modes here) with exponentials of a
    // large matrix, minutes under the sanitizers against a second for Dormand-Prince.
    run.integrator = Integrator::DormandPrince54;
    run.stepper.rtol = 1e-10;
    run.stepper.atol = 1e-14;
    const double t_end = 2 * 2 * kPi / Omega;
    const auto result = simulate(sys, sys.requested_mode(), 0.0, x0, t_end, run);
    ASSERT_EQ(result.status, Status::Success) << result.message;
    const Vector expected = closed_form(t_end);
    // rtol 1e-10 over two periods: the state's error stays ~1e-9 of its size.
    EXPECT_LE((result.x.head(2 * basis.size()) - expected).norm(), 1e-7 * expected.norm()) << "EO = " << eo;
    // Only the harmonics +-EO (mod N) of the blade displacements respond; the others carry the
    // round-off of phi_r^T Fhat (~1e-16 relative), and the modal equations are uncoupled, so the
    // integration error does not leak between families.
    const Vector norms = harmonic_norms(disk, basis.nodal_displacements(result.x.head(basis.size())));
    const Eigen::Index r = reduced_engine_order(eo, N);
    for (Eigen::Index g = 0; g < N; ++g) {
      if (g == r || g == (N - r) % N) EXPECT_GT(norms(g), 0.1 * norms.maxCoeff()) << "EO = " << eo << ", h = " << g;
      else EXPECT_LE(norms(g), 1e-10 * norms.maxCoeff()) << "EO = " << eo << ", h = " << g;
    }
  }
}

TEST(DiskEngineOrder, AliasedAndNegativeOrdersGiveTheSameLoads) {
  const Disk disk(6, kPitch, builder(), springs());
  EXPECT_EQ(reduced_engine_order(-1, 6), 5);
  EXPECT_EQ(engine_order_nodal_diameter(-1, 6), 1);
  EXPECT_EQ(engine_order_nodal_diameter(9, 6), 3);
  EXPECT_EQ(engine_order_nodal_diameter(7, 6), 1);
  const auto a = engine_order_loads(disk, kBladeMember, 0.1, LoadDirection::GlobalX, 1.0, 300.0, 2);
  const auto b = engine_order_loads(disk, kBladeMember, 0.1, LoadDirection::GlobalX, 1.0, 300.0, 14);
  const auto c = engine_order_loads(disk, kBladeMember, 0.1, LoadDirection::GlobalX, 1.0, 300.0, -10);
  for (std::size_t k = 0; k < a.size(); ++k)
    for (double t : {0.0, 1e-3, 7e-3}) {
      // F_k(t) = cos(Omega t + 2 pi 2 k / 6) from the formula, against each load's value.
      const double expected = std::cos(300.0 * t + 2 * kPi * 2.0 * double(k) / 6.0);
      EXPECT_NEAR(a[k].value(t), expected, 1e-14);
      EXPECT_NEAR(b[k].value(t), expected, 1e-14);
      EXPECT_NEAR(c[k].value(t), expected, 1e-14);
      EXPECT_EQ(a[k].member, disk.member(static_cast<Eigen::Index>(k), kBladeMember));
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input

template <class F>
void expect_refused(F&& f, const std::string& what) {
  contact_test::expect_invalid_argument(std::forward<F>(f), {what.c_str()});
}

TEST(DiskInputs, BadInputIsRefusedNamingTheParameter) {
  expect_refused([] { Disk(1, kPitch, builder(), springs()); }, "num_sectors");
  expect_refused([] { Disk(4, kPlatform, builder(), springs()); }, "pitch");
  expect_refused([] { Disk(4, std::nan(""), builder(), springs()); }, "pitch");
  expect_refused([] { Disk(4, kPitch, Disk::SectorBuilder{}, springs()); }, "builder");
  expect_refused([] { Disk(4, kPitch, builder(), SectorCoupling<double>{}); }, "coupling");
  expect_refused([] { Disk(4, kPitch, builder(), SectorCoupling<double>::springs(-1, 0, 0)); }, "coupling.k_x");
  expect_refused(
      [] {
        Disk(4, kPitch,
             [](FrameModel<double>& f, const SectorPlacement<double>& p) {
               auto a = build_sector(f, p.origin);
               a.left = -1;
               return a;
             },
             springs());
      },
      "attachments.left");
  expect_refused(
      [] {
        Disk(4, kPitch,
             [](FrameModel<double>& f, const SectorPlacement<double>& p) {
               auto a = build_sector(f, p.origin);
               a.right = 99;
               return a;
             },
             springs());
      },
      "attachments.right");
  // A builder that ignores the placement (every sector at the origin) collides with sector 0.
  expect_refused(
      [] {
        Disk(3, kPitch, [](FrameModel<double>& f, const SectorPlacement<double>& p) {
          return build_sector(f, Vector2(p.index == 2 ? 0.001 + 2 * kPitch : p.origin.x(), 0));
        }, springs());
      },
      "sector 2");
  const Disk disk(4, kPitch, builder(), springs());
  expect_refused([&] { engine_order_loads(disk, MemberId(2), 0.1, LoadDirection::GlobalX, 1.0, 300.0, 1); },
                 "sector_member");
  expect_refused([&] { engine_order_loads(disk, kBladeMember, 0.1, LoadDirection::GlobalX, std::nan(""), 300.0, 1); },
                 "amplitude");
  expect_refused([&] { disk.node(4, 0); }, "sector index k");
  expect_refused([] { Disk(5, kPitch, builder(), springs(), std::vector<double>(3, 0.0)); }, "mistuning.size()");
  expect_refused([] { Disk(3, kPitch, builder(), springs(), {0.0, 0.1, -1.0}); }, "mistuning[2]");
  expect_refused([] { compute_cyclic_modes(Disk(3, kPitch, builder(), springs(), {0.0, 0.1, 0.0})); }, "mistuning");
  expect_refused([] { draw_mistuning<double>(3, -0.1, 1); }, "sigma");
  CyclicModalOptions<double> o;
  o.num_modes = 0;
  expect_refused([&] { compute_cyclic_modes(disk, o); }, "options.num_modes");
  expect_refused([&] {
    neighbour_joints(disk, {kPlatformMember, kPlatform}, {MemberId(5), 0.0}, PlaneDirection<double>::global_x(),
                     CoulombLaw<double>(0.3, 0.3), 10.0);
  }, "left_wing.member");
  expect_refused([&] {
    neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0}, PlaneDirection<double>::global_x(),
                     CoulombLaw<double>(0.3, 0.3), 0.0);
  }, "normal");
}

// ---------------------------------------------------------------------------------------------
// Mistuning

TEST(DiskMistuning, ZeroDeltasGiveTheTunedDiskAndEachDeltaScalesItsSector) {
  const Eigen::Index N = 5;
  const Disk tuned(N, kPitch, builder(), springs());
  const Disk zero(N, kPitch, builder(), springs(), std::vector<double>(N, 0.0));
  EXPECT_TRUE(zero.is_tuned());
  const auto t = tuned.assemble(), z = zero.assemble();
  EXPECT_EQ((Matrix(t.stiffness) - Matrix(z.stiffness)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((Matrix(t.mass) - Matrix(z.mass)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE(max_relative_difference(cyclic_spectrum(compute_cyclic_modes(zero, all_modes())),
                                    cyclic_spectrum(compute_cyclic_modes(tuned, all_modes()))), 0.0);

  const auto sample = draw_mistuning<double>(N, 0.05, 42);
  const Disk mistuned(N, kPitch, builder(), springs(), sample.deltas);
  EXPECT_FALSE(mistuned.is_tuned());
  // Element stiffness is linear in E and the sectors' own K is block diagonal (the coupling is
  // the same in both disks): K_mistuned - K_tuned = diag(delta of each DOF's sector) K_sectors,
  // to the round-off of the products.
  const Matrix sectors(tuned.frame().assemble().stiffness);
  Matrix expected = sectors;
  for (Eigen::Index i = 0; i < expected.rows(); ++i) {
    const auto node = tuned.annulus_dofs().node_dof(i).first;
    expected.row(i) *= sample.deltas[static_cast<std::size_t>(node / tuned.nodes_per_sector())];
  }
  const auto m = mistuned.assemble();
  EXPECT_LE((Matrix(m.stiffness) - Matrix(t.stiffness) - expected).cwiseAbs().maxCoeff(),
            1e-13 * sectors.cwiseAbs().maxCoeff());
  EXPECT_EQ((Matrix(m.mass) - Matrix(t.mass)).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DiskMistuning, DrawsAreReproducibleFromTheSeedWithTheRequestedScatter) {
  const auto a = draw_mistuning<double>(7, 0.03, 2024), b = draw_mistuning<double>(7, 0.03, 2024);
  const auto c = draw_mistuning<double>(7, 0.03, 2025);
  EXPECT_EQ(a.deltas, b.deltas);
  EXPECT_NE(a.deltas, c.deltas);
  EXPECT_EQ(a.seed, 2024u);
  // 20000 draws: mean and standard deviation within four standard errors (sigma / sqrt(n) and
  // sigma / sqrt(2 n)) of 0 and sigma; the seed is fixed, so this is deterministic.
  const auto big = draw_mistuning<double>(20000, 0.1, 7);
  const Eigen::Map<const Vector> d(big.deltas.data(), 20000);
  const double mean = d.mean(), sd = std::sqrt((d.array() - mean).square().sum() / double(d.size() - 1));
  EXPECT_LE(std::abs(mean), 4 * 0.1 / std::sqrt(20000.0));
  EXPECT_LE(std::abs(sd - 0.1), 4 * 0.1 / std::sqrt(40000.0));
}

// ---------------------------------------------------------------------------------------------
// A frictional disk

TEST(DiskFriction, NeighbourJointsRunThroughSimulateWithAClosedEnergyAudit) {
  const Eigen::Index N = 4;
  const Disk disk(N, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  CyclicModalOptions<double> o;
  o.num_modes = 3;  // per nodal diameter: whole families, no pair split
  const auto cm = compute_cyclic_modes(disk, o);
  const ModalBasis<double> basis = annulus_basis(disk, cm).with_modal_damping(Vector::Constant(3 * N, 0.005));
  const double Omega = cm.families[1].omega(0);  // resonance of the EO 1 family
  const auto loads = engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, 20.0, Omega, 1);
  // Inclined faces (as the paper's damper): along X alone the N joints' rows sum to the
  // platforms' axial stretch, which the retained modes lack, and all-stuck rows are dependent.
  const auto joints = neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0},
                                       PlaneDirection<double>::at_angle(0.6), CoulombLaw<double>(0.4, 0.3), 20.0);
  ContactSystem<double> sys(disk.frame(), basis, joints, loads);
  auto x = sys.initial_state();
  auto mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  RunOptions<double> run;
  run.stepper.rtol = 1e-9;
  run.stepper.atol = 1e-13;
  const auto result = simulate(sys, mode, 0.0, x, 20 * 2 * kPi / Omega, run);
  ASSERT_EQ(result.status, Status::Success) << result.message;
  EXPECT_GE(sys.events().size(), 8u);  // the joints stick and slip
  const auto b = sys.energy_balance(result.x, 0.0);
  EXPECT_GT(b.friction_dissipation, 0.05 * b.external_work);
  // rtol 1e-9: the audit integrals carry the integration error, ~1e-8 of the work.
  EXPECT_LE(b.relative_residual(), 1e-6);
}


// Integrator::Auto on a disk with neighbour joints (every mode exactly linear): the exponential
// method while its linear part is of order d = 2 x modes <= 64, Dormand-Prince above
// (detail::kExponentialMaxOrder: a new mode's propagators cost O(d^3); measured on the example's
// disk, Dormand-Prince was 17x to 116x cheaper at d = 72 to 288). Four sectors with 3 modes per
// family (d = 24) and with 9 (d = 72); the larger one's Auto run equals Dormand-Prince's run
// named explicitly (same final state to the bit, same counters), a short run from a state away
// from rest through a few stick-slip events.
TEST(DiskFriction, AutoTakesDormandPrinceWhereTheLinearPartIsLarge) {
  const Disk disk(4, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  const auto joints = neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0},
                                       PlaneDirection<double>::at_angle(0.6), CoulombLaw<double>(0.4, 0.3), 20.0);
  auto system = [&](Eigen::Index per_family) {
    CyclicModalOptions<double> o;
    o.num_modes = per_family;
    const ModalBasis<double> basis = annulus_basis(disk, compute_cyclic_modes(disk, o))
                                         .with_modal_damping(Vector::Constant(4 * per_family, 0.005));
    return ContactSystem<double>(disk.frame(), basis, joints);
  };
  for (const Eigen::Index per_family : {Eigen::Index(3), Eigen::Index(9)}) {
    ContactSystem<double> sys = system(per_family);
    auto x = sys.initial_state();
    for (Eigen::Index j = 0; j < sys.num_modes(); ++j) x[j] = 2e-5 * std::sin(0.7 * double(j + 1));
    auto mode = sys.requested_mode();
    ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
    const IntegratorChoice choice = choose_integrator(sys, mode, 0.0, x, 0.01, 1e-6);
    if (per_family == 3) {
      EXPECT_EQ(choice.integrator, Integrator::Exponential) << choice.reason;
      continue;
    }
    EXPECT_EQ(choice.integrator, Integrator::DormandPrince54) << choice.reason;
    EXPECT_NE(choice.reason.find("order 72 is above 64"), std::string::npos) << choice.reason;
    ContactSystem<double> named = system(per_family);
    RunOptions<double> run;
    const auto ra = simulate(sys, mode, 0.0, x, 0.01, run);
    run.integrator = Integrator::DormandPrince54;
    const auto rb = simulate(named, mode, 0.0, x, 0.01, run);
    ASSERT_EQ(ra.status, Status::Success) << ra.message;
    EXPECT_EQ(ra.method, "dopri5") << ra.method_reason;
    EXPECT_EQ(ra.x, rb.x);
    EXPECT_EQ(ra.stats.accepted_steps, rb.stats.accepted_steps);
    EXPECT_EQ(ra.stats.events, rb.stats.events);
    EXPECT_GE(ra.stats.events, 2) << "the joints must slip and stick";
  }
}

// ExactLinearStepper's deferred ladders on the same disk with 9 modes per family (Â of order
// 2 x 36 + 3 audit integrals + 1 clock = 76 > eager_ladder_order): a mode that ends within its
// first 76 grid steps never computes its propagators, and the run differs from the one with
// eager ladders by round-off only. Reference: the same run with set_deferred_ladders(false).
TEST(DiskFriction, DeferredLaddersGiveTheEagerRunWithFewerExponentials) {
  const Disk disk(4, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  const auto joints = neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0},
                                       PlaneDirection<double>::at_angle(0.6), CoulombLaw<double>(0.4, 0.3), 20.0);
  CyclicModalOptions<double> o;
  o.num_modes = 9;
  const ModalBasis<double> basis =
      annulus_basis(disk, compute_cyclic_modes(disk, o)).with_modal_damping(Vector::Constant(36, 0.005));
  struct Run {
    ExactLinearStepper<ContactSystem<double>>::Result result;
    ExactStepperStats work;
    std::vector<double> times;
  };
  auto run = [&](bool deferred) {
    ContactSystem<double> sys(disk.frame(), basis, joints);
    auto x = sys.initial_state();
    for (Eigen::Index j = 0; j < sys.num_modes(); ++j) x[j] = 2e-5 * std::sin(0.7 * double(j + 1));
    auto mode = sys.requested_mode();
    EXPECT_TRUE(sys.make_consistent(mode, 0.0, x));
    ExactLinearStepper<ContactSystem<double>> stepper(sys);
    stepper.set_deferred_ladders(deferred);
    Run r;
    r.result = stepper.integrate(mode, 0.0, x, 0.002);
    r.work = stepper.work();
    for (const auto& e : sys.events()) r.times.push_back(e.t);
    return r;
  };
  const Run eager = run(false), deferred = run(true);
  ASSERT_EQ(eager.result.status, Status::Success) << eager.result.message;
  ASSERT_EQ(deferred.result.status, Status::Success) << deferred.result.message;
  ASSERT_GE(eager.times.size(), 2u) << "the joints must slip and stick";
  ASSERT_EQ(deferred.times.size(), eager.times.size());
  double dt = 0;
  for (std::size_t k = 0; k < eager.times.size(); ++k) dt = std::max(dt, std::abs(deferred.times[k] - eager.times[k]));
  const double dx = (deferred.result.x - eager.result.x).cwiseAbs().maxCoeff() / eager.result.x.cwiseAbs().maxCoeff();
  EXPECT_EQ(deferred.result.stats.accepted_steps, eager.result.stats.accepted_steps);
  // Both runs locate each event to the event time tolerance (1e-12 s); round-off of the two
  // propagations moves the roots far less (measured on a 0.01 s run of this scene, 826 events:
  // 1e-12 s and 2e-12 relative).
  EXPECT_LE(dt, 1e-11);
  EXPECT_LE(dx, 1e-10);
  // On that 0.01 s run: 966 exponentials eager, none deferred (no mode lasted 76 grid steps).
  EXPECT_LT(deferred.work.propagator_exponentials, eager.work.propagator_exponentials / 2);
}

// ---------------------------------------------------------------------------------------------
// The coupled solve of a disk with neighbour joints: every joint's row is constant (both sides on
// the structure), so the factorisation of each stuck set's capacitance matrix is kept per set.

/// N = 4 sample sectors with neighbour joints sliding at `angle` from the platform (inclined:
/// the four stuck rows independent), three modes per family, no loads; `duplicate`: joint 0
/// once more as a fifth contact.
struct JointDisk {
  Disk disk{4, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0)};
  ModalBasis<double> basis;
  std::vector<PointContact<double>> joints;
  double mu_k = 0.3, N0 = 20.0;
  explicit JointDisk(bool duplicate = false, double angle = 0.6) {
    CyclicModalOptions<double> o;
    o.num_modes = 3;
    basis = annulus_basis(disk, compute_cyclic_modes(disk, o)).with_modal_damping(Vector::Constant(12, 0.005));
    joints = neighbour_joints(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0},
                              PlaneDirection<double>::at_angle(angle), CoulombLaw<double>(0.4, mu_k), N0);
    if (duplicate) joints.push_back(joints.front());
  }
  ContactSystem<double> system() const { return ContactSystem<double>(disk.frame(), basis, joints); }
  /// Contacts in `stuck` stick, the others slip in the direction `sign` (+1 or -1).
  DamperStates mode(const std::vector<Eigen::Index>& stuck, int sign) const {
    DamperStates m(static_cast<Eigen::Index>(joints.size()),
                   sign > 0 ? ContactState::SlipPositive : ContactState::SlipNegative);
    for (Eigen::Index i : stuck) m[i] = ContactState::Stick;
    return m;
  }
  /// A state away from rest that differs from step to step.
  Vector state(const ContactSystem<double>& sys, int step) const {
    Vector x = sys.initial_state();
    for (Eigen::Index j = 0; j < 24; ++j) x[j] = 1e-5 * std::sin(0.7 * double(j + 1) + 0.3 * step);
    return x;
  }
};

TEST(DiskFriction, CachedCapacitanceSolveEqualsAFreshSystemAndTheHandSolve) {
  const JointDisk d;
  ContactSystem<double> sys = d.system();
  const Eigen::Index n = d.basis.size();
  // Every stuck set of the four joints and back (15 sets, more than the factorisations kept), so
  // that sets are found in the cache, evicted and factored again, with a new state at each step.
  std::vector<std::vector<Eigen::Index>> sets;
  for (unsigned bits = 1; bits < 16; ++bits) {
    std::vector<Eigen::Index> s;
    for (Eigen::Index i = 0; i < 4; ++i)
      if (bits & (1u << i)) s.push_back(i);
    sets.push_back(s);
  }
  for (int k = 14; k >= 0; --k) sets.push_back(sets[static_cast<std::size_t>(k)]);
  for (std::size_t k = 0; k < 15; ++k) sets.push_back(sets[(7 * k) % 15]);
  for (std::size_t step = 0; step < sets.size(); ++step) {
    SCOPED_TRACE("step " + std::to_string(step));
    const std::vector<Eigen::Index>& stuck = sets[step];
    const int sign = step % 2 ? 1 : -1;
    const DamperStates mode = d.mode(stuck, sign);
    const Vector x = d.state(sys, static_cast<int>(step));
    const auto& e = sys.evaluate(mode, 0.0, x);
    ASSERT_TRUE(e.finite);
    // A system constructed now, with nothing kept from earlier modes: the same numbers to
    // rounding (1e-12 relative: the same arithmetic on the same rows).
    ContactSystem<double> fresh = d.system();
    const auto& ef = fresh.evaluate(mode, 0.0, x);
    ASSERT_TRUE(ef.finite);
    EXPECT_LE((e.qdd - ef.qdd).norm(), 1e-12 * ef.qdd.norm());
    EXPECT_LE((e.f - ef.f).norm(), 1e-12 * ef.f.norm());
    // By hand: r = -c q' - omega^2 q + sum over sliding joints of -s mu_k N0 w_i, and the stuck
    // forces lambda from (W_S W_S^T) lambda = -W_S r (M = I, constant rows: no rate terms);
    // q'' = r + W_S^T lambda. Tolerance 1e-9: rounding amplified by the condition number of
    // W_S W_S^T (below 1e4 for these sets).
    const Vector q = x.head(n), qd = x.segment(n, n);
    Vector r = -d.basis.damping_coefficients().cwiseProduct(qd) - d.basis.omega().cwiseAbs2().cwiseProduct(q);
    Matrix W(static_cast<Eigen::Index>(stuck.size()), n);
    for (Eigen::Index i = 0, a = 0; i < 4; ++i) {
      if (std::find(stuck.begin(), stuck.end(), i) != stuck.end()) W.row(a++) = sys.contact_row(i).transpose();
      else r += -sign * d.mu_k * d.N0 * sys.contact_row(i);
    }
    const Vector lambda = (W * W.transpose()).fullPivLu().solve(-W * r);
    const Vector qdd = r + W.transpose() * lambda;
    EXPECT_LE((e.qdd - qdd).norm(), 1e-9 * qdd.norm());
    for (std::size_t a = 0; a < stuck.size(); ++a)
      EXPECT_NEAR(e.f[stuck[a]], lambda[static_cast<Eigen::Index>(a)], 1e-9 * lambda.norm());
  }
}

TEST(DiskFriction, DependentStuckSetIsNotFiniteEachTimeItIsSolved) {
  // Joint 4 repeats joint 0: any stuck set holding both has two equal rows, and the solve cannot
  // split their forces; sets without the pair are regular. Each set is solved twice, with
  // another set in between.
  const JointDisk d(true);
  ContactSystem<double> sys = d.system();
  const std::vector<std::pair<std::vector<Eigen::Index>, bool>> cases = {
      {{0, 4}, false}, {{0}, true}, {{0, 4}, false}, {{0, 1, 2, 3}, true}, {{0, 1, 2, 3, 4}, false},
      {{4}, true},     {{0, 4}, false}, {{0, 1, 2, 3, 4}, false}, {{1, 2, 3, 4}, true}};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    SCOPED_TRACE("case " + std::to_string(k));
    const auto& e = sys.evaluate(d.mode(cases[k].first, 1), 0.0, d.state(sys, static_cast<int>(k)));
    EXPECT_EQ(e.finite, cases[k].second);
    if (!cases[k].second) EXPECT_TRUE(std::isnan(e.qdd[0]));
    else EXPECT_TRUE(e.qdd.allFinite());
  }
  // Joints along X: the four rows sum to the platforms' axial stretch, which the retained modes
  // lack, so the four stuck rows are dependent to rounding only (no exact zero pivot: the rank
  // test decides), any three are independent.
  const JointDisk along_x(false, 0.0);
  ContactSystem<double> sx = along_x.system();
  const std::vector<std::pair<std::vector<Eigen::Index>, bool>> x_cases = {
      {{0, 1, 2, 3}, false}, {{0, 1, 2}, true}, {{0, 1, 2, 3}, false}, {{1, 2, 3}, true}};
  for (std::size_t k = 0; k < x_cases.size(); ++k) {
    SCOPED_TRACE("case along X " + std::to_string(k));
    EXPECT_EQ(sx.evaluate(along_x.mode(x_cases[k].first, 1), 0.0, along_x.state(sx, 1)).finite, x_cases[k].second);
  }
}

}  // namespace bladed_disk_test

// compute_modes does not trust its eigensolvers: regression tests of the
// cases in the issue (small frames with a rigid-body mode on the Spectra path; a cantilever with
// a tiny element on the dense path) against closed forms, and of the a-posteriori checks.

#include "beam/beam_test_support.hpp"
#include "modal/modal_test_frames.hpp"
#include "stickslip/modal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace modal_checks_test {

using namespace stickslip;
using namespace stickslip_test;

ModalOptions<double> options_with(Eigen::Index modes, ModalSolver solver) {
  ModalOptions<double> o;
  o.num_modes = modes;
  o.solver = solver;
  return o;
}

// A beam of length 1 along X, pinned at node 0 (one rigid-body mode: rotation about the pin).
AssembledFrame<double> pinned_free_beam(int elements) {
  FrameModel<double> model;
  const auto a = model.add_node(0.0, 0.0), b = model.add_node(1.0, 0.0);
  model.add_member(a, b, slender_steel(), elements);
  model.pin(a);
  return model.assemble();
}

// The paper's blade (E = 2.06e11 Pa, rho = 7800 kg/m^3, A = 6e-5 m^2, I = 2e-11 m^4, L = 0.2 m),
// clamped at the root, 40 elements of 5 mm of which the first is split at `tiny` [m] into an
// element of length `tiny` and one of 5 mm - tiny.
AssembledFrame<double> blade_with_tiny_root_element(double tiny) {
  const SectionProperties<double> blade{2.06e11, 7800.0, 6e-5, 2e-11};
  FrameModel<double> model;
  const auto root = model.add_node(0.0, 0.0), tip = model.add_node(0.0, 0.2);
  std::vector<double> stations{0.0, tiny};
  for (int i = 1; i <= 40; ++i) stations.push_back(0.2 * i / 40.0);
  model.add_member(root, tip, blade, stations);
  model.clamp(root);
  return model.assemble();
}

TEST(ComputeModesChecks, SparseSolverOnSmallPinnedBeamsHasNoSpuriousMode) {
  // With one rigid-body mode, Lanczos about sigma = -100 eps trace(K)/trace(M) returned
  // a spurious second near-zero mode (omega ~ 1e-5 rad/s, residual 1) and elastic frequencies
  // off by 1e-3 to 0.5. Reference: the dense solver on the same matrices (standard reduction,
  // backward stable; these 1-6 element models are well conditioned, eps lambda_max / lambda_2 <
  // 1e-9), so the frequencies must agree to 1e-8 (Lanczos tolerance 1e-10 on 1/(lambda - sigma)
  // plus margin). The first elastic mode is also checked against the pinned-free closed form
  // tan(bL) = tanh(bL), bL = 3.926602 (Blevins table 8-1), within the Hermite discretisation
  // error of a 3-element mesh (~1e-3 for (beta h)^4 ~ 3.6, measured 1.7e-3 at 3 elements).
  for (int elements = 1; elements <= 6; ++elements) {
    const auto frame = pinned_free_beam(elements);
    ASSERT_EQ(frame.num_rigid_body_modes, 1);
    const Eigen::Index modes = std::min<Eigen::Index>(4, frame.num_free() - 1);
    const auto d = compute_modes(frame, options_with(modes, ModalSolver::Dense));
    const auto s = compute_modes(frame, options_with(modes, ModalSolver::Sparse));
    ASSERT_EQ(s.size(), modes);
    EXPECT_EQ(s.num_rigid_body_modes(), 1) << elements << " elements";
    EXPECT_EQ(s.omega()(0), 0.0);
    for (Eigen::Index i = 1; i < modes; ++i)
      EXPECT_NEAR(s.omega()(i) / d.omega()(i), 1.0, 1e-8) << elements << " elements, mode " << i;
    if (elements >= 3) {
      const double bl = 3.926602312;
      EXPECT_NEAR(s.omega()(1) / (bl * bl * bending_unit(slender_steel(), 1.0)), 1.0, 3e-3)
          << elements << " elements";
    }
  }
}

TEST(ComputeModesChecks, SparseSolverOnSmallFreeFreeBeamsMatchesDense) {
  // The same defect with three rigid-body modes (free-free beam of 2-6 elements):
  // elastic frequencies were off by up to 1e-5 (residuals 1e-5). Dense reference as above.
  for (int elements = 2; elements <= 6; ++elements) {
    FrameModel<double> model;
    const auto a = model.add_node(0.0, 0.0), b = model.add_node(1.0, 0.0);
    model.add_member(a, b, slender_steel(), elements);
    const auto frame = model.assemble();
    const Eigen::Index modes = std::min<Eigen::Index>(8, frame.num_free() - 1);
    const auto d = compute_modes(frame, options_with(modes, ModalSolver::Dense));
    const auto s = compute_modes(frame, options_with(modes, ModalSolver::Sparse));
    EXPECT_EQ(s.num_rigid_body_modes(), 3);
    for (Eigen::Index i = 3; i < modes; ++i)
      EXPECT_NEAR(s.omega()(i) / d.omega()(i), 1.0, 1e-8) << elements << " elements, mode " << i;
  }
}

TEST(ComputeModesChecks, PinnedBeamOnSparsePathMatchesClosedForm) {
  // 20 elements: the pinned-free beam's elastic modes bL = 3.926602, 7.068583, 10.210176
  // (tan bL = tanh bL) within the Hermite discretisation error (~1e-5 for mode 3 at 20
  // elements; tolerance 1e-4). Before the fix mode 3 came out 6e-5 off the dense value.
  const auto frame = pinned_free_beam(20);
  const auto s = compute_modes(frame, options_with(4, ModalSolver::Sparse));
  const auto d = compute_modes(frame, options_with(4, ModalSolver::Dense));
  const double bl[] = {3.926602312, 7.068582745, 10.21017612};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s.omega()(i + 1) / (bl[i] * bl[i] * bending_unit(slender_steel(), 1.0)), 1.0, 1e-4);
    EXPECT_NEAR(s.omega()(i + 1) / d.omega()(i + 1), 1.0, 1e-8);
  }
}

TEST(ComputeModesChecks, CantileverWithTinyElementHasTheEulerBernoulliFrequencies) {
  // A 1e-9 m element next to 5 mm ones made the dense solver return omega = 0, 0 (no
  // rigid-body mode), a 1e-6 m element a wrong first frequency: the standard reduction's error
  // eps * lambda_max swamps lambda_1 when the tiny element's stiffness (EI / h^3) dominates.
  // Reference: Euler-Bernoulli clamped-free, omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)) with
  // beta_1 L = 1.875104, beta_2 L = 4.694091 (about 261 and 1634 rad/s for the blade). The
  // 40-element mesh errs by ~1e-9 (mode 1) and ~1e-7 (mode 2) (order-4 convergence, see
  // compute_modes_test.cpp); the tiny element only splits one element. Tolerance 1e-6.
  const SectionProperties<double> blade{2.06e11, 7800.0, 6e-5, 2e-11};
  const double unit = bending_unit(blade, 0.2);
  const double ref[] = {1.875104069 * 1.875104069 * unit, 4.694091133 * 4.694091133 * unit};
  for (double tiny : {1e-9, 1e-6}) {
    const auto frame = blade_with_tiny_root_element(tiny);
    ASSERT_EQ(frame.num_rigid_body_modes, 0);
    for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse}) {
      const auto basis = compute_modes(frame, options_with(4, solver));
      EXPECT_EQ(basis.num_rigid_body_modes(), 0);
      for (int i = 0; i < 2; ++i)
        EXPECT_NEAR(basis.omega()(i) / ref[i], 1.0, 1e-6)
            << "tiny element " << tiny << " m, " << to_string(solver) << ", mode " << i + 1;
    }
  }
}

// The paper's blade section as a clamped 0.2 m cantilever along X on the given stations.
FrameModel<double> blade_cantilever(const std::vector<double>& stations, bool clamp_root = true) {
  const SectionProperties<double> blade{2.06e11, 7800.0, 6e-5, 2e-11};
  FrameModel<double> model;
  const auto root = model.add_node(0.0, 0.0), tip = model.add_node(0.2, 0.0);
  model.add_member(root, tip, blade, stations);
  model.clamp(clamp_root ? root : tip);
  return model;
}

// Stations of 20 elements of 10 mm, one of them (at index `at`) split `gap` from its start.
std::vector<double> fine_stations_with_gap(int at, double gap) {
  std::vector<double> s;
  for (int i = 0; i <= 20; ++i) {
    s.push_back(0.01 * i);
    if (i == at) s.push_back(0.01 * i + gap);
  }
  return s;
}

TEST(ComputeModesChecks, ShortElementIsRefusedWhereItsRoundOffWouldSwampTheModes) {
  // A clamped 0.2 m blade cantilever on stations {0, 0.1, 0.1 + gap, 0.2} returned, as success,
  // omega_1 1 % low (gap 1e-6 m) and omega = 734, 5521, 13976 rad/s for ~261, 1648, 5546 (gap
  // 1e-9 m): the round-off of the short element's 12 EI/gap^3 in the assembled K swamps the
  // structure's stiffness (docs/modal.md, "Short elements"). Reference: Euler-Bernoulli
  // clamped-free omega_n = (beta_n L)^2 sqrt(EI / (rho A L^4)), beta_n L = 1.875104, 4.694091,
  // 7.854757.
  const SectionProperties<double> blade{2.06e11, 7800.0, 6e-5, 2e-11};
  const double unit = bending_unit(blade, 0.2);
  const double bl[] = {1.875104069, 4.694091133, 7.854757438};
  // Refused, naming the element (member 0, element 1), its length and the ratio to the member.
  for (double gap : {1e-6, 1e-9}) {
    const auto model = blade_cantilever({0.0, 0.1, 0.1 + gap, 0.2});
    EXPECT_INVALID_ARGUMENT(model.assemble(), "member 0, element 1 (length " + detail::format_value(0.1 + gap - 0.1) + " m) is");
    EXPECT_INVALID_ARGUMENT(model.assemble(), "times shorter than the longest member (0.20000000000000001 m)");
    EXPECT_INVALID_ARGUMENT(model.assemble(), "max_element_length_ratio()");
  }
  // Gap 1e-3 m (ratio 200) is accepted and right to the discretisation error of this coarse
  // mesh: conforming Hermite elements with consistent mass give upper bounds (Rayleigh-Ritz), and
  // two 0.1 m elements put omega_1 within 1e-3 (measured 4.7e-4; the short element adds ~1e-5).
  for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse}) {
    const auto basis = compute_modes(blade_cantilever({0.0, 0.1, 0.101, 0.2}).assemble(), options_with(3, solver));
    EXPECT_EQ(basis.num_rigid_body_modes(), 0);
    for (int i = 0; i < 3; ++i) EXPECT_GT(basis.omega()(i), bl[i] * bl[i] * unit * (1 - 1e-12)) << i;
    EXPECT_NEAR(basis.omega()(0) / (bl[0] * bl[0] * unit), 1.0, 1e-3);
  }
  // On a 10 mm mesh, a short element in mid-span (gap 1e-3 m) or at the free tip at L/h = 800
  // (just below the limit 908; the tip is the worst place, round-off <= ~3.3 eps 800^3 = 4e-7 in
  // lambda) keeps omega_1..3 within 5e-5 of the closed form: the 20-element mesh errs by 1.6e-5 at
  // mode 3 (order-4 convergence: the 40-element mesh's 1e-7 at mode 2 times 2^4 (beta_3/beta_2)^4
  // = 125), 2e-6 at mode 2. At L/h = 1000 the tip element is refused (round-off up to 3e-6 in
  // omega_1), unless the cantilever is clamped at that end (then the element only stiffens a
  // support, and the modes are right).
  const std::vector<std::vector<double>> accepted{fine_stations_with_gap(10, 1e-3),
                                                  fine_stations_with_gap(19, 0.01 - 0.2 / 800)};
  for (const auto& stations : accepted)
    for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse}) {
      const auto basis = compute_modes(blade_cantilever(stations).assemble(), options_with(3, solver));
      for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(basis.omega()(i) / (bl[i] * bl[i] * unit), 1.0, 5e-5)
            << stations[11] << " " << to_string(solver) << ", mode " << i;
    }
  const auto tip_1000 = fine_stations_with_gap(19, 0.01 - 0.2 / 1000);
  EXPECT_INVALID_ARGUMENT(blade_cantilever(tip_1000).assemble(), "member 0, element 20 (length");
  const auto basis = compute_modes(blade_cantilever(tip_1000, false).assemble(), options_with(3, ModalSolver::Dense));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(basis.omega()(i) / (bl[i] * bl[i] * unit), 1.0, 5e-5) << i;
}

// The grounded oscillators (K = diag(800, 1800, 50), M = diag(2, 2, 0.5)); the tests below
// corrupt K or the rigid-body count by hand.
AssembledFrame<double> oscillators() { return grounded_oscillators().assemble(); }

TEST(ComputeModesChecks, NegativeEigenvalueIsAnErrorNotOmegaZero) {
  // Lambda <= 0 became omega = 0. K = diag(-800, 1800, 50) has lambda = -400, far
  // beyond round-off: an error on both paths (the sparse one finds no positive definite
  // K - sigma M and falls back to dense).
  auto frame = oscillators();
  frame.stiffness.coeffRef(0, 0) = -800.0;
  for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse})
    EXPECT_DOMAIN_ERROR(compute_modes(frame, options_with(2, solver)), "negative eigenvalue");
}

TEST(ComputeModesChecks, ZeroEigenvalueWithoutRigidBodyModeIsAnError) {
  // K = diag(800, 1800, 0) with num_rigid_body_modes = 0: a zero-stiffness motion the count does
  // not allow (a mechanism or ill-conditioning) must not pass as a mode.
  auto frame = oscillators();
  frame.stiffness.coeffRef(2, 2) = 0.0;
  frame.num_rigid_body_modes = 0;
  for (ModalSolver solver : {ModalSolver::Dense, ModalSolver::Sparse})
    EXPECT_DOMAIN_ERROR(compute_modes(frame, options_with(2, solver)),
                         "where the supports allow 0 rigid-body mode");
  // The opposite: a count of 2 where only one zero eigenvalue exists.
  frame.num_rigid_body_modes = 2;
  EXPECT_DOMAIN_ERROR(compute_modes(frame, options_with(3, ModalSolver::Dense)),
                       "only 1 of the 2 rigid-body modes");
  // With the right count the frame is fine: omega = 0, sqrt(800/2) = 20, sqrt(1800/2) = 30.
  frame.num_rigid_body_modes = 1;
  const auto basis = compute_modes(frame, options_with(3, ModalSolver::Dense));
  EXPECT_EQ(basis.omega()(0), 0.0);
  EXPECT_NEAR(basis.omega()(1), 20.0, 1e-12);
  EXPECT_NEAR(basis.omega()(2), 30.0, 1e-12);
}

TEST(ComputeModesChecks, FailedSparseSolveFallsBackToDenseAndReportsWhy) {
  // One Lanczos restart with a minimal basis cannot converge 10 modes of a 180-DOF cantilever:
  // Spectra's NotConverging becomes the reason of a dense fallback, whose result is the dense
  // solver's (same frequencies to the last bits: the same computation).
  const auto frame = cantilever(1.0, 60).assemble();
  ModalOptions<double> o = options_with(10, ModalSolver::Sparse);
  o.max_iterations = 1;
  o.ncv = 11;
  ModalSolveReport<double> report;
  const auto fell_back = compute_modes(frame, o, &report);
  EXPECT_EQ(report.solver, ModalSolver::Dense);
  EXPECT_NE(report.fallback_reason.find("did not converge in 1 restarts"), std::string::npos)
      << report.fallback_reason;
  const auto dense = compute_modes(frame, options_with(10, ModalSolver::Dense));
  EXPECT_EQ(fell_back.omega(), dense.omega());
  // Above the fallback limit the failure is an exception with Spectra's cause.
  o.dense_fallback_limit = 100;
  EXPECT_DOMAIN_ERROR(compute_modes(frame, o), "did not converge in 1 restarts");
  o.dense_fallback_limit = -1;
  EXPECT_INVALID_ARGUMENT(compute_modes(frame, o), "options.dense_fallback_limit");
}

TEST(ComputeModesChecks, RealisticFramesPassTheChecksWithoutFallback) {
  // The paper's T-frame (Auto: dense) and a 20-element-per-member L frame of 3 members (sparse
  // forced): no fallback, backward errors at round-off (dense: ~eps; sparse: ~ the Lanczos
  // tolerance 1e-10), mass-orthonormal to 1e-8.
  FrameModel<double> t = blade_platform_frame().model;
  FrameModel<double> l;
  const auto a = l.add_node(0.0, 0.0), b = l.add_node(0.0, 1.0), c = l.add_node(1.0, 1.0), d = l.add_node(1.0, 0.0);
  l.add_member(a, b, slender_steel(), 20);
  l.add_member(b, c, slender_steel(), 20);
  l.add_member(c, d, slender_steel(), 20);
  l.pin(a);
  for (const auto& [model, solver] : {std::pair{&t, ModalSolver::Auto}, std::pair{&l, ModalSolver::Sparse}}) {
    ModalSolveReport<double> report;
    compute_modes(model->assemble(), options_with(10, solver), &report);
    EXPECT_TRUE(report.fallback_reason.empty()) << report.fallback_reason;
    EXPECT_LT(report.backward_error, 1e-9);
    EXPECT_LT(report.orthonormality_error, 1e-8);
  }
}

}  // namespace modal_checks_test

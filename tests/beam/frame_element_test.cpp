// Tests of FrameElement: properties of the element matrices that hold independently of the
// code (symmetry, rigid-body null space, total mass, orthogonality of T), the textbook entries,
// and the argument checks.

#include "beam/beam_test_support.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace stickslip;
using namespace stickslip_test;
using Element = FrameElement<double>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Tolerances: matrices are built from O(1)..O(EI/L^3) products, so relative round-off ~1e-15;
// 1e-12 relative leaves a wide margin while any wrong entry is off by O(1).
constexpr double kRel = 1e-12;

// Rigid motions of the element in global DOFs (X1 Y1 Rz1 X2 Y2 Rz2) for nodes at p1, p2:
// translation X, translation Y, rotation about p1.
Eigen::Matrix<double, 6, 3> rigid_motions(double L, double c, double s) {
  Eigen::Matrix<double, 6, 3> r = Eigen::Matrix<double, 6, 3>::Zero();
  r(0, 0) = r(3, 0) = 1;
  r(1, 1) = r(4, 1) = 1;
  // Rotation theta about node 1: node 2 at (L c, L s) moves by theta * (-L s, L c).
  r(2, 2) = r(5, 2) = 1;
  r(3, 2) = -L * s;
  r(4, 2) = L * c;
  return r;
}

TEST(FrameElement, LocalStiffnessHasTextbookEntries) {
  // Przemieniecki, Theory of Matrix Structural Analysis, eq. 5.51 / any FE text.
  const Section s{2.0e11, 7800.0, 3e-4, 5e-8};
  const double L = 0.7;
  const Element e(L, 1.0, 0.0, s);
  const auto k = e.local_stiffness();
  const double ea = s.E * s.A / L, ei = s.E * s.I;
  EXPECT_NEAR(k(0, 0), ea, kRel * ea);
  EXPECT_NEAR(k(0, 3), -ea, kRel * ea);
  EXPECT_NEAR(k(1, 1), 12 * ei / (L * L * L), kRel * ea);
  EXPECT_NEAR(k(1, 2), 6 * ei / (L * L), kRel * ea);
  EXPECT_NEAR(k(2, 2), 4 * ei / L, kRel * ea);
  EXPECT_NEAR(k(2, 5), 2 * ei / L, kRel * ea);
  EXPECT_NEAR(k(4, 5), -6 * ei / (L * L), kRel * ea);
  EXPECT_EQ(k(0, 1), 0.0);  // axial and bending are uncoupled in local axes
  const auto m = e.local_consistent_mass();
  const double mass = s.rho * s.A * L;
  EXPECT_NEAR(m(1, 1), 156 * mass / 420, kRel * mass);
  EXPECT_NEAR(m(1, 5), -13 * L * mass / 420, kRel * mass);
  EXPECT_NEAR(m(2, 5), -3 * L * L * mass / 420, kRel * mass);
  EXPECT_NEAR(m(0, 3), mass / 6, kRel * mass);
}

TEST(FrameElement, GlobalMatricesAreSymmetricWithRigidBodyNullSpace) {
  const Section s{2.06e11, 7800.0, 6e-5, 2e-11};
  for (double angle : {0.0, 0.3, 1.5707963267948966, 2.5, -1.1}) {
    const double L = 0.013, c = std::cos(angle), sn = std::sin(angle);
    const Element e(L, c, sn, s);
    const auto K = e.global_stiffness();
    const double scale = K.cwiseAbs().maxCoeff();
    EXPECT_LE((K - K.transpose()).cwiseAbs().maxCoeff(), kRel * scale);
    // Rigid motions store no strain energy: K r = 0 (to round-off of the O(scale) entries).
    EXPECT_LE((K * rigid_motions(L, c, sn)).cwiseAbs().maxCoeff(), 1e-10 * scale) << "angle " << angle;
    // Exactly three zero eigenvalues, the other three positive.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(K);
    int zeros = 0;
    for (int i = 0; i < 6; ++i) zeros += es.eigenvalues()(i) < 1e-10 * scale ? 1 : 0;
    EXPECT_EQ(zeros, 3);
    for (MassType type : {MassType::Consistent, MassType::Lumped}) {
      const auto M = e.global_mass(type);
      EXPECT_LE((M - M.transpose()).cwiseAbs().maxCoeff(), kRel * M.cwiseAbs().maxCoeff());
      // A rigid translation in any direction carries the element mass rho A L.
      Vector6 tx = Vector6::Zero(), ty = Vector6::Zero();
      tx(0) = tx(3) = 1;
      ty(1) = ty(4) = 1;
      const double mass = s.rho * s.A * L;
      EXPECT_NEAR(tx.dot(M * tx), mass, kRel * mass) << to_string(type);
      EXPECT_NEAR(ty.dot(M * ty), mass, kRel * mass) << to_string(type);
      EXPECT_NEAR(tx.dot(M * ty), 0.0, kRel * mass) << to_string(type);
      // Positive definite (Cholesky succeeds).
      EXPECT_EQ(Eigen::LLT<Matrix6>(M).info(), Eigen::Success) << to_string(type);
    }
  }
}

TEST(FrameElement, LumpedMassIsDiagonalHrz) {
  const Section s{1.0, 2.0, 3.0, 4.0};
  const double L = 0.5, m = 2.0 * 3.0 * L;
  const auto M = Element(L, 0.6, 0.8, s).global_mass(MassType::Lumped);
  EXPECT_LE((M - Eigen::Matrix<double, 6, 6>(M.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 1e-15);
  // HRZ: rotary term = (420 / 312) * (4 m L^2 / 420) = m L^2 / 78.
  EXPECT_NEAR(M(2, 2), m * L * L / 78.0, 1e-15);
  EXPECT_NEAR(M(4, 4), m / 2, 1e-15);
}

TEST(FrameElement, RotationMapsGlobalToLocalAxes) {
  const Section s{1.0, 1.0, 1.0, 1.0};
  // Member along +Y: u is +Y and w is -X.
  const auto T = Element(1.0, 0.0, 1.0, s).rotation();
  Vector6 d = Vector6::Zero();
  d(0) = 2.0;  // X1
  d(1) = 3.0;  // Y1
  d(2) = 0.5;  // Rz1
  const Vector6 local = T * d;
  EXPECT_DOUBLE_EQ(local(0), 3.0);   // u1 = Y1
  EXPECT_DOUBLE_EQ(local(1), -2.0);  // w1 = -X1
  EXPECT_DOUBLE_EQ(local(2), 0.5);   // theta unchanged
  const auto T2 = Element(1.0, std::cos(0.4), std::sin(0.4), s).rotation();
  EXPECT_LE((T2 * T2.transpose() - Eigen::Matrix<double, 6, 6>::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(FrameElement, RejectsBadArguments) {
  const Section good{2e11, 7800.0, 1e-4, 1e-8};
  EXPECT_INVALID_ARGUMENT(Element(0.0, 1.0, 0.0, good), "length");
  EXPECT_INVALID_ARGUMENT(Element(-1.0, 1.0, 0.0, good), "length");
  EXPECT_INVALID_ARGUMENT(Element(std::nan(""), 1.0, 0.0, good), "length");
  EXPECT_INVALID_ARGUMENT(Element(1.0, 1.0, 1.0, good), "cos^2 + sin^2");
  EXPECT_INVALID_ARGUMENT(Element(1.0, INFINITY, 0.0, good), "cos");
  EXPECT_INVALID_ARGUMENT(Element(1.0, 1.0, 0.0, (Section{0.0, 7800.0, 1e-4, 1e-8})), "section.E");
  EXPECT_INVALID_ARGUMENT(Element(1.0, 1.0, 0.0, (Section{2e11, -1.0, 1e-4, 1e-8})), "section.rho");
  EXPECT_INVALID_ARGUMENT(Element(1.0, 1.0, 0.0, (Section{2e11, 7800.0, INFINITY, 1e-8})), "section.A");
  EXPECT_INVALID_ARGUMENT(Element(1.0, 1.0, 0.0, (Section{2e11, 7800.0, 1e-4, std::nan("")})), "section.I");
}

}  // namespace

// Tests of ModalBasis: nodal rows, expansion, truncation and modal damping formulas.

#include "beam/beam_test_support.hpp"
#include "stickslip/modal.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace stickslip;
using namespace stickslip_test;

ModalBasis<double> cantilever_basis(Eigen::Index modes = 4) {
  ModalOptions<double> o;
  o.num_modes = modes;
  return compute_modes(cantilever(1.0, 10).assemble(), o);
}

TEST(ModalBasis, NodalRowsAreRowsOfPhiAndZeroWhenConstrained) {
  const auto frame = cantilever(1.0, 10).assemble();
  const auto basis = compute_modes(frame, ModalOptions<double>{4});
  EXPECT_EQ(basis.model_id(), frame.model_id);
  for (Eigen::Index node = 0; node < frame.dofs.num_nodes(); ++node) {
    for (Dof d : {Dof::X, Dof::Y, Dof::Rz}) {
      const auto row = basis.nodal(node, d);
      ASSERT_EQ(row.size(), 4);
      const Eigen::Index f = frame.dofs.free_index(node, d);
      const Eigen::RowVectorXd expected = f < 0 ? Eigen::RowVectorXd::Zero(4) : Eigen::RowVectorXd(basis.phi().row(f));
      EXPECT_EQ(Eigen::RowVectorXd(row), expected) << "node " << node;
    }
  }
  // The clamped root (node 0) does not move in any mode.
  EXPECT_EQ(basis.nodal(0, Dof::Y).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_INVALID_ARGUMENT(basis.nodal(99, Dof::X), "node = 99 does not exist");
}

TEST(ModalBasis, ExpandIsPhiTimesQ) {
  const auto basis = cantilever_basis();
  const Eigen::Vector4d q(0.3, -1.0, 2.0, 0.5);
  const Eigen::VectorXd x = basis.expand(q);
  EXPECT_LE((x - basis.phi() * q).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::VectorXd full = basis.nodal_displacements(q);
  ASSERT_EQ(full.size(), 3 * basis.dofs().num_nodes());
  EXPECT_EQ(full.head(3).cwiseAbs().maxCoeff(), 0.0);  // clamped node
  EXPECT_EQ(basis.dofs().gather(full), x);
  EXPECT_INVALID_ARGUMENT(basis.expand(Eigen::Vector3d::Zero()), "vector size 3");
}

TEST(ModalBasis, TruncatedKeepsTheLowestModes) {
  const auto basis = cantilever_basis().with_modal_damping(Eigen::Vector4d(0.01, 0.02, 0.03, 0.04));
  const auto t = basis.truncated(2);
  EXPECT_EQ(t.size(), 2);
  EXPECT_EQ(t.omega(), basis.omega().head(2));
  EXPECT_EQ(t.phi(), basis.phi().leftCols(2));
  EXPECT_EQ(t.damping_ratios(), basis.damping_ratios().head(2));
  EXPECT_INVALID_ARGUMENT(basis.truncated(0), "n = 0");
  EXPECT_INVALID_ARGUMENT(basis.truncated(5), "n = 5");
}

TEST(ModalBasis, RayleighDampingRatiosFollowTheFormula) {
  // zeta_i = alpha / (2 w_i) + beta w_i / 2; c_i = alpha + beta w_i^2 = 2 zeta_i w_i.
  const auto basis = cantilever_basis();
  const double alpha = 3.0, beta = 2e-5;
  const auto damped = basis.with_rayleigh_damping(alpha, beta);
  for (Eigen::Index i = 0; i < 4; ++i) {
    const double w = basis.omega()(i);
    EXPECT_NEAR(damped.damping_ratios()(i), alpha / (2 * w) + beta * w / 2, 1e-15);
    EXPECT_NEAR(damped.damping_coefficients()(i), alpha + beta * w * w, 1e-12);
  }
  EXPECT_EQ(basis.damping_ratios().cwiseAbs().maxCoeff(), 0.0);  // the original is undamped
  EXPECT_INVALID_ARGUMENT(basis.with_rayleigh_damping(-1.0, 0.0), "alpha");
  EXPECT_INVALID_ARGUMENT(basis.with_rayleigh_damping(0.0, std::nan("")), "beta");
}

TEST(ModalBasis, RigidBodyModesKeepOnlyTheMassProportionalDamping) {
  FrameModel<double> model;
  const auto a = model.add_node(0, 0), b = model.add_node(1, 0);
  model.add_member(a, b, slender_steel(), 6);
  const auto basis = compute_modes(model.assemble(), ModalOptions<double>{5}).with_rayleigh_damping(2.0, 1e-4);
  ASSERT_EQ(basis.num_rigid_body_modes(), 3);
  for (Eigen::Index i = 0; i < 3; ++i) {
    EXPECT_EQ(basis.damping_ratios()(i), 0.0);
    EXPECT_EQ(basis.damping_coefficients()(i), 2.0);
  }
}

TEST(ModalBasis, ModalDampingSetsRatios) {
  const auto basis = cantilever_basis();
  const Eigen::Vector4d zeta(0.01, 0.02, 0.0, 0.05);
  const auto damped = basis.with_modal_damping(zeta);
  EXPECT_EQ(damped.damping_ratios(), Eigen::VectorXd(zeta));
  EXPECT_NEAR(damped.damping_coefficients()(1), 2 * 0.02 * basis.omega()(1), 1e-12);
  EXPECT_INVALID_ARGUMENT(basis.with_modal_damping(Eigen::Vector2d(0.1, 0.1)), "vector size 2");
  EXPECT_INVALID_ARGUMENT(basis.with_modal_damping(Eigen::Vector4d(0.1, -0.1, 0, 0)), "ratios");
}

TEST(ModalBasis, ConstructorRejectsInconsistentData) {
  const DofMap dofs(std::vector<bool>(6, false));
  EXPECT_INVALID_ARGUMENT(ModalBasis<double>(Eigen::VectorXd(0), Eigen::MatrixXd(6, 0), dofs, 1, 0),
                          "omega.size() must be >= 1");
  EXPECT_INVALID_ARGUMENT(ModalBasis<double>(Eigen::Vector2d(1, 2), Eigen::MatrixXd(5, 2), dofs, 1, 0),
                          "expected num_free = 6");
  EXPECT_INVALID_ARGUMENT(ModalBasis<double>(Eigen::Vector2d(2, 1), Eigen::MatrixXd::Zero(6, 2), dofs, 1, 0),
                          "ascending");
  EXPECT_INVALID_ARGUMENT(ModalBasis<double>(Eigen::Vector2d(1, 2), Eigen::MatrixXd::Zero(6, 2), dofs, 1, 3),
                          "num_rigid_body_modes");
}

}  // namespace

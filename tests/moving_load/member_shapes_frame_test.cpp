// Tests of MemberShapes built from a FrameModel and its ModalBasis: nodal agreement with the
// basis, work equivalence with the real Phi, the static cantilever closed form, bad input.

#include "stickslip/moving_load/member_shapes.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <cmath>
#include <stdexcept>
#include <string>

#include "moving_load/moving_load_test_support.hpp"
#include "stickslip/beam.hpp"
#include "stickslip/modal.hpp"

namespace stickslip {
namespace {

using Shapes = MemberShapes<double>;

// The paper's platform section (E, rho, A, I of the numerical example).
SectionProperties<double> platform_section() { return {2.06e11, 7800.0, 6e-5, 2e-11}; }

// An L-shaped frame like the paper's Fig. 3 (clamped vertical blade, horizontal platform on its
// top) plus an inclined member, so that members of three directions are tested.
struct Frame {
  FrameModel<double> model;
  Eigen::Index blade = -1, platform = -1, strut = -1;
  Frame() {
    const auto s = platform_section();
    const auto root = model.add_node(0.0, 0.0);
    const auto top = model.add_node(0.0, 0.2);
    const auto tip = model.add_node(0.04, 0.2);
    const auto end = model.add_node(0.04 + 0.03 * std::cos(0.5), 0.2 + 0.03 * std::sin(0.5));
    blade = model.add_member(root, top, s, 10);
    platform = model.add_member(top, tip, s, 7);
    strut = model.add_member(tip, end, s, 5);
    model.clamp(root);
  }
};

ModalBasis<double> modes_of(const FrameModel<double>& model, Eigen::Index n) {
  ModalOptions<double> options;
  options.num_modes = n;
  return compute_modes(model.assemble(), options);
}

// At every node of every member the interpolated displacement in global axes and the slope equal
// the basis's nodal rows. Tolerance: the local rotation and its inverse round twice (~2 eps of
// the largest component).
TEST(MemberShapesFrame, NodalValuesEqualBasisRows) {
  const Frame f;
  const auto basis = modes_of(f.model, 8);
  for (const Eigen::Index id : {f.blade, f.platform, f.strut}) {
    const Shapes shapes(f.model, id, basis);
    const auto& member = f.model.member(id);
    EXPECT_EQ(shapes.member(), id);
    EXPECT_EQ(shapes.num_modes(), 8);
    EXPECT_EQ(shapes.num_elements(), member.num_elements());
    EXPECT_DOUBLE_EQ(shapes.length(), member.length);
    Shapes::Vector gx, gy;
    ElementCursor cursor;
    for (std::size_t k = 0; k < member.nodes.size(); ++k) {
      const double eps = member.stations[k];
      const auto node = member.nodes[k];
      shapes.evaluate_global(eps, gx, gy, cursor);
      const Eigen::VectorXd X = basis.nodal(node, Dof::X).transpose();
      const Eigen::VectorXd Y = basis.nodal(node, Dof::Y).transpose();
      const Eigen::VectorXd R = basis.nodal(node, Dof::Rz).transpose();
      const double scale = std::max(X.cwiseAbs().maxCoeff(), Y.cwiseAbs().maxCoeff());
      EXPECT_EIGEN_NEAR(gx, X, 4e-16 * scale) << "member " << id << " node " << node;
      EXPECT_EIGEN_NEAR(gy, Y, 4e-16 * scale) << "member " << id << " node " << node;
      EXPECT_EIGEN_NEAR(shapes.evaluate(eps).dpsi_w, R, 0.0) << "member " << id << " node " << node;
    }
  }
}

// Phi^T f_consistent = modal_force with the real (mass-normalised) basis, for points anywhere on
// each member and all three load components. Tolerance: a dot product over all free DOFs with
// O(1e2) terms of mixed sign, relative rounding ~1e-13 of |Phi|_max * |load|.
TEST(MemberShapesFrame, ConsistentLoadIsWorkEquivalentWithBasis) {
  const Frame f;
  const auto basis = modes_of(f.model, 6);
  for (const Eigen::Index id : {f.blade, f.platform, f.strut}) {
    const Shapes shapes(f.model, id, basis);
    for (const double t : {0.0, 0.137, 0.5, 0.91, 1.0}) {
      const double eps = t * shapes.length();
      const Eigen::VectorXd q = shapes.modal_force(eps, 3.0, -2.0, 0.05);
      const Eigen::VectorXd load = shapes.consistent_nodal_load(eps, 3.0, -2.0, 0.05);
      ASSERT_EQ(load.size(), basis.num_free());
      EXPECT_EIGEN_NEAR((basis.phi().transpose() * load).eval(), q,
                        1e-13 * basis.phi().cwiseAbs().maxCoeff() * 3.0)
          << "member " << id << " eps " << eps;
    }
  }
}

// Static point loads on a cantilever (clamped at eps = 0, inclined by 30 degrees so that the
// rotation to global axes is exercised): K d = f_consistent gives nodal values equal to the
// Euler-Bernoulli closed forms for a load at a (x = distance from the clamp):
//   transverse P: w = P x^2 (3a - x) / (6 EI), theta = P x (2a - x) / (2 EI)    for x <= a,
//                 w = P a^2 (3x - a) / (6 EI), theta = P a^2 / (2 EI)           for x >= a;
//   moment M:     w = M x^2 / (2 EI), theta = M x / EI (x <= a); w = M a (2x - a) / (2 EI),
//                 theta = M a / EI (x >= a);
//   axial F:      u = F min(x, a) / EA.
// Hermite (and linear axial) elements with consistent loads are nodally exact, so the only error
// is the rounding of the sparse Cholesky solve: cond(K) ~ 1e8 here, tolerance 1e-8 relative.
TEST(MemberShapesFrame, CantileverPointLoadNodalDeflectionsAreExact) {
  const double L = 0.2, angle = M_PI / 6, c = std::cos(angle), s = std::sin(angle);
  const auto sec = platform_section();
  const double EI = sec.E * sec.I, EA = sec.E * sec.A;
  FrameModel<double> model;
  const auto a_node = model.add_node(0.0, 0.0);
  const auto b_node = model.add_node(L * c, L * s);
  const auto id = model.add_member(a_node, b_node, sec, 9);
  model.clamp(a_node);
  const auto frame = model.assemble();
  const auto basis = modes_of(model, 3);  // only for the DOF numbering and ownership
  const Shapes shapes(model, id, basis);
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> K(frame.stiffness);
  ASSERT_EQ(K.info(), Eigen::Success);
  const auto& member = model.member(id);
  for (const double a : {0.0731, 0.1234, L}) {  // inside elements and at the tip
    const double P = 12.5, M = 0.8, F = 1e3;
    const Eigen::VectorXd d_t = K.solve(shapes.consistent_nodal_load(a, 0.0, P, 0.0));
    const Eigen::VectorXd d_m = K.solve(shapes.consistent_nodal_load(a, 0.0, 0.0, M));
    const Eigen::VectorXd d_a = K.solve(shapes.consistent_nodal_load(a, F, 0.0, 0.0));
    const double w_ref_scale = P * L * L * L / EI, u_ref_scale = F * L / EA;
    for (std::size_t k = 1; k < member.nodes.size(); ++k) {
      const double x = member.stations[k];
      const auto node = member.nodes[k];
      const auto local = [&](const Eigen::VectorXd& d) {
        const double X = d(frame.dofs.free_index(node, Dof::X));
        const double Y = d(frame.dofs.free_index(node, Dof::Y));
        return Eigen::Vector3d(c * X + s * Y, -s * X + c * Y, d(frame.dofs.free_index(node, Dof::Rz)));
      };
      const double lo = std::min(x, a);
      const Eigen::Vector3d t = local(d_t), m = local(d_m), ax = local(d_a);
      const double w_t = x <= a ? P * x * x * (3 * a - x) / (6 * EI) : P * a * a * (3 * x - a) / (6 * EI);
      const double th_t = x <= a ? P * x * (2 * a - x) / (2 * EI) : P * a * a / (2 * EI);
      const double w_m = x <= a ? M * x * x / (2 * EI) : M * a * (2 * x - a) / (2 * EI);
      const double th_m = M * lo / EI;
      EXPECT_NEAR(t(1), w_t, 1e-8 * w_ref_scale) << "a " << a << " x " << x;
      EXPECT_NEAR(t(2), th_t, 1e-8 * w_ref_scale / L) << "a " << a << " x " << x;
      EXPECT_NEAR(t(0), 0.0, 1e-8 * w_ref_scale);
      EXPECT_NEAR(m(1), w_m, 1e-8 * M * L * L / EI) << "a " << a << " x " << x;
      EXPECT_NEAR(m(2), th_m, 1e-8 * M * L / EI) << "a " << a << " x " << x;
      EXPECT_NEAR(ax(0), F * lo / EA, 1e-8 * u_ref_scale) << "a " << a << " x " << x;
      EXPECT_NEAR(ax(1), 0.0, 1e-8 * u_ref_scale);
    }
  }
}

// Bad input: a member not in the model, a basis of another model or of the model before a
// change, a basis whose DOF numbering does not match, a fixed Modes != basis.size(), eps off the
// member.
TEST(MemberShapesFrame, RejectsForeignBasisUnknownMemberAndOffMemberPoints) {
  Frame f;
  const auto basis = modes_of(f.model, 4);
  const auto message = [](auto&& make) -> std::string {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_EQ(message([&] { Shapes s(f.model, 3, basis); }),
            "MemberShapes: member = 3 is not in the model (it has 3 members)");
  EXPECT_NE(message([&] { Shapes s(f.model, -1, basis); }).find("member = -1 is not in the model"),
            std::string::npos);

  const Frame other;
  const auto other_basis = modes_of(other.model, 4);
  EXPECT_NE(message([&] { Shapes s(f.model, f.platform, other_basis); })
                .find("MemberShapes: basis does not belong to this model"),
            std::string::npos);

  // A hand-made basis claiming the model's id but numbering DOFs of a different model.
  std::vector<bool> constrained(3 * static_cast<std::size_t>(f.model.num_nodes()), false);
  const DofMap wrong(constrained);  // nothing clamped: 3 free DOFs too many
  const ModalBasis<double> forged(Eigen::VectorXd::LinSpaced(2, 1.0, 2.0),
                                  Eigen::MatrixXd::Zero(wrong.num_free(), 2), wrong, f.model.id(), 0);
  EXPECT_NE(message([&] { Shapes s(f.model, f.platform, forged); })
                .find("basis DOF count does not match the model"),
            std::string::npos);

  EXPECT_NE(message([&] { MemberShapes<double, 6> s(f.model, f.platform, basis); })
                .find("fixed Modes = 6"),
            std::string::npos);
  EXPECT_NO_THROW((MemberShapes<double, 4>(f.model, f.platform, basis)));

  const Shapes platform(f.model, f.platform, basis);
  EXPECT_EQ(message([&] { platform.evaluate(0.0412); }),
            "MemberShapes::evaluate: eps = 0.0412 is off member 1 (valid range [0, 0.04])");

  f.model.add_point_mass(0, 0.0);  // any change makes the old basis stale
  EXPECT_NE(message([&] { Shapes s(f.model, f.platform, basis); })
                .find("basis does not belong to this model"),
            std::string::npos);
}

}  // namespace
}  // namespace stickslip

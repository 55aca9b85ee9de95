// Tests of FrameModel: static solutions against closed-form beam theory, the DOF map, the
// rigid-body count, model ids and the argument checks.

#include "beam/beam_test_support.hpp"

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

using namespace stickslip;
using namespace stickslip_test;

// Solve K d = f for a tip load on a cantilever and return the full nodal displacement vector.
Eigen::VectorXd tip_load_displacements(const FrameModel<double>& model, Eigen::Index tip, Dof dof,
                                       double load) {
  const auto frame = model.assemble();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(frame.num_free());
  f(frame.dofs.free_index(tip, dof)) = load;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(frame.stiffness);
  EXPECT_EQ(ldlt.info(), Eigen::Success);
  return frame.dofs.scatter(Eigen::VectorXd(ldlt.solve(f)));
}

TEST(FrameModel, TipLoadDeflectionAndRotationAreExactForAnyMesh) {
  // Hermite cubics contain the exact (cubic) deflection of a tip-loaded cantilever, so
  // w = P L^3 / (3 EI) and theta = P L^2 / (2 EI) hold to round-off for every mesh
  // (Euler-Bernoulli theory). Round-off ~ eps * cond(K); cond(K) ~ (EA/h) / (3EI/L^3) reaches
  // ~1e8 for 40 elements of this slender strip, hence 1e-8 relative.
  const Section s = slender_steel();
  const double L = 1.3, P = 250.0;
  for (int n : {1, 2, 3, 7, 40}) {
    for (double angle : {0.0, 0.9}) {
      const auto model = cantilever(L, n, s, angle);
      const Eigen::Index tip = 1;
      // Load perpendicular to the member: components along global X and Y.
      const auto frame = model.assemble();
      Eigen::VectorXd f = Eigen::VectorXd::Zero(frame.num_free());
      f(frame.dofs.free_index(tip, Dof::X)) = -P * std::sin(angle);
      f(frame.dofs.free_index(tip, Dof::Y)) = P * std::cos(angle);
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(frame.stiffness);
      const Eigen::VectorXd d = frame.dofs.scatter(Eigen::VectorXd(ldlt.solve(f)));
      const double w = -d(3 * tip) * std::sin(angle) + d(3 * tip + 1) * std::cos(angle);
      const double u = d(3 * tip) * std::cos(angle) + d(3 * tip + 1) * std::sin(angle);
      const double w_ref = P * L * L * L / (3 * s.E * s.I), th_ref = P * L * L / (2 * s.E * s.I);
      EXPECT_NEAR(w / w_ref, 1.0, 1e-8) << "n = " << n << ", angle = " << angle;
      EXPECT_NEAR(d(3 * tip + 2) / th_ref, 1.0, 1e-8) << "n = " << n;
      EXPECT_NEAR(u / w_ref, 0.0, 1e-8) << "no axial displacement under a transverse load";
    }
  }
}

TEST(FrameModel, AxialTipLoadAndGradedMeshAreExact) {
  // Linear bar elements contain the exact linear u(x) = P x / EA; a graded mesh too.
  const Section s = slender_steel();
  FrameModel<double> model;
  const auto a = model.add_node(0.0, 0.0), b = model.add_node(2.0, 0.0);
  model.add_member(a, b, s, std::vector<double>{0.0, 0.1, 0.3, 0.7, 1.3, 2.0});
  model.clamp(a);
  const Eigen::VectorXd d = tip_load_displacements(model, b, Dof::X, 1e4);
  EXPECT_NEAR(d(3 * b) / (1e4 * 2.0 / (s.E * s.A)), 1.0, 1e-12);
  const Eigen::VectorXd dw = tip_load_displacements(model, b, Dof::Y, 10.0);
  EXPECT_NEAR(dw(3 * b + 1) / (10.0 * 8.0 / (3 * s.E * s.I)), 1.0, 1e-10);
  // The graded member keeps its stations and places interior nodes on them.
  const auto& m = model.member(0);
  ASSERT_EQ(m.nodes.size(), 6u);
  EXPECT_DOUBLE_EQ(model.node_position(m.nodes[3]).x(), 0.7);
  EXPECT_EQ(m.num_elements(), 5);
}

TEST(FrameModel, PortalFrameSwayMatchesSlopeDeflection) {
  // Fixed-base portal, rigid joints, columns h, beam b, same EI, axially rigid in the limit of
  // large A: sway stiffness k = 24 EI/h^3 * (6 rho + 1) / (6 rho + 4), rho = (I_b/b)/(I_c/h)
  // (slope-deflection method). A = 1e3 * I / h^2 makes axial shortening negligible (~1e-6).
  const double h = 3.0, bw = 4.0, I = 1e-5;
  const Section s{2e11, 7800.0, 1e3 * I / (h * h) * 1e3, I};
  FrameModel<double> model;
  const auto n0 = model.add_node(0, 0), n1 = model.add_node(0, h), n2 = model.add_node(bw, h),
             n3 = model.add_node(bw, 0);
  model.add_member(n0, n1, s, 3);
  model.add_member(n1, n2, s, 4);
  model.add_member(n3, n2, s, 5);
  model.clamp(n0);
  model.clamp(n3);
  const double F = 1e3;
  const auto frame = model.assemble();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(frame.num_free());
  f(frame.dofs.free_index(n1, Dof::X)) = F;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(frame.stiffness);
  const Eigen::VectorXd d = ldlt.solve(f);
  const double rho = (I / bw) / (I / h);
  const double k = 24 * s.E * I / (h * h * h) * (6 * rho + 1) / (6 * rho + 4);
  EXPECT_NEAR(d(frame.dofs.free_index(n1, Dof::X)) * k / F, 1.0, 1e-5);
}

TEST(FrameModel, DofMapEliminatesSupportedDofs) {
  FrameModel<double> model;
  const auto a = model.add_node(0, 0), b = model.add_node(1, 0), c = model.add_node(2, 0);
  model.add_member(a, b, slender_steel(), 2);  // interior node 3
  model.add_member(b, c, slender_steel(), 1);
  model.clamp(a);
  model.fix(c, Dof::Y);
  const auto frame = model.assemble();
  const DofMap& map = frame.dofs;
  EXPECT_EQ(map.num_nodes(), 4);
  EXPECT_EQ(map.num_free(), 12 - 4);
  EXPECT_EQ(map.free_index(a, Dof::X), -1);
  EXPECT_EQ(map.free_index(c, Dof::Y), -1);
  EXPECT_TRUE(map.is_free(c, Dof::X));
  for (Eigen::Index i = 0; i < map.num_free(); ++i) {
    const auto nd = map.node_dof(i);
    EXPECT_EQ(map.free_index(nd.first, nd.second), i);
  }
  const Eigen::VectorXd free = Eigen::VectorXd::LinSpaced(map.num_free(), 1.0, 8.0);
  const Eigen::VectorXd full = map.scatter(free);
  EXPECT_EQ(full(3 * a), 0.0);
  EXPECT_EQ(map.gather(full), free);
  EXPECT_EQ(frame.stiffness.rows(), 8);
  EXPECT_INVALID_ARGUMENT(map.free_index(4, Dof::X), "node = 4 does not exist");
  EXPECT_INVALID_ARGUMENT(map.node_dof(8), "free index 8");
  EXPECT_INVALID_ARGUMENT(map.scatter(Eigen::VectorXd(3)), "free.size() = 3");
}

TEST(FrameModel, AssemblyCostIsLinear) {
  // 36 entries per element at most: nnz(K) <= 36 * elements for a chain (shared nodes add up).
  for (int n : {10, 1000}) {
    const auto frame = cantilever(1.0, n).assemble();
    EXPECT_LE(frame.stiffness.nonZeros(), 36 * n);
    EXPECT_EQ(frame.mass.nonZeros(), frame.stiffness.nonZeros());
    EXPECT_EQ(cantilever(1.0, n).assemble(MassType::Lumped).mass.nonZeros(), 3 * n);
  }
}

TEST(FrameModel, CountsRigidBodyModesFromSupports) {
  // Plane rigid motions: 2 translations + 1 rotation per connected part, minus independent
  // supports.
  const auto count = [](auto&& configure) {
    FrameModel<double> m;
    const auto a = m.add_node(0, 0), b = m.add_node(1, 0), c = m.add_node(1, 1);
    m.add_member(a, b, slender_steel(), 2);
    m.add_member(b, c, slender_steel(), 2);
    configure(m, a, b, c);
    return m.assemble().num_rigid_body_modes;
  };
  using M = FrameModel<double>;
  using I = Eigen::Index;
  EXPECT_EQ(count([](M&, I, I, I) {}), 3);
  EXPECT_EQ(count([](M& m, I a, I, I) { m.pin(a); }), 1);
  EXPECT_EQ(count([](M& m, I a, I, I) { m.clamp(a); }), 0);
  EXPECT_EQ(count([](M& m, I a, I, I) { m.fix(a, Dof::Y); }), 2);
  EXPECT_EQ(count([](M& m, I a, I, I c) { m.fix(a, Dof::Y); m.fix(c, Dof::Y); }), 1);  // parallel rollers
  // Rollers at a (Y) and c (X): their reaction lines meet at (0, 1), a free rotation centre.
  EXPECT_EQ(count([](M& m, I a, I, I c) { m.fix(a, Dof::Y); m.fix(c, Dof::X); }), 1);
  EXPECT_EQ(count([](M& m, I a, I b, I c) { m.fix(a, Dof::Y); m.fix(b, Dof::Y); m.fix(c, Dof::X); }), 0);
  EXPECT_EQ(count([](M& m, I a, I, I c) { m.pin(a); m.add_spring(c, Dof::X, 10.0); }), 0);
  // Two separate parts: 3 + 3 rigid modes.
  FrameModel<double> two;
  const auto p = two.add_node(0, 0), q = two.add_node(1, 0), r = two.add_node(0, 1), t = two.add_node(1, 1);
  two.add_member(p, q, slender_steel(), 1);
  two.add_member(r, t, slender_steel(), 1);
  EXPECT_EQ(two.assemble().num_rigid_body_modes, 6);
}

TEST(FrameModel, IdIsUniqueAndChangesOnMutation) {
  FrameModel<double> a, b;
  EXPECT_NE(a.id(), b.id());
  const auto n0 = a.add_node(0, 0);
  const auto id1 = a.id();
  const FrameModel<double> copy = a;
  EXPECT_EQ(copy.id(), id1);
  a.add_node(1, 0);
  EXPECT_NE(a.id(), id1);
  const auto id2 = a.id();
  a.clamp(n0);
  EXPECT_NE(a.id(), id2);
  a.add_member(0, 1, slender_steel(), 2);
  EXPECT_EQ(a.assemble().model_id, a.id());
}

TEST(FrameModel, RejectsBadInput) {
  FrameModel<double> m;
  const auto a = m.add_node(0, 0), b = m.add_node(1, 0), c = m.add_node(1, 1);
  const Section s = slender_steel();
  EXPECT_INVALID_ARGUMENT(m.add_member(a, 7, s, 2), "node_b = 7 does not exist (model has 3 nodes)");
  EXPECT_INVALID_ARGUMENT(m.add_member(-1, b, s, 2), "node_a = -1 does not exist");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, a, s, 2), "zero-length member");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, s, 0), "elements must be in [1, max_elements_per_member");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{2e11, 0.0, 1e-4, 1e-9}), 2), "section.rho");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, (Section{2e11, 7800.0, 1e-4, -1.0}), 2), "section.I");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, s, std::vector<double>{0.0, 0.5, 0.4, 1.0}), "strictly ascending");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, s, std::vector<double>{0.0, 0.9}), "stations.back()");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, s, std::vector<double>{0.1, 1.0}), "stations.front()");
  EXPECT_INVALID_ARGUMENT(m.add_member(a, b, s, std::vector<double>{0.0}), "stations.size()");
  EXPECT_INVALID_ARGUMENT(m.add_node(1.0, 1e-12), "coincides with node 1");
  EXPECT_INVALID_ARGUMENT(m.add_node(std::nan(""), 0.0), "x must be finite");
  EXPECT_INVALID_ARGUMENT(m.clamp(3), "FrameModel::clamp: node = 3 does not exist");
  EXPECT_INVALID_ARGUMENT(m.pin(9), "FrameModel::pin: node = 9");
  EXPECT_INVALID_ARGUMENT(m.fix(-2, Dof::X), "FrameModel::fix: node = -2");
  EXPECT_INVALID_ARGUMENT(m.add_point_mass(a, -1.0), "m must be finite and >= 0");
  EXPECT_INVALID_ARGUMENT(m.add_rotary_inertia(a, INFINITY), "J must be finite");
  EXPECT_INVALID_ARGUMENT(m.add_spring(c, Dof::Rz, -5.0), "k must be finite and >= 0");
  EXPECT_INVALID_ARGUMENT(m.member(0), "id = 0 does not exist (model has 0 members)");
  EXPECT_INVALID_ARGUMENT(m.node_position(3), "node = 3 does not exist");
  // Node c is not attached to a member and has no mass.
  m.add_member(a, b, s, 2);
  EXPECT_INVALID_ARGUMENT(m.assemble(), "of node 2 is free but has no mass");
  // No free DOFs at all.
  FrameModel<double> fixed;
  const auto f0 = fixed.add_node(0, 0), f1 = fixed.add_node(1, 0);
  fixed.add_member(f0, f1, s, 1);
  fixed.clamp(f0);
  fixed.clamp(f1);
  EXPECT_INVALID_ARGUMENT(fixed.assemble(), "no free DOFs");
}

}  // namespace

// Tests of MemberShapes built from raw nodal data (no FrameModel): interpolation properties,
// element location, end policies, point-load projections, construction errors.

#include "stickslip/moving_load/member_shapes.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "moving_load/moving_load_test_support.hpp"

namespace stickslip {
namespace {

using test::random_member;
using Shapes = MemberShapes<double>;
using Values = Shapes::Values;

constexpr double kLength = 0.04;  // the paper's platform length L2 [m]

// Every nodal value must be reproduced bit for bit: the shape-function weights are exactly 0 or
// 1 at xi = 0 and xi = 1 (factored forms), and xi is exactly 0 at a node that starts an element
// and exactly 1 at the member end (same rounded element length in numerator and denominator).
TEST(MemberShapes, NodalValuesEqualNodalModeComponentsExactly) {
  std::mt19937_64 rng(test::announced_seed(20240611));
  const auto data = random_member(rng, 13, 7, kLength, 2);
  const Shapes shapes(data);
  Values v;
  ElementCursor cursor;
  for (Eigen::Index k = 0; k < data.stations.size(); ++k) {
    for (int pass = 0; pass < 2; ++pass) {  // with the binary search, then with the cursor
      if (pass == 0) shapes.evaluate(data.stations(k), v);
      else shapes.evaluate(data.stations(k), v, cursor);
      for (Eigen::Index j = 0; j < 7; ++j) {
        EXPECT_EQ(v.psi_u(j), data.u(k, j)) << "node " << k << " mode " << j;
        EXPECT_EQ(v.psi_w(j), data.w(k, j)) << "node " << k << " mode " << j;
        EXPECT_EQ(v.dpsi_w(j), data.theta(k, j)) << "node " << k << " mode " << j;
      }
    }
  }
}

// psi_u, psi_w and psi_w' are continuous at interior nodes (C0 / C1 Hermite interpolation): the
// left element evaluated at its right end and the right element at its left end both give the
// nodal components exactly.
TEST(MemberShapes, DisplacementAndSlopeContinuousAcrossElements) {
  std::mt19937_64 rng(test::announced_seed(7));
  const auto data = random_member(rng, 9, 5, kLength);
  const Shapes shapes(data);
  Values left, right;
  for (Eigen::Index k = 1; k < shapes.num_elements(); ++k) {
    const double s = data.stations(k);
    shapes.evaluate_in_element(k - 1, s, left);
    shapes.evaluate_in_element(k, s, right);
    EXPECT_EIGEN_NEAR(left.psi_u, right.psi_u, 0.0);
    EXPECT_EIGEN_NEAR(left.psi_w, right.psi_w, 0.0);
    EXPECT_EIGEN_NEAR(left.dpsi_w, right.dpsi_w, 0.0);
    // Curvature is only piecewise linear: random nodal data give a jump at the node.
    EXPECT_GT((left.ddpsi_w - right.ddpsi_w).cwiseAbs().maxCoeff(), 1.0);
  }
}

// Hermite cubics interpolate any cubic exactly and linear functions interpolate a linear axial
// field exactly, so nodal data sampled from w(x) = a + b x + c x^2 + d x^3 (theta = w') and
// u(x) = p + r x give psi_w = w, psi_w' = w', psi_w'' = 2c + 6 d x, psi_u = u, psi_u' = r at every
// point. Tolerance: rounding only. The k-th derivative sums terms of size ~|w| / Le^k (the shape
// functions' derivatives scale as Le^-k) that cancel to the result, so its error is a few unit
// roundoffs times W / Le^k, W the largest nodal value; 64 eps W / Le^k bounds it.
TEST(MemberShapes, ReproducesCubicTransverseAndLinearAxialFieldsExactly) {
  std::mt19937_64 rng(test::announced_seed(99));
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto data = random_member(rng, 11, 4, kLength);
  const Eigen::Index n = 4;
  Eigen::VectorXd a(n), b(n), c(n), d(n), p(n), r(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    a(j) = unit(rng);
    b(j) = unit(rng) / kLength;
    c(j) = unit(rng) / (kLength * kLength);
    d(j) = unit(rng) / (kLength * kLength * kLength);
    p(j) = unit(rng);
    r(j) = unit(rng) / kLength;
  }
  const auto w = [&](double x) { return (a + x * (b + x * (c + x * d))).eval(); };
  const auto dw = [&](double x) { return (b + x * (2 * c + 3 * x * d)).eval(); };
  const auto ddw = [&](double x) { return (2 * c + 6 * x * d).eval(); };
  for (Eigen::Index k = 0; k < data.stations.size(); ++k) {
    const double x = data.stations(k);
    data.w.row(k) = w(x).transpose();
    data.theta.row(k) = dw(x).transpose();
    data.u.row(k) = (p + x * r).transpose();
  }
  const Shapes shapes(data);
  const double le_min = (data.stations.tail(11) - data.stations.head(11)).minCoeff();
  const double W = std::max(data.w.cwiseAbs().maxCoeff(),
                            le_min * data.theta.cwiseAbs().maxCoeff());
  const double U = data.u.cwiseAbs().maxCoeff();
  const double tol = 64 * std::numeric_limits<double>::epsilon();
  Values v;
  ElementCursor cursor;
  std::uniform_real_distribution<double> where(0.0, kLength);
  for (int i = 0; i < 200; ++i) {
    const double x = where(rng);
    shapes.evaluate(x, v, cursor);
    EXPECT_EIGEN_NEAR(v.psi_w, w(x), tol * W);
    EXPECT_EIGEN_NEAR(v.dpsi_w, dw(x), tol * W / le_min);
    EXPECT_EIGEN_NEAR(v.ddpsi_w, ddw(x), tol * W / (le_min * le_min));
    EXPECT_EIGEN_NEAR(v.psi_u, (p + x * r).eval(), tol * U);
    EXPECT_EIGEN_NEAR(v.dpsi_u, r, tol * U / le_min);
  }
}

// psi_w'' against an independent computation: the element's cubic in monomial form
// w(x) = c0 + c1 x + c2 x^2 + c3 x^3 solved (LU) from w(0) = w_a, w'(0) = theta_a,
// w(Le) = w_b, w'(Le) = theta_b, whose second derivative is 2 c2 + 6 c3 x. Tolerance: rounding,
// ~1e-13 relative to |w''| ~ 10 / Le^2 (the LU solve of the badly scaled 4x4 system loses a few
// more digits than the shape-function sum).
TEST(MemberShapes, CurvatureMatchesElementCubicSecondDerivative) {
  std::mt19937_64 rng(test::announced_seed(4242));
  const auto data = random_member(rng, 6, 3, kLength);
  const Shapes shapes(data);
  Values v;
  for (Eigen::Index e = 0; e < shapes.num_elements(); ++e) {
    const double s0 = data.stations(e), le = data.stations(e + 1) - s0;
    Eigen::Matrix4d A;
    A << 1, 0, 0, 0,  //
        0, 1, 0, 0,   //
        1, le, le * le, le * le * le, 0, 1, 2 * le, 3 * le * le;
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(A);
    for (const double xi : {0.0, 0.13, 0.5, 0.77, 0.999}) {
      const double x = xi * le;
      shapes.evaluate_in_element(e, s0 + x, v);
      for (Eigen::Index j = 0; j < 3; ++j) {
        const Eigen::Vector4d rhs(data.w(e, j), data.theta(e, j), data.w(e + 1, j),
                                  data.theta(e + 1, j));
        const Eigen::Vector4d cf = lu.solve(rhs);
        EXPECT_NEAR(v.ddpsi_w(j), 2 * cf(2) + 6 * cf(3) * x, 1e-12 / (le * le))
            << "element " << e << " xi " << xi << " mode " << j;
      }
    }
  }
}

// Derivatives against central differences of the values at interior points of elements. For a
// cubic the central-difference error of w' is exactly h^2 w'''/6, so the measured order is 2;
// w'' from differences of w' (quadratic) and u' from differences of u (linear) are exact up to
// rounding: the cancellation in f(x + h) - f(x - h) costs ~eps |f| / h, and each value carries a
// few eps of the (up to ~10x larger) terms of its shape-function sum; 64 eps |f|_max / h bounds it.
TEST(MemberShapes, DerivativesAgreeWithFiniteDifferences) {
  std::mt19937_64 rng(test::announced_seed(31337));
  const auto data = random_member(rng, 8, 6, kLength);
  const Shapes shapes(data);
  Values plus, minus, centre;
  std::uniform_real_distribution<double> xi_dist(0.2, 0.8);
  for (Eigen::Index e = 0; e < shapes.num_elements(); ++e) {
    const double s0 = data.stations(e), le = data.stations(e + 1) - s0;
    const double x = s0 + xi_dist(rng) * le;
    shapes.evaluate(x, centre);
    const auto fd_error = [&](double h) {
      shapes.evaluate(x + h, plus);
      shapes.evaluate(x - h, minus);
      return ((plus.psi_w - minus.psi_w) / (2 * h) - centre.dpsi_w).cwiseAbs().maxCoeff();
    };
    const double h = 1e-2 * le;
    EXPECT_NEAR(std::log2(fd_error(h) / fd_error(h / 2)), 2.0, 0.05) << "element " << e;
    shapes.evaluate(x + h, plus);
    shapes.evaluate(x - h, minus);
    const double rounding = 64 * std::numeric_limits<double>::epsilon() / h;
    EXPECT_EIGEN_NEAR(((plus.dpsi_w - minus.dpsi_w) / (2 * h)).eval(), centre.ddpsi_w,
                      rounding * centre.dpsi_w.cwiseAbs().maxCoeff());
    EXPECT_EIGEN_NEAR(((plus.psi_u - minus.psi_u) / (2 * h)).eval(), centre.dpsi_u,
                      rounding * centre.psi_u.cwiseAbs().maxCoeff());
  }
}

// A fixed number of modes gives the same numbers as the dynamic layout.
TEST(MemberShapes, FixedModesMatchDynamicModes) {
  std::mt19937_64 rng(test::announced_seed(5));
  const auto data = random_member(rng, 10, 6, kLength);
  const Shapes dynamic_shapes(data);
  const MemberShapes<double, 6> fixed_shapes(data);
  MemberShapes<double, 6>::Values fv;
  ElementCursor cursor;
  std::uniform_real_distribution<double> where(0.0, kLength);
  for (int i = 0; i < 50; ++i) {
    const double x = where(rng);
    const Values dv = dynamic_shapes.evaluate(x);
    fixed_shapes.evaluate(x, fv, cursor);
    EXPECT_EIGEN_NEAR(fv.psi_u, dv.psi_u, 1e-15);
    EXPECT_EIGEN_NEAR(fv.psi_w, dv.psi_w, 1e-15);
    EXPECT_EIGEN_NEAR(fv.dpsi_w, dv.dpsi_w, 1e-15 / kLength);
    EXPECT_EIGEN_NEAR(fv.ddpsi_w, dv.ddpsi_w, 1e-15 / (kLength * kLength));
  }
}

// Element location: the element [s_e, s_e+1) (last one closed) by brute force, for the binary
// search and for cursors that are fresh, in the right element, a neighbour, far away, or stale.
TEST(MemberShapes, LocatesElementWithAndWithoutCursor) {
  std::mt19937_64 rng(test::announced_seed(11));
  const auto data = random_member(rng, 37, 2, kLength);
  const Shapes shapes(data);
  const auto brute = [&](double x) {
    Eigen::Index e = 0;
    while (e + 1 < shapes.num_elements() && x >= data.stations(e + 1)) ++e;
    return e;
  };
  std::uniform_real_distribution<double> where(0.0, kLength);
  std::uniform_int_distribution<Eigen::Index> any_hint(-3, 60);
  ElementCursor walking;
  for (int i = 0; i < 2000; ++i) {
    double x = where(rng);
    if (i % 5 == 0) x = data.stations(i % data.stations.size());  // exactly on a node
    const Eigen::Index expected = brute(x);
    EXPECT_EQ(shapes.locate_element(x), expected) << "x = " << x;
    ElementCursor hint{any_hint(rng)};
    EXPECT_EQ(shapes.locate_element(x, hint), expected) << "x = " << x;
    EXPECT_EQ(hint.element, expected);
    EXPECT_EQ(shapes.locate_element(x, walking), expected) << "x = " << x;
  }
  EXPECT_EQ(shapes.locate_element(0.0), 0);
  EXPECT_EQ(shapes.locate_element(kLength), shapes.num_elements() - 1);
  // A slowly moving point: the cursor follows it element by element.
  ElementCursor cursor;
  for (double x = 0.0; x <= kLength; x += kLength / 997) {
    EXPECT_EQ(shapes.locate_element(x, cursor), brute(x));
  }
}

// locate() gives the element and the shape-function weights with which every row of evaluate()
// is the element's nodal block times a weight vector (eqs 4-7), under each end policy, and
// follows the end policy exactly as evaluate() does. The reference is evaluate() itself (its own
// fused loop); the two sum the same four products in a different order, so they agree to a few
// ulps of the largest nodal value: 1e-14 relative.
TEST(MemberShapes, LocateGivesElementBlockAndWeightsOfEveryRow) {
  std::mt19937_64 rng(test::announced_seed(12));
  const auto data = random_member(rng, 9, 5, kLength);
  std::uniform_real_distribution<double> where(-0.2 * kLength, 1.2 * kLength);
  for (const EndPolicy policy : {EndPolicy::Clamp, EndPolicy::Extrapolate}) {
    const Shapes shapes(data, policy);
    ElementCursor cursor, eval_cursor;
    for (int i = 0; i < 200; ++i) {
      const double x = i % 7 == 0 ? data.stations(i % data.stations.size()) : where(rng);
      const auto loc = shapes.locate(x, cursor);
      EXPECT_EQ(cursor.element, loc.element);
      EXPECT_EQ(loc.element, shapes.locate_element(x)) << "x = " << x;
      const auto B = shapes.element_block(loc.element);
      const auto& w = loc.weights;
      Eigen::Matrix<double, 6, 1> cu, cdu, cw, cdw, cddw;
      cu << w.u1, 0, 0, w.u2, 0, 0;
      cdu << -w.du, 0, 0, w.du, 0, 0;
      cw << 0, w.w1, w.t1, 0, w.w2, w.t2;
      cdw << 0, w.dw1, w.dt1, 0, w.dw2, w.dt2;
      cddw << 0, w.ddw1, w.ddt1, 0, w.ddw2, w.ddt2;
      Values v;
      shapes.evaluate(x, v, eval_cursor);
      // Round-off scale of each row: the sum of the absolute products, |B| |c|.
      const auto check = [&](const Eigen::Matrix<double, 6, 1>& c, const Eigen::VectorXd& row, const char* name) {
        const double tol = 1e-14 * (B.cwiseAbs() * c.cwiseAbs()).maxCoeff();
        EXPECT_EIGEN_NEAR(Eigen::VectorXd(B * c), row, tol) << name << ", " << to_string(policy) << ", x = " << x;
      };
      check(cu, v.psi_u, "psi_u");
      check(cdu, v.dpsi_u, "dpsi_u");
      check(cw, v.psi_w, "psi_w");
      check(cdw, v.dpsi_w, "dpsi_w");
      check(cddw, v.ddpsi_w, "ddpsi_w");
    }
  }
  const Shapes strict(data);
  ElementCursor cursor;
  EXPECT_THROW(strict.locate(1.01 * kLength, cursor), std::invalid_argument);
  EXPECT_THROW(strict.locate(std::nan(""), cursor), std::invalid_argument);
}

// Throw (default): a point off the member is an error naming the member, eps and the range; the
// ends themselves are on the member. Non-finite eps is an error under every policy.
TEST(MemberShapes, ThrowPolicyNamesMemberEpsAndRange) {
  std::mt19937_64 rng(test::announced_seed(3));
  const auto data = random_member(rng, 4, 3, kLength, 1);
  const Shapes shapes(data);
  EXPECT_EQ(shapes.end_policy(), EndPolicy::Throw);
  Values v;
  EXPECT_NO_THROW(shapes.evaluate(0.0, v));
  EXPECT_NO_THROW(shapes.evaluate(kLength, v));
  EXPECT_TRUE(shapes.contains(0.0));
  EXPECT_TRUE(shapes.contains(kLength));
  EXPECT_FALSE(shapes.contains(std::nextafter(kLength, 1.0)));
  EXPECT_FALSE(shapes.contains(-1e-300));
  try {
    shapes.evaluate(0.0412, v);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "MemberShapes::evaluate: eps = 0.0412 is off member 1 (valid range [0, 0.04])");
  }
  EXPECT_THROW(shapes.evaluate(-1e-12, v), std::invalid_argument);
  EXPECT_THROW(shapes.evaluate(std::nextafter(kLength, 1.0), v), std::invalid_argument);
  EXPECT_THROW(shapes.locate_element(-0.001), std::invalid_argument);
  EXPECT_THROW(shapes.modal_force(0.05, 1.0, 1.0, 1.0), std::invalid_argument);
  Shapes::Vector gx, gy;
  ElementCursor cursor;
  EXPECT_THROW(shapes.evaluate_global(0.05, gx, gy, cursor), std::invalid_argument);
  for (const EndPolicy policy : {EndPolicy::Throw, EndPolicy::Clamp, EndPolicy::Extrapolate}) {
    const Shapes s(data, policy);
    EXPECT_THROW(s.evaluate(std::nan(""), v), std::invalid_argument) << to_string(policy);
    EXPECT_THROW(s.evaluate(HUGE_VAL, v), std::invalid_argument) << to_string(policy);
  }
}

// Clamp: off the member, the values (and derivatives) of the nearest end.
TEST(MemberShapes, ClampPolicyUsesNearestEnd) {
  std::mt19937_64 rng(test::announced_seed(8));
  const auto data = random_member(rng, 5, 3, kLength);
  const Shapes shapes(data, EndPolicy::Clamp);
  const Values at0 = shapes.evaluate(0.0), atL = shapes.evaluate(kLength);
  for (const double x : {-1.0, -1e-9}) {
    const Values v = shapes.evaluate(x);
    EXPECT_EIGEN_NEAR(v.psi_w, at0.psi_w, 0.0);
    EXPECT_EIGEN_NEAR(v.ddpsi_w, at0.ddpsi_w, 0.0);
  }
  for (const double x : {kLength + 1e-9, 3.0}) {
    const Values v = shapes.evaluate(x);
    EXPECT_EIGEN_NEAR(v.psi_u, atL.psi_u, 0.0);
    EXPECT_EIGEN_NEAR(v.dpsi_w, atL.dpsi_w, 0.0);
  }
}

// Extrapolate: the end element's polynomials continued beyond the end.
TEST(MemberShapes, ExtrapolatePolicyContinuesEndElement) {
  std::mt19937_64 rng(test::announced_seed(9));
  const auto data = random_member(rng, 5, 3, kLength);
  const Shapes shapes(data, EndPolicy::Extrapolate);
  Values expected;
  const double beyond = kLength * 1.1;
  shapes.evaluate_in_element(shapes.num_elements() - 1, beyond, expected);
  const Values v = shapes.evaluate(beyond);
  EXPECT_EIGEN_NEAR(v.psi_w, expected.psi_w, 0.0);
  EXPECT_EIGEN_NEAR(v.ddpsi_w, expected.ddpsi_w, 0.0);
  shapes.evaluate_in_element(0, -0.1 * kLength, expected);
  EXPECT_EIGEN_NEAR(shapes.evaluate(-0.1 * kLength).dpsi_w, expected.dpsi_w, 0.0);
  // The continued cubic is not the nodal value at the end any more.
  EXPECT_GT((v.psi_w - data.w.bottomRows(1).transpose()).cwiseAbs().maxCoeff(), 1e-3);
}

// Global components are the local ones rotated by the member direction:
// X = c u - s w, Y = s u + c w.
TEST(MemberShapes, GlobalComponentsAreRotatedLocalOnes) {
  std::mt19937_64 rng(test::announced_seed(12));
  const auto data = random_member(rng, 7, 4, kLength);
  const Shapes shapes(data);
  Shapes::Vector gx, gy;
  ElementCursor cursor;
  for (const double x : {0.0, 0.011, 0.02, 0.039, kLength}) {
    const Values v = shapes.evaluate(x);
    shapes.evaluate_global(x, gx, gy, cursor);
    EXPECT_EIGEN_NEAR(gx, (data.cos * v.psi_u - data.sin * v.psi_w).eval(), 1e-15);
    EXPECT_EIGEN_NEAR(gy, (data.sin * v.psi_u + data.cos * v.psi_w).eval(), 1e-15);
  }
}

// Generalised force Q = psi_u Fa + psi_w Ft + psi_w' M (computed here from evaluate()), and the
// consistent nodal load is work-equivalent: Phi^T f = Q for the global mode matrix Phi of the
// member's nodes (X = c u - s w, Y = s u + c w, Rz = theta), with constrained DOFs dropped from
// both. Tolerance: sums of ~6 products of O(1) numbers, relative rounding ~1e-15.
TEST(MemberShapes, ModalForceAndConsistentLoadAreWorkEquivalent) {
  std::mt19937_64 rng(test::announced_seed(2718));
  auto data = random_member(rng, 6, 5, kLength);
  const Eigen::Index nodes = data.stations.size();
  // Number the member's DOFs as in a model where the first node is pinned (X, Y fixed) and
  // the DOFs of the others are free, shuffled by an offset of 4 other free DOFs.
  data.free_dofs.resize(3 * nodes);
  Eigen::Index next = 4;
  for (Eigen::Index g = 0; g < 3 * nodes; ++g) data.free_dofs(g) = (g < 2) ? -1 : next++;
  data.num_free = next;
  // A mode has no component on a constrained DOF: X = Y = 0 at the pin means u = w = 0 there.
  data.u.row(0).setZero();
  data.w.row(0).setZero();
  Eigen::MatrixXd phi = Eigen::MatrixXd::Random(data.num_free, 5);  // other DOFs: arbitrary
  for (Eigen::Index k = 0; k < nodes; ++k) {
    const Eigen::RowVectorXd X = data.cos * data.u.row(k) - data.sin * data.w.row(k);
    const Eigen::RowVectorXd Y = data.sin * data.u.row(k) + data.cos * data.w.row(k);
    const Eigen::RowVectorXd comps[3] = {X, Y, data.theta.row(k)};
    for (Eigen::Index d = 0; d < 3; ++d) {
      const Eigen::Index i = data.free_dofs(3 * k + d);
      if (i >= 0) phi.row(i) = comps[d];
    }
  }
  const Shapes shapes(data);
  ASSERT_TRUE(shapes.has_dof_numbering());
  std::uniform_real_distribution<double> where(0.0, kLength), force(-10.0, 10.0);
  for (int i = 0; i < 20; ++i) {
    const double x = (i == 0) ? 0.0 : where(rng);  // x = 0 puts the load on the pinned node
    const double fa = force(rng), ft = force(rng), m = force(rng) * kLength;
    const Values v = shapes.evaluate(x);
    const Eigen::VectorXd q = shapes.modal_force(x, fa, ft, m);
    EXPECT_EIGEN_NEAR(q, (v.psi_u * fa + v.psi_w * ft + v.dpsi_w * m).eval(), 1e-13);
    const Eigen::VectorXd f = shapes.consistent_nodal_load(x, fa, ft, m);
    ASSERT_EQ(f.size(), data.num_free);
    EXPECT_EQ(f.head(4).cwiseAbs().maxCoeff(), 0.0);  // other DOFs carry nothing
    if (i == 0) {
      // On the pinned node only the moment stays: Rz of node 0 is free index 4.
      EXPECT_NEAR(f(4), m, 1e-15);
      EXPECT_NEAR(f.tail(f.size() - 5).cwiseAbs().maxCoeff(), 0.0, 1e-15);
      EXPECT_EIGEN_NEAR((phi.transpose() * f).eval(), (v.dpsi_w * m).eval(), 1e-13);
    } else {
      EXPECT_EIGEN_NEAR((phi.transpose() * f).eval(), q, 1e-13);
    }
  }
  // The same load with a reused cursor, allocation-free overload.
  Shapes::Vector out;
  ElementCursor cursor;
  shapes.modal_force(0.03, 1.0, 2.0, 0.1, out, cursor);
  EXPECT_EIGEN_NEAR(out, shapes.modal_force(0.03, 1.0, 2.0, 0.1), 0.0);
  EXPECT_EQ(cursor.element, shapes.locate_element(0.03));
}

TEST(MemberShapes, ConsistentLoadNeedsDofNumbering) {
  std::mt19937_64 rng(test::announced_seed(1));
  const Shapes shapes(random_member(rng, 3, 2, kLength, 4));
  EXPECT_FALSE(shapes.has_dof_numbering());
  EXPECT_THROW(shapes.consistent_nodal_load(0.01, 1.0, 0.0, 0.0), std::invalid_argument);
}

// Construction from inconsistent raw data is a caller error with a message naming the field.
TEST(MemberShapes, RejectsInconsistentNodalData) {
  std::mt19937_64 rng(test::announced_seed(17));
  const auto good = random_member(rng, 4, 3, kLength);
  const auto expect_error = [](const MemberNodalModes<double>& d, const std::string& text) {
    try {
      const Shapes s(d);
      ADD_FAILURE() << "no exception, expected one mentioning '" << text << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  auto d = good;
  d.stations(0) = 1e-3;
  expect_error(d, "stations must start at 0");
  d = good;
  d.stations(2) = d.stations(1);
  expect_error(d, "strictly ascending");
  d = good;
  d.stations.resize(1);
  expect_error(d, "stations needs >= 2");
  d = good;
  d.w.conservativeResize(4, 3);
  expect_error(d, "w must be 5 x 3");
  d = good;
  d.theta.conservativeResize(5, 2);
  expect_error(d, "theta must be 5 x 3");
  d = good;
  d.u(1, 1) = std::nan("");
  expect_error(d, "u must be finite");
  d = good;
  d.cos = 1.0;
  d.sin = 0.5;
  expect_error(d, "unit vector");
  d = good;
  d.free_dofs = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>::Constant(7, -1);
  expect_error(d, "3 entries per node");
  d = good;
  d.free_dofs = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>::Constant(15, 3);
  d.num_free = 3;
  expect_error(d, "free_dofs must lie in [-1, num_free)");
  try {
    const MemberShapes<double, 6> fixed(good);
    ADD_FAILURE() << "no exception for Modes = 6 with 3 modes";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fixed Modes = 6"), std::string::npos) << e.what();
  }
  Values v;
  const Shapes shapes(good);
  EXPECT_THROW(shapes.evaluate_in_element(4, 0.01, v), std::invalid_argument);
  EXPECT_THROW(shapes.evaluate_in_element(-1, 0.01, v), std::invalid_argument);
}

}  // namespace
}  // namespace stickslip

#pragma once
// Shared by the ContactSystem tests with rigid bodies: two cantilever platforms, a wedge damper
// between their tips whose normal forces come from the wedge's statics by hand, and the static
// state of a system holding that wedge (platforms deflected, damper at rest with closed gaps).

#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace wedge_scene {

using namespace stickslip;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;
using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = 3.14159265358979323846;
inline const SectionProperties<double> kPlatform{2.06e11, 7800, 1e-4, 1e-8};

/// A one-mode cantilever the bodies never touch (the scene needs a structure).
struct Ground {
  FrameModel<double> frame;
  ModalBasis<double> basis;
  Ground() {
    const NodeId root = frame.add_node(0, 0), tip = frame.add_node(0, 0.1);
    frame.add_member(root, tip, kPlatform, 2);
    frame.clamp(root);
    ModalOptions<double> mo;
    mo.num_modes = 1;
    basis = compute_modes(frame.assemble(), mo);
  }
};

/// Two horizontal cantilever platforms of length 0.125 m, clamped at x = -0.25 and x = +0.25,
/// their tips (the platform points) at x = -0.125 and x = +0.125.
struct Platforms {
  FrameModel<double> frame;
  MemberId left = 0, right = 0;
  NodeId tip_l = 0, tip_r = 0;
  ModalBasis<double> basis;
  explicit Platforms(Eigen::Index modes, double damping = 0.0) {
    const NodeId root_l = frame.add_node(-0.25, 0.0), root_r = frame.add_node(0.25, 0.0);
    tip_l = frame.add_node(-0.125, 0.0);
    tip_r = frame.add_node(0.125, 0.0);
    left = frame.add_member(root_l, tip_l, kPlatform, 4);
    right = frame.add_member(root_r, tip_r, kPlatform, 4);
    frame.clamp(root_l);
    frame.clamp(root_r);
    ModalOptions<double> mo;
    mo.num_modes = modes;
    mo.solver = ModalSolver::Dense;
    basis = compute_modes(frame.assemble(), mo);
    if (damping > 0) basis = basis.with_modal_damping(Vector::Constant(modes, damping));
  }
  StructurePoint<double> tip_left() const { return {left, 0.125}; }
  StructurePoint<double> tip_right() const { return {right, 0.125}; }
};

/// The wedge of the statics and frequency tests: face angles 30 and 45 degrees, one contact point
/// per face at (-a, h) and (b, h), b chosen (by hand) so that the frictionless normal forces
/// balance the moment about the centre of mass.
struct Wedge {
  double mass = 0.05, inertia = 2e-5, P = 100.0;
  double al = kPi / 6, ar = kPi / 4, a = 0.01, h = 0.004, b = 0;
  double Nl = 0, Nr = 0;  // by hand: N_l sin a_l = N_r sin a_r, N_l cos a_l + N_r cos a_r = P
  Vec2 nl, nr, rl, rr;    // contact normals (platform -> damper) and points
  Wedge() {
    Nl = P * std::sin(ar) / std::sin(al + ar);
    Nr = P * std::sin(al) / std::sin(al + ar);
    // Moments about the centre of mass of N_l n_l at (-a, h) and N_r n_r at (b, h) cancel.
    b = (Nl * (a * std::cos(al) - h * std::sin(al)) + Nr * h * std::sin(ar)) / (Nr * std::cos(ar));
    nl = Vec2(std::sin(al), -std::cos(al));
    nr = Vec2(-std::sin(ar), -std::cos(ar));
    rl = Vec2(-a, h);
    rr = Vec2(b, h);
  }
  WedgeDamper<double> build(const Platforms& p, double mu = 0.5) const {
    WedgeFace<double> left{{p.tip_left()}, rl, al, 0.0}, right{{p.tip_right()}, rr, ar, 0.0};
    return wedge_damper<double>(0, mass, inertia, P, left, right, CoulombLaw<double>(mu, mu));
  }
};

/// Structure part of a platform point's row along d (hand: the tip's nodal rows).
inline Vector nodal_row(const Platforms& p, NodeId node, const Vec2& d) {
  return (d.x() * p.basis.nodal(node, Dof::X) + d.y() * p.basis.nodal(node, Dof::Y)).transpose();
}

/// Modal coordinates of the platforms' static deflection under the forces -N_k n_k the wedge
/// exerts on them: omega^2 q = Phi^T F.
inline Vector static_deflection(const Platforms& p, const Wedge& w) {
  const Vector F = -w.Nl * nodal_row(p, p.tip_l, w.nl) - w.Nr * nodal_row(p, p.tip_r, w.nr);
  return F.cwiseQuotient(p.basis.omega().cwiseAbs2());
}

/// The static state: platforms deflected (static_deflection), the damper translated so that
/// both gaps are zero, n_k . (x, y) = n_k . u_k (theta = 0), at rest.
template <class System>
typename System::State static_state(const System& sys, const Platforms& p, const Wedge& w) {
  const Eigen::Index n = p.basis.size();
  typename System::State x = sys.initial_state();
  x.head(n) = static_deflection(p, w);
  Eigen::Matrix2d A;
  A << w.nl.transpose(), w.nr.transpose();
  const Eigen::Vector2d rhs(nodal_row(p, p.tip_l, w.nl).dot(x.head(n)), nodal_row(p, p.tip_r, w.nr).dot(x.head(n)));
  x.template segment<2>(n) = A.inverse() * rhs;
  return x;
}


/// Sorted real parts of the eigenvalues of -dz''/dz of `sys` at (mode, x) over its first m
/// coordinates, by central differences of evaluate() (step 1e-7).
template <class System>
std::vector<double> stuck_rates(System& sys, const typename System::Mode& mode, const typename System::State& x,
                                Eigen::Index m) {
  Matrix A(m, m);
  const double step = 1e-7;
  for (Eigen::Index j = 0; j < m; ++j) {
    typename System::State xp = x, xm = x;
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
  return lam;
}

/// The stuck wedge's linear system by hand, M = diag(1, m, m, J), K = diag(omega^2, 0, 0,
/// sum_k N_k n_k . r_k) (the preload's stiffness on theta: a force N n at R(theta) r has the
/// moment N n . (k x R r), whose theta-derivative is -N n . r), and `rows` constraint rows of
/// which the first four are the wedge's g_k = [-d . Psi_tip, d, d . (k x r)] (the rest zero).
struct HandSystem {
  Matrix M, K, G;
  HandSystem(const Platforms& p, const Wedge& w, Eigen::Index rows) {
    const Eigen::Index n = p.basis.size(), m = n + 3;
    M = Matrix::Identity(m, m);
    K = Matrix::Zero(m, m);
    G = Matrix::Zero(rows, m);
    M(n, n) = M(n + 1, n + 1) = w.mass;
    M(n + 2, n + 2) = w.inertia;
    K.topLeftCorner(n, n) = p.basis.omega().cwiseAbs2().asDiagonal();
    K(n + 2, n + 2) = w.Nl * w.nl.dot(w.rl) + w.Nr * w.nr.dot(w.rr);
    auto constraint = [&](Eigen::Index row, NodeId tip, const Vec2& d, const Vec2& r) {
      G.row(row).head(n) = -nodal_row(p, tip, d).transpose();
      G(row, n) = d.x();
      G(row, n + 1) = d.y();
      G(row, n + 2) = -d.x() * r.y() + d.y() * r.x();
    };
    const Vec2 tl(w.nl.y(), -w.nl.x()), tr(w.nr.y(), -w.nr.x());
    constraint(0, p.tip_l, w.nl, w.rl);
    constraint(1, p.tip_l, tl, w.rl);
    constraint(2, p.tip_r, w.nr, w.rr);
    constraint(3, p.tip_r, tr, w.rr);
  }
  /// The squared frequencies of the system constrained by the first `rows` rows of G: the
  /// eigenvalues of T^T K T against T^T M T, T the null space of those rows (ascending).
  Vector constrained_eigenvalues(Eigen::Index rows) const {
    const Matrix T = G.topRows(rows).fullPivLu().kernel();
    Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> ref(T.transpose() * K * T, T.transpose() * M * T);
    return ref.eigenvalues();
  }
};

}  // namespace wedge_scene

#pragma once
/// \file blade_mirror.hpp
/// \brief The blade's mirror symmetry with a half-period shift: the T-shaped frame and its two
/// dampers are symmetric about the blade axis (x -> -x), and the lateral load F sin(W t) turns
/// into -F sin(W t) = F sin(W (t + T/2)) under the mirror, so x(t) is a solution iff
/// c + S (x(t + T/2) - c) is (stickslip::HalfPeriodSymmetry; docs/blade_damper.md).
///
/// S on the FrictionDampedSystem's state:
///   - modal coordinates and rates: S_q = Phi^T M P Phi, P the mirror of the frame's free DOFs
///     (node at (x, y) onto the node at (-x, y); u_x -> -u_x, u_y -> u_y, theta -> -theta);
///   - damper displacements and rates along the platform axis (+x): swapped, sign flipped;
///   - contact coordinates along the platform (left -> right): swapped, X -> L2 - X (the centre
///     c = L2 / 2);
///   - flight coordinates (normal, y): swapped;
///   - audit integrals: kept.
/// The mode image swaps the dampers' states, turns SlipPositive into SlipNegative and back, and
/// a rest at the wall at X = 0 into one at X = L2.

#include "blade_scene.hpp"

#include <stickslip/steady_state/half_period_symmetry.hpp>

#include <Eigen/Core>

#include <cmath>
#include <stdexcept>
#include <string>

namespace blade {

/// The mirror of `scene`'s frame, its modes and `system`'s state (the blade scene's two dampers,
/// in the order make_blade_system adds them). \throws std::invalid_argument when the frame's
/// nodes are not symmetric about x = 0 or the modal basis is not closed under the mirror (S_q
/// not orthogonal to 1e-8: a degenerate pair split by the truncation).
inline stickslip::HalfPeriodSymmetry<BladeScene::System> blade_half_period_symmetry(const BladeScene& scene,
                                                                                   const BladeScene::System& system) {
  using stickslip::Dof;
  static const std::string where = "blade_half_period_symmetry";
  const auto& frame = scene.frame;
  const auto fe = frame.assemble();
  const Index nf = fe.dofs.num_free(), n = scene.basis.size();
  if (system.num_dampers() != 2) throw std::invalid_argument(where + ": the scene must have its two dampers");
  // P: the mirror on the free DOFs.
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(nf, nf);
  const double tol = 1e-9 * (scene.parameters.L1 + scene.parameters.L2);
  for (Index a = 0; a < frame.num_nodes(); ++a) {
    const auto pa = frame.node_position(a);
    Index b = -1;
    for (Index c = 0; c < frame.num_nodes() && b < 0; ++c) {
      const auto pc = frame.node_position(c);
      if (std::abs(pc.x() + pa.x()) <= tol && std::abs(pc.y() - pa.y()) <= tol) b = c;
    }
    if (b < 0) throw std::invalid_argument(where + ": node " + std::to_string(a) + " has no mirror image");
    for (const auto& [dof, sign] : {std::pair{Dof::X, -1.0}, std::pair{Dof::Y, 1.0}, std::pair{Dof::Rz, -1.0}}) {
      const Index i = fe.dofs.free_index(a, dof), j = fe.dofs.free_index(b, dof);
      if ((i < 0) != (j < 0)) throw std::invalid_argument(where + ": the supports are not symmetric");
      if (i >= 0) P(j, i) = sign;
    }
  }
  const Eigen::MatrixXd& Phi = scene.basis.phi();
  const Eigen::MatrixXd M(fe.mass);
  const Eigen::MatrixXd Sq = Phi.transpose() * M * P * Phi;
  if (!((Sq * Sq.transpose() - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() <= 1e-8))
    throw std::invalid_argument(where + ": the modal basis is not closed under the mirror (S_q not orthogonal)");

  const Index N = system.state_size();
  stickslip::HalfPeriodSymmetry<BladeScene::System> sym;
  sym.S = Eigen::MatrixXd::Identity(N, N);
  sym.S.block(system.q_offset(), system.q_offset(), n, n) = Sq;
  sym.S.block(system.qd_offset(), system.qd_offset(), n, n) = Sq;
  auto swap = [&](Index offset, double sign) {
    sym.S(offset, offset) = sym.S(offset + 1, offset + 1) = 0;
    sym.S(offset, offset + 1) = sym.S(offset + 1, offset) = sign;
  };
  swap(system.x_offset(), -1);
  swap(system.xd_offset(), -1);
  bool affine = false;
  BladeScene::System::State c = BladeScene::System::State::Zero(N);
  if (system.contact_offset() >= 0) {
    swap(system.contact_offset(), -1);
    c.segment(system.contact_offset(), 2).setConstant(scene.parameters.L2 / 2);
    affine = true;
  }
  if (system.flight_offset() >= 0) {
    const Index S = system.num_separable();
    if (S != 2) throw std::invalid_argument(where + ": both dampers or neither may separate");
    swap(system.flight_offset(), 1);
    swap(system.flight_offset() + S, 1);
  }
  if (affine) sym.centre = c;
  sym.mode_image = [](const BladeScene::System::Mode& m) {
    BladeScene::System::Mode out = m;
    for (Index i = 0; i < 2; ++i) {
      stickslip::ContactState s = m[1 - i];
      if (s == stickslip::ContactState::SlipPositive) s = stickslip::ContactState::SlipNegative;
      else if (s == stickslip::ContactState::SlipNegative) s = stickslip::ContactState::SlipPositive;
      out[i] = s;
      const stickslip::WallRest w = m.wall(1 - i);
      out.set_wall(i, w == stickslip::WallRest::Start    ? stickslip::WallRest::Finish
                      : w == stickslip::WallRest::Finish ? stickslip::WallRest::Start
                                                         : stickslip::WallRest::None);
    }
    return out;
  };
  return sym;
}

}  // namespace blade

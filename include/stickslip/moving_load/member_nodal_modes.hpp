#pragma once
/// \file member_nodal_modes.hpp
/// \brief The raw data a MemberShapes interpolates: the stations of a member's nodes and the
/// local-axis modal components (u, w, theta) at those nodes.

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>

#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/frame_model.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/modal/modal_basis.hpp"

namespace stickslip {

/// Nodal mode components of one member (the paper's psi^FE restricted to the member, in its
/// local axes), ready to be interpolated by MemberShapes.
///
/// Row k belongs to the k-th node of the member's chain, column j to mode j. Local axes: u along
/// the member (direction (cos, sin)), w normal to it (direction (-sin, cos)), theta = rotation
/// about Z (counter-clockwise positive) = dw/deps.
template <class Scalar_>
struct MemberNodalModes {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Nodal components, nodes x modes.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// Local coordinates of the nodes.
  using StationVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Vector of indices.
  using IndexVector = Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1>;

  MemberId member = 0;  ///< member id (used in messages)
  StationVector stations;   ///< local coordinates of the nodes [m]: 0 = s_0 < s_1 < ... < s_ne = L
  Matrix u;                 ///< axial components, nodes x modes [m per unit modal coordinate]
  Matrix w;                 ///< transverse components, nodes x modes
  Matrix theta;             ///< rotations, nodes x modes [rad per unit modal coordinate]
  Scalar cos = Scalar(1);   ///< member direction cosine (global X component of the u axis)
  Scalar sin = Scalar(0);   ///< member direction sine (global Y component of the u axis)
  /// Optional, for consistent nodal loads: per node the free-DOF indices of its global DOFs
  /// (X, Y, Rz) at 3k, 3k+1, 3k+2, -1 when constrained; empty when unknown.
  IndexVector free_dofs;
  Eigen::Index num_free = 0;  ///< number of free DOFs of the model (with free_dofs)
};

/// The nodal modes of member `member` of `model` from a basis computed for that model: the
/// member's stations and direction, each node's rows basis.nodal(node, X | Y | Rz) rotated into
/// local axes (u = cos X + sin Y, w = -sin X + cos Y, theta = Rz), and the free-DOF numbering.
/// `where` names the caller in messages.
/// \throws std::invalid_argument when the member does not exist, when the basis does not belong
///         to this model (basis.model_id() != model.id(), i.e. another model or a model changed
///         since assembly), or when the basis's DOF numbering does not match the model's nodes
///         and constraints
template <class Scalar>
MemberNodalModes<Scalar> member_nodal_modes(const FrameModel<Scalar>& model, MemberId member,
                                            const ModalBasis<Scalar>& basis,
                                            const std::string& where = "member_nodal_modes") {
  if (member < 0 || member >= model.num_members())
    throw std::invalid_argument(where + ": member = " + std::to_string(member) +
                                " is not in the model (it has " +
                                std::to_string(model.num_members()) + " members)");
  if (basis.model_id() != model.id())
    throw std::invalid_argument(where + ": basis does not belong to this model (basis.model_id() = " +
                                std::to_string(basis.model_id()) + ", model.id() = " +
                                std::to_string(model.id()) +
                                "; recompute the modes after changing the model)");
  const DofMap& dofs = basis.dofs();
  Eigen::Index model_free = 0;
  for (Eigen::Index node = 0; node < model.num_nodes(); ++node)
    for (const Dof d : {Dof::X, Dof::Y, Dof::Rz}) model_free += model.is_constrained(node, d) ? 0 : 1;
  if (dofs.num_nodes() != model.num_nodes() || dofs.num_free() != model_free ||
      basis.num_free() != model_free)
    throw std::invalid_argument(where + ": basis DOF count does not match the model (basis: " +
                                std::to_string(dofs.num_nodes()) + " nodes, " +
                                std::to_string(basis.num_free()) + " free DOFs; model: " +
                                std::to_string(model.num_nodes()) + " nodes, " +
                                std::to_string(model_free) + " free DOFs)");

  const FrameMember<Scalar>& m = model.member(member);
  const Eigen::Index nodes = static_cast<Eigen::Index>(m.nodes.size());
  const Eigen::Index n = basis.size();
  MemberNodalModes<Scalar> out;
  out.member = member;
  out.cos = m.cos;
  out.sin = m.sin;
  out.stations = Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(m.stations.data(), nodes);
  out.u.resize(nodes, n);
  out.w.resize(nodes, n);
  out.theta.resize(nodes, n);
  out.free_dofs.resize(3 * nodes);
  out.num_free = basis.num_free();
  for (Eigen::Index k = 0; k < nodes; ++k) {
    const Eigen::Index node = m.nodes[static_cast<std::size_t>(k)];
    const auto X = basis.nodal(node, Dof::X);
    const auto Y = basis.nodal(node, Dof::Y);
    out.u.row(k) = m.cos * X + m.sin * Y;
    out.w.row(k) = -m.sin * X + m.cos * Y;
    out.theta.row(k) = basis.nodal(node, Dof::Rz);
    for (const Dof d : {Dof::X, Dof::Y, Dof::Rz})
      out.free_dofs(3 * k + static_cast<Eigen::Index>(d)) = dofs.free_index(node, d);
  }
  return out;
}

}  // namespace stickslip

#pragma once
/// \file dof.hpp
/// \brief The three in-plane degrees of freedom of a frame node and the global numbering.

#include <Eigen/Core>

#include <cstdint>

namespace stickslip {

/// Global degrees of freedom of a node: translations along X and Y [m], rotation about Z [rad]
/// (counter-clockwise positive). Node i owns the global DOFs 3i + Dof.
enum class Dof : std::uint8_t { X = 0, Y = 1, Rz = 2 };

/// Number of DOFs per node of a plane frame.
inline constexpr Eigen::Index dofs_per_node = 3;

/// Global index 3 * node + dof of a nodal DOF.
constexpr Eigen::Index global_dof(Eigen::Index node, Dof dof) noexcept {
  return dofs_per_node * node + static_cast<Eigen::Index>(dof);
}

/// Name of a DOF ("X", "Y", "Rz").
inline const char* to_string(Dof dof) noexcept {
  switch (dof) {
    case Dof::X: return "X";
    case Dof::Y: return "Y";
    case Dof::Rz: return "Rz";
  }
  return "unknown";
}

}  // namespace stickslip

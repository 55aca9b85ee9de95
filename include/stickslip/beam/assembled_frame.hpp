#pragma once
/// \file assembled_frame.hpp
/// \brief Global stiffness and mass matrices of a frame over its free DOFs.

#include "stickslip/beam/dof_map.hpp"
#include "stickslip/beam/mass_type.hpp"

#include <Eigen/SparseCore>

#include <cstdint>

namespace stickslip {

/// K and M (symmetric, both triangles stored) over the free DOFs numbered by `dofs`, produced by
/// FrameModel::assemble. Units: K in N/m, N, N m; M in kg, kg m, kg m^2 (per DOF pairing).
template <class Scalar_>
struct AssembledFrame {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Storage of K and M (column-major Eigen sparse matrix).
  using SparseMatrix = Eigen::SparseMatrix<Scalar>;

  SparseMatrix stiffness;  ///< K, num_free x num_free
  SparseMatrix mass;       ///< M, num_free x num_free, positive definite
  DofMap dofs;             ///< free-DOF numbering
  std::uint64_t model_id = 0;  ///< FrameModel::id() of the model at assembly
  /// Consistent or lumped element mass matrices, as assembled.
  MassType mass_type = MassType::Consistent;
  /// Number of zero-stiffness (rigid-body) modes K phi = 0, counted exactly from the topology and
  /// supports by FrameModel::assemble; -1 when unknown (compute_modes then classifies by
  /// ModalOptions::rigid_body_tolerance).
  Eigen::Index num_rigid_body_modes = -1;

  /// Number of free DOFs: the order of K and M.
  Eigen::Index num_free() const noexcept { return dofs.num_free(); }
};

}  // namespace stickslip

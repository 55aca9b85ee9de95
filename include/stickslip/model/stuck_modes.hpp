#pragma once
/// \file stuck_modes.hpp
/// \brief Natural frequencies and mode shapes of a friction-damped system with every damper
/// stuck (the frequencies that matter when forcing a damped structure).

#include "stickslip/detail/validate.hpp"
#include "stickslip/model/normal_load.hpp"
#include "stickslip/model/point_load.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace stickslip {

/// Undamped natural modes of the all-stuck system on the retained modal basis.
template <class Scalar>
struct StuckModes {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;  ///< column vector
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  ///< dense matrix
  Vector omega;   ///< natural circular frequencies [rad/s], ascending (0 for a rigid-body mode)
  Matrix shapes;  ///< column j: mode j in modal coordinates q, normalised to v^T M v = 1
};

/// The all-stuck system's natural modes with the contacts at `X` (one coordinate per damper):
/// every damper stuck (V_i = 0, so x_i = b_i^T q + const, docs/model.md with V = 0) adds its
/// mass and spring to the structure,
///   M = I + sum_i m_i (b_i b_i^T + [inertial N] a_i a_i^T),   K = Omega^2 + sum_i k_i b_i b_i^T,
///   K v = omega^2 M v,
/// with a_i = psi_w(X_i), b_i = psi_u(X_i), m_i, k_i the effective (shared) mass and spring; the
/// a_i a_i^T term only for a damper whose normal force is inertial (N = N0 - m_i y'', paper eqs
/// 23-24). Dampers with a regularised law count as stuck too. Viscous modal damping is left out.
/// Same structure as FrictionDampedSystem::linear_part in the all-stuck mode (its eigenvalues
/// are +-i omega without damping). Cost: one dense n x n generalized eigensolve.
/// \throws std::invalid_argument when X has not one entry per damper
template <class System>
StuckModes<typename System::Scalar> stuck_natural_modes(
    const System& system, const Eigen::Matrix<typename System::Scalar, Eigen::Dynamic, 1>& X) {
  using Scalar = typename System::Scalar;
  using Matrix = typename StuckModes<Scalar>::Matrix;
  using Vector = typename StuckModes<Scalar>::Vector;
  if (X.size() != system.num_dampers())
    detail::throw_invalid("stuck_natural_modes", "X must hold one contact coordinate per damper, size", X.size());
  const Eigen::Index n = system.num_modes();
  Matrix M = Matrix::Identity(n, n);
  Matrix K = system.omega_squared().asDiagonal();
  const bool inertial_model = system.options().normal_load == NormalLoad::Inertial;
  for (std::size_t i = 0; i < system.dampers().size(); ++i) {
    const auto& d = system.dampers()[i];
    const Scalar Xi = X[static_cast<Eigen::Index>(i)];
    const Vector b = system.point_shape(d.member, Xi, LoadDirection::Axial);
    const Scalar m = d.effective_mass();
    M.noalias() += m * b * b.transpose();
    K.noalias() += d.effective_stiffness() * b * b.transpose();
    if (inertial_model && d.normal_load == NormalLoad::Inertial) {
      const Vector a = system.point_shape(d.member, Xi, LoadDirection::Transverse);  // side^2 = 1
      M.noalias() += m * a * a.transpose();
    }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> solver(K, M);
  StuckModes<Scalar> out;
  using std::sqrt;
  out.omega = solver.eigenvalues().unaryExpr([](Scalar l) { return sqrt(std::max(l, Scalar(0))); });
  out.shapes = solver.eigenvectors();
  return out;
}

/// stuck_natural_modes at the dampers' initial contact coordinates X0.
template <class System>
StuckModes<typename System::Scalar> stuck_natural_modes(const System& system) {
  Eigen::Matrix<typename System::Scalar, Eigen::Dynamic, 1> X(system.num_dampers());
  for (Eigen::Index i = 0; i < X.size(); ++i)
    X[i] = system.dampers()[static_cast<std::size_t>(i)].contact_coordinate;
  return stuck_natural_modes(system, X);
}

}  // namespace stickslip

#pragma once
/// \file contact_linear_workspace.hpp
/// \brief Workspace of ContactSystem::linear_part (contact_system_linear.hpp): sized once per
/// system, so that a call allocates nothing once the LinearPart it fills has its sizes.

#include <stickslip/model/damper_states.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <cstdint>

namespace stickslip::detail {

/// Matrices and vectors of ContactSystem::linear_part for m coordinates and D contacts.
template <class Scalar>
struct ContactLinearWorkspace {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  Matrix K, Dm;     // m x m: d r / d z and d r / d z' of the known generalised forces r
  Matrix Q;         // m x m: z'' = Q r + acc_rate (the constrained acceleration map)
  Matrix L;         // 2D x m: lambda = L r + lambda_rate (the unknowns' map, top U rows)
  Vector rhs, col;  // 2D: one solve with the capacitance matrix
  Vector lambda_rate;  // 2D: -C^-1 (rows' rates times z')
  Vector acc_rate;  // m: M^-1 cols^T lambda_rate
  Vector known;     // m: the constant known forces (slipping contacts' friction)
  Vector f, b;      // 2m: rhs and b(t) at the call's (t, x) (inexact modes)
  Eigen::PartialPivLU<Matrix> lu;  // of the padded capacitance matrix
  DamperStates mode;               // the exact mode of `version`
  std::uint64_t version = 0;
  bool exact_valid = false;

  /// Sizes for m coordinates and D contacts (no-op when already so sized).
  void resize(Eigen::Index m, Eigen::Index D) {
    if (K.rows() == m && L.rows() == 2 * D) return;
    K.setZero(m, m);
    Dm.setZero(m, m);
    Q.setZero(m, m);
    L.setZero(2 * D, m);
    rhs.setZero(2 * D);
    col.setZero(2 * D);
    lambda_rate.setZero(2 * D);
    acc_rate.setZero(m);
    known.setZero(m);
    f.setZero(2 * m);
    b.setZero(2 * m);
    lu = Eigen::PartialPivLU<Matrix>(2 * D);
  }
};

}  // namespace stickslip::detail

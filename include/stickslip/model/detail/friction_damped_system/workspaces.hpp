#pragma once
/// \file workspaces.hpp
/// \brief FrictionDampedSystem's work storage for its linear part and its Jacobian: sized by the
/// first call, reused by every later one (no allocation once sized).

#include "stickslip/model/damper_states.hpp"
#include "stickslip/moving_load/member_shapes.hpp"
#include "stickslip/ode/linear_part.hpp"

#include <Eigen/Core>
#include <Eigen/LU>

#include <cstdint>
#include <vector>

namespace stickslip {
namespace detail {

/// linear_part(): probe work vectors, the key of the last call (mode, frozen X and slip
/// coefficients) with its version, the last exact mode's result.
template <class Scalar>
struct LinearPartWork {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  Vector xs;
  Vector f, b, X, mu, key_X, key_mu;
  Matrix fz, vz;  // f and V of an exact mode as maps of z (audit_forms)
  Vector g;
  std::vector<Scalar> preload;
  DamperStates mode;
  bool key_valid = false, cached = false;
  std::uint64_t version = 0;
  LinearPart<Scalar> cache;
};

/// jacobian(): the linear part of the mode, z of the audit forms, difference vectors; the
/// workspace of the tangent Jacobian (per unknown its row of the tangent right side and of du,
/// the gradients of one damper's scalars, its shapes at X, the capacitance matrix and its LU per
/// number of unknowns) and of the contact columns (psi_w''' at X, the right side
/// g = dr0/dX + (dF/dX) u of the tangent, dq''/dX and du/dX).
template <class Scalar>
struct JacobianWork {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  LinearPart<Scalar> lp;
  Vector z;
  Vector x, fp, fm;
  Matrix rho, du, S;
  Eigen::Matrix<Scalar, 1, Eigen::Dynamic> gV, gs, gh, gd, gc;
  typename MemberShapes<Scalar>::Values shape;
  std::vector<Eigen::PartialPivLU<Matrix>> lu;
  Vector d3w, g, dqdd, dux, sol;
};

}  // namespace detail
}  // namespace stickslip

#pragma once
/// \file moving_contact.hpp
/// \brief Kinematics of a contact point that moves along a member (paper eqs 10, 17-19), shared
/// by FrictionDampedSystem and ContactSystem: the convective accelerations of the member's motion
/// under a point whose coordinate X changes at X' = V, from component 3's shapes at X.
///
/// For a displacement y(t) = psi(X(t)) . q(t) of the member at the moving point,
///     y'  = psi . q' + (psi' . q) V,
///     y'' = psi . q'' + 2 (psi' . q') V + (psi'' . q) V^2 + (psi' . q) V',
/// and for the material velocity at the point, d/dt [psi(X(t)) . q'(t)] = psi . q'' + (psi' . q') V.

#include <stickslip/moving_load/member_shapes.hpp>

#include <Eigen/Core>

#include <utility>

namespace stickslip {
namespace detail {

/// 2 (psi' . q') V + (psi'' . q) V^2: the part of y'' (above) that the point's motion adds to
/// psi . q'' + (psi' . q) V' (the paper's h, eq. 19).
template <class Scalar>
inline Scalar convective_displacement_acceleration(Scalar dpsi_qd, Scalar ddpsi_q, Scalar V) {
  return Scalar(2) * dpsi_qd * V + ddpsi_q * V * V;
}

/// (psi' . q') V: the part of d/dt [psi(X) . q'] that the point's motion adds to psi . q''.
template <class Scalar>
inline Scalar convective_velocity_rate(Scalar dpsi_qd, Scalar V) {
  return dpsi_qd * V;
}

/// One contact of a ContactSystem whose side b is the point of a member under a moving contact
/// point: the member's shapes (continued past its ends, where the system's end guards stop the
/// run), the values at the current X and the directions' signs along the member's axes.
template <class Scalar>
struct MovingSide {
  Eigen::Index contact = 0;        ///< index of the contact in the system
  MemberShapes<Scalar> shapes;     ///< side b's member
  ShapeValues<Scalar> values;      ///< psi_u, psi_u', psi_w, psi_w', psi_w'' at X
  ElementCursor cursor;            ///< element of the last evaluation
  Scalar sigma_t = Scalar(1);      ///< t . u = +-1 (the tangent along the member's axis)
  Scalar sigma_n = Scalar(1);      ///< n . w = +-1 (the normal along the member's normal)
  Scalar start = Scalar(0);        ///< X0 [m]
  /// The member's shapes for a contact `contact` whose side b starts at X0 = `start`.
  MovingSide(Eigen::Index contact_, MemberShapes<Scalar> shapes_, Scalar sigma_t_, Scalar sigma_n_, Scalar start_)
      : contact(contact_), shapes(std::move(shapes_)), sigma_t(sigma_t_), sigma_n(sigma_n_), start(start_) {
    shapes.evaluate(start, values, cursor);  // sizes the values once
  }
};

}  // namespace detail
}  // namespace stickslip

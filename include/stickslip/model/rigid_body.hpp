#pragma once
/// \file rigid_body.hpp
/// \brief Planar rigid bodies of a ContactSystem scene: mass and rotary inertia, linear springs
/// and dashpots to ground attached at body points, constant (or timed) loads at the centre of
/// mass (docs/contacts.md, "Rigid bodies").
///
/// A body's coordinates are the displacement (x, y) of its centre of mass from its reference
/// position and its rotation theta (counter-clockwise) from its reference orientation. A point
/// given in body coordinates r (from the centre of mass, in the reference orientation) sits at
/// (x, y) + R(theta) r - r from its reference position and moves at V + omega k x R(theta) r.

#include <stickslip/detail/validate.hpp>
#include <stickslip/model/structure_point.hpp>

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace stickslip {

/// A point of a rigid body: body index in the scene and position r in body coordinates [m]
/// (from the centre of mass, in the reference orientation).
template <class Scalar>
struct BodyPoint {
  Eigen::Index body = 0;                                   ///< index of the body in the scene
  Eigen::Matrix<Scalar, 2, 1> point = Eigen::Matrix<Scalar, 2, 1>::Zero();  ///< r [m]
};

/// A linear spring (stiffness k) and dashpot (c) to ground along the global unit direction d,
/// attached at body point r: with the elongation delta = d . ((x, y) + (R(theta) - I) r), the
/// force on the body at the point is -(k delta + c delta') d.
template <class Scalar>
struct BodySpring {
  Eigen::Matrix<Scalar, 2, 1> point = Eigen::Matrix<Scalar, 2, 1>::Zero();  ///< r [m]
  PlaneDirection<Scalar> direction;   ///< d (global unit vector)
  Scalar stiffness = Scalar(0);       ///< k [N/m], >= 0
  Scalar damping = Scalar(0);         ///< c [N s/m], >= 0
};

/// A force F(t) d at the centre of mass along the global unit direction d: F(t) = value, or
/// `time_function(t)` when set [N].
template <class Scalar>
struct BodyLoad {
  PlaneDirection<Scalar> direction;             ///< d (global unit vector)
  Scalar value = Scalar(0);                     ///< constant F [N]
  std::function<Scalar(Scalar)> time_function;  ///< optional F(t) [N]
  /// F(t).
  Scalar operator()(Scalar t) const { return time_function ? time_function(t) : value; }

  /// The centrifugal preload m r Omega^2 of a body of mass m at radius r on a rotor turning at
  /// Omega [rad/s], along the radial direction `radial`.
  static BodyLoad centrifugal(Scalar mass, Scalar radius, Scalar Omega, PlaneDirection<Scalar> radial) {
    BodyLoad load;
    load.direction = radial;
    load.value = mass * radius * Omega * Omega;
    return load;
  }
};

/// A planar rigid body: mass m, rotary inertia J about its centre of mass, springs and dashpots
/// to ground, loads at the centre of mass. Equations of motion (contact forces F_c at points r_c):
///   m (x'', y'') = sum_loads F d + sum_springs -(k delta + c delta') d + sum_c F_c,
///   J theta''    = sum_springs (R r x -(k delta + c delta') d) + sum_c (R r_c x F_c).
template <class Scalar>
struct RigidBody {
  Scalar mass = Scalar(1);     ///< m [kg], > 0
  Scalar inertia = Scalar(1);  ///< J about the centre of mass [kg m^2], > 0
  std::vector<BodySpring<Scalar>> springs;  ///< springs and dashpots to ground
  std::vector<BodyLoad<Scalar>> loads;      ///< loads at the centre of mass

  /// \throws std::invalid_argument naming `where` and the parameter: mass or inertia not finite
  ///         and > 0, a spring with a non-unit direction, a negative or non-finite stiffness or
  ///         damping, a non-finite point; a load with a non-unit direction or a non-finite value.
  void validate(const std::string& where) const {
    detail::require_positive(where, "mass", mass);
    detail::require_positive(where, "inertia", inertia);
    for (std::size_t k = 0; k < springs.size(); ++k) {
      const std::string w = where + ": springs[" + std::to_string(k) + "]";
      springs[k].direction.validate(w, "direction");
      detail::require_non_negative(w, "stiffness", springs[k].stiffness);
      detail::require_non_negative(w, "damping", springs[k].damping);
      detail::require_finite(w, "point", springs[k].point.x());
      detail::require_finite(w, "point", springs[k].point.y());
    }
    for (std::size_t k = 0; k < loads.size(); ++k) {
      const std::string w = where + ": loads[" + std::to_string(k) + "]";
      loads[k].direction.validate(w, "direction");
      if (!loads[k].time_function) detail::require_finite(w, "value", loads[k].value);
    }
  }
};

namespace detail {

/// R(theta) r, with turn = (cos theta, sin theta) (one sine and cosine per body and evaluation,
/// however many of its points are turned).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> rotated(const Eigen::Matrix<Scalar, 2, 1>& turn, const Eigen::Matrix<Scalar, 2, 1>& r) {
  const Scalar c = turn.x(), s = turn.y();
  return {c * r.x() - s * r.y(), s * r.x() + c * r.y()};
}

/// (cos theta, sin theta), the argument `turn` of rotated().
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> turn_of(Scalar theta) {
  using std::cos;
  using std::sin;
  return {cos(theta), sin(theta)};
}

/// R(theta) r.
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> rotated(Scalar theta, const Eigen::Matrix<Scalar, 2, 1>& r) {
  return rotated(turn_of(theta), r);
}

/// The body part of the row of a body point's velocity along d: d . (V + omega k x R r) =
/// [d_x, d_y, d . (k x R r)] . (x', y', theta'), with Rr = R(theta) r.
template <class Scalar>
Eigen::Matrix<Scalar, 3, 1> body_point_row(const Eigen::Matrix<Scalar, 2, 1>& d, const Eigen::Matrix<Scalar, 2, 1>& Rr) {
  return {d.x(), d.y(), -d.x() * Rr.y() + d.y() * Rr.x()};
}

}  // namespace detail

}  // namespace stickslip

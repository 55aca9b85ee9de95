#pragma once
/// \file structure_point.hpp
/// \brief A material point of the modal structure and the modal row of its displacement along
/// an in-plane direction: the kinematic relation of a contact side fixed on a member.

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/beam/ids.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/modal/modal_basis.hpp>
#include <stickslip/moving_load/member_shapes.hpp>

#include <Eigen/Core>

#include <cmath>
#include <string>

namespace stickslip {

/// A material point of the structure: coordinate `coordinate` [m] along member `member` (0 at
/// the member's first node). Nodes and points between nodes are both allowed (the modes are
/// interpolated by the member's element shape functions, component 3).
template <class Scalar>
struct StructurePoint {
  MemberId member = 0;     ///< member the point lies on
  Scalar coordinate{};     ///< position along the member [m], in [0, length]
};

/// A unit in-plane direction (cos a, sin a) at angle `a` [rad] from global X.
template <class Scalar>
struct PlaneDirection {
  Scalar x = Scalar(1);  ///< global X component
  Scalar y = Scalar(0);  ///< global Y component

  /// The direction at angle `angle` [rad] from global X (counter-clockwise).
  static PlaneDirection at_angle(Scalar angle) {
    using std::cos;
    using std::sin;
    return {cos(angle), sin(angle)};
  }
  /// Global X.
  static PlaneDirection global_x() { return {Scalar(1), Scalar(0)}; }
  /// Global Y.
  static PlaneDirection global_y() { return {Scalar(0), Scalar(1)}; }

  /// \throws std::invalid_argument naming `name` unless the components are finite with
  ///         |(x, y)| = 1 to 1e-9 (a unit vector: the contact's velocity and force are its
  ///         components along it).
  void validate(const std::string& where, const char* name) const {
    using std::abs;
    using std::sqrt;
    detail::require_finite(where, name, x);
    detail::require_finite(where, name, y);
    const Scalar norm = sqrt(x * x + y * y);
    if (!(abs(norm - Scalar(1)) <= Scalar(1e-9)))
      detail::throw_invalid(where, std::string(name) + " must be a unit vector, |d| =", norm);
  }
};

/// The shapes of `point.member` (component 3) after checking that the point lies on a member of
/// `frame`. \throws std::invalid_argument naming `where`, the member or the coordinate.
template <class Scalar>
MemberShapes<Scalar> shapes_at_point(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                                     const StructurePoint<Scalar>& point, const std::string& where) {
  if (point.member < 0 || point.member >= frame.num_members())
    detail::throw_invalid(where, "member must name a member of the frame", point.member);
  detail::require_finite(where, "coordinate", point.coordinate);
  MemberShapes<Scalar> shapes(frame, point.member, basis);
  if (!shapes.contains(point.coordinate))
    detail::throw_invalid(where, "coordinate must lie on member " + std::to_string(point.member) +
                                     " (valid range [0, " + detail::format_value(shapes.length()) + "])",
                          point.coordinate);
  return shapes;
}

/// Modal row of the displacement of `point` along `direction`: u_d = row . q, where q are the
/// modal coordinates of `basis` (mass-normalised). The row is the member's shapes at the point
/// in global components, row = d_x psi_X + d_y psi_Y (component 3, MemberShapes::evaluate_global).
/// \throws std::invalid_argument for a member outside `frame`, a coordinate off the member, a
///         basis of another model or a direction that is not a unit vector.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> structure_point_row(const FrameModel<Scalar>& frame,
                                                             const ModalBasis<Scalar>& basis,
                                                             const StructurePoint<Scalar>& point,
                                                             const PlaneDirection<Scalar>& direction,
                                                             const std::string& where) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  direction.validate(where, "direction");
  const MemberShapes<Scalar> shapes = shapes_at_point(frame, basis, point, where);
  Vector psi_x, psi_y;
  shapes.evaluate_global(point.coordinate, psi_x, psi_y);
  return direction.x * psi_x + direction.y * psi_y;
}

}  // namespace stickslip

#pragma once
/// \file point_contact.hpp
/// \brief A friction contact between a structure point and ground (a grounded slider) or
/// between two structure points (a point-to-point friction joint): relation + law + normal.
///
/// Relation: the relative tangential displacement of side a over side b along an in-plane unit
/// direction d, s = (u_a - u_b) . d = w . q, so v = w . q' with the constant modal row
/// w = row_a - row_b (structure_point_row; ground's row is zero). Law: a friction law of
/// component 4 (CoulombLaw, StribeckLaw, RegularisedLaw). Normal: held, N(t) > 0 given (a
/// clamped joint or a preloaded slider): the normal force acts inside the joint and does no
/// work on the structure. The friction force f on side a along d (and -f on side b) enters the
/// modal equations as w f (docs/contacts.md).

#include <stickslip/model/point_damper.hpp>
#include <stickslip/model/structure_point.hpp>

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace stickslip {

/// A held normal force: N(t) = value, or `time_function(t)` when set [N], > 0 at every t.
template <class Scalar>
struct HeldNormal {
  Scalar value = Scalar(1);                      ///< constant normal force [N]
  std::function<Scalar(Scalar)> time_function;   ///< optional N(t) [N]
  /// N(t).
  Scalar operator()(Scalar t) const { return time_function ? time_function(t) : value; }
};

/// A friction contact at a structure point: side a is a material point of the structure, side
/// b is ground or another material point; both sides stay in contact under a held normal force.
/// Satisfies the contact concept of ContactSystem (is_contact_v).
template <class Scalar_>
struct PointContact {
  using Scalar = Scalar_;                          ///< floating-point type
  using Law = FrictionLawVariant<Scalar>;          ///< friction laws of component 4
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;  ///< modal row

  StructurePoint<Scalar> a;                          ///< the sliding side
  std::optional<StructurePoint<Scalar>> b;           ///< the other side; none: ground
  PlaneDirection<Scalar> direction;                  ///< tangential unit direction d (global)
  Law friction = CoulombLaw<Scalar>(Scalar(0.3), Scalar(0.3));  ///< friction law
  HeldNormal<Scalar> normal;                         ///< N(t) [N]
  /// Initial contact state (Stick: the sides start stuck; a slip state needs v != 0 at t0).
  ContactState initial_state = ContactState::Stick;
  /// A relation of one's own on the same modes: when set, s = w . q with w = row(frame, basis)
  /// (one finite value per retained mode), and `a`, `b`, `direction` are not read; e.g. a
  /// rotational friction hinge between two members, w = the difference of their rotations' modal
  /// rows (docs/contacts.md, "A relation of one's own").
  std::function<Vector(const FrameModel<Scalar>&, const ModalBasis<Scalar>&)> row;

  /// A grounded slider: `point` rubs on ground along `direction` under normal force N.
  static PointContact grounded(StructurePoint<Scalar> point, PlaneDirection<Scalar> direction, Law law,
                               Scalar N) {
    PointContact c;
    c.a = point;
    c.direction = direction;
    c.friction = std::move(law);
    c.normal.value = N;
    return c;
  }
  /// A friction joint: `point_a` rubs on `point_b` along `direction` under normal force N.
  static PointContact joint(StructurePoint<Scalar> point_a, StructurePoint<Scalar> point_b,
                            PlaneDirection<Scalar> direction, Law law, Scalar N) {
    PointContact c = grounded(point_a, direction, std::move(law), N);
    c.b = point_b;
    return c;
  }

  /// A contact whose relation s = w . q has the modal row w = row_function(frame, basis), with
  /// `law` under the normal force N.
  static PointContact with_row(std::function<Vector(const FrameModel<Scalar>&, const ModalBasis<Scalar>&)> row_function,
                               Law law, Scalar N) {
    PointContact c;
    c.row = std::move(row_function);
    c.friction = std::move(law);
    c.normal.value = N;
    return c;
  }
  /// The friction law.
  const Law& law() const noexcept { return friction; }
  /// Normal force N(t) [N].
  Scalar normal_force(Scalar t) const { return normal(t); }
  /// The contact state at the start of a run.
  ContactState start_state() const noexcept { return initial_state; }

  /// The constant modal row w of the relative tangential displacement, s = w . q (row(frame,
  /// basis) when set).
  /// \throws std::invalid_argument (naming `where`) for a side off the frame or a bad direction.
  Vector tangential_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                        const std::string& where) const {
    if (row) {
      Vector w = row(frame, basis);
      if (w.size() != basis.size())
        detail::throw_invalid(where, "row must return one value per retained mode (" +
                                         std::to_string(basis.size()) + "), size",
                              w.size());
      if (!w.allFinite()) throw std::invalid_argument(where + ": row must return finite values");
      return w;
    }
    Vector w = structure_point_row(frame, basis, a, direction, where + ": side a");
    if (b) {
      if (b->member == a.member && b->coordinate == a.coordinate)
        detail::throw_invalid(where, "side b must be another point than side a (coordinate)", b->coordinate);
      w -= structure_point_row(frame, basis, *b, direction, where + ": side b");
    }
    return w;
  }

  /// \throws std::invalid_argument naming `where` and the parameter: a non-finite or
  ///         non-positive constant normal force, an initial state that is not an enumerator of
  ///         ContactState or is not a contact state of a held normal (LiftOff, Separated).
  void validate(const std::string& where) const {
    if (!normal.time_function) detail::require_positive(where, "normal.value", normal.value);
    switch (initial_state) {
      case ContactState::Stick:
      case ContactState::SlipPositive:
      case ContactState::SlipNegative:
        break;
      default:
        detail::throw_invalid(where, "initial_state must be Stick, SlipPositive or SlipNegative under a held normal",
                              static_cast<int>(initial_state));
    }
  }
};

}  // namespace stickslip

#pragma once
/// \file any_contact.hpp
/// \brief A contact of either of the library's kinds, PointContact (structure points under a held
/// normal) or BodyContact (a rigid-body point with a unilateral normal), so that one ContactSystem
/// scene holds both: ContactSystem<Scalar, AnyContact<Scalar>> (docs/contacts.md, "Mixed scenes").
///
/// The system asks each contact once, at assembly, whether it has a body side (body_side()), and
/// reads the rows, directions and the law from it then; during a run it reads only the held normal
/// force of a PointContact (normal_force(t), one dispatch per contact and evaluation). The solve,
/// guards and transitions are the same for both kinds: they see per-contact rows and a flag for a
/// unilateral normal, never the kind.

#include <stickslip/model/body_contact.hpp>
#include <stickslip/model/point_contact.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace stickslip {

/// A PointContact or a BodyContact. Satisfies the contact concept with a body side
/// (contact_concept.hpp); body_side() tells at run time which members are meaningful: the
/// body-side members of a PointContact return neutral values the system never reads.
template <class Scalar_>
struct AnyContact {
  using Scalar = Scalar_;                                   ///< floating-point type
  using Law = FrictionLawVariant<Scalar>;                   ///< friction laws of component 4
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;  ///< modal row
  using Kind = std::variant<PointContact<Scalar>, BodyContact<Scalar>>;  ///< the two kinds

  Kind kind;  ///< the contact

  /// A grounded slider or a joint between structure points.
  AnyContact(PointContact<Scalar> c) : kind(std::move(c)) {}  // NOLINT(google-explicit-constructor)
  /// A rigid-body point on a structure point or ground.
  AnyContact(BodyContact<Scalar> c) : kind(std::move(c)) {}   // NOLINT(google-explicit-constructor)

  /// True for a BodyContact (a rigid-body side and a unilateral normal).
  bool body_side() const noexcept { return std::holds_alternative<BodyContact<Scalar>>(kind); }

  /// The friction law.
  const Law& law() const noexcept {
    return std::visit([](const auto& c) -> const Law& { return c.law(); }, kind);
  }
  /// The held normal force of a PointContact; 0 (not read) for a BodyContact.
  Scalar normal_force(Scalar t) const {
    return std::visit([t](const auto& c) { return Scalar(c.normal_force(t)); }, kind);
  }
  /// The contact state at the start of a run.
  ContactState start_state() const noexcept {
    return std::visit([](const auto& c) { return c.start_state(); }, kind);
  }
  /// The contact's tangential_row (the whole row of a PointContact, the structure part of a
  /// BodyContact's).
  Vector tangential_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                        const std::string& where) const {
    return std::visit([&](const auto& c) { return Vector(c.tangential_row(frame, basis, where)); }, kind);
  }
  /// The contact's own checks.
  void validate(const std::string& where) const {
    std::visit([&](const auto& c) { c.validate(where); }, kind);
  }

  /// The body point of a BodyContact (a default point for a PointContact).
  BodyPoint<Scalar> body_point() const noexcept { return body() ? body()->a : BodyPoint<Scalar>{}; }
  /// n of a BodyContact (global Y for a PointContact).
  PlaneDirection<Scalar> normal_direction() const noexcept {
    return body() ? body()->normal_direction() : PlaneDirection<Scalar>::global_y();
  }
  /// t of a BodyContact (global X for a PointContact).
  PlaneDirection<Scalar> tangent_direction() const noexcept {
    return body() ? body()->tangent_direction() : PlaneDirection<Scalar>::global_x();
  }
  /// The structure part of a BodyContact's normal row (zero for a PointContact).
  Vector normal_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis, const std::string& where) const {
    return body() ? body()->normal_row(frame, basis, where) : Vector(Vector::Zero(basis.size()));
  }
  /// e of a BodyContact (0 for a PointContact).
  Scalar restitution_coefficient() const noexcept { return body() ? body()->restitution : Scalar(0); }
  /// g0 of a BodyContact (0 for a PointContact).
  Scalar gap_at_reference() const noexcept { return body() ? body()->initial_gap : Scalar(0); }
  /// Whether a BodyContact's side b moves along its member (Fixed for a PointContact).
  ContactPoint side_b_motion() const noexcept { return body() ? body()->contact_point : ContactPoint::Fixed; }
  /// A BodyContact's side b (none for a PointContact).
  std::optional<StructurePoint<Scalar>> structure_side() const { return body() ? body()->b : std::nullopt; }
  /// A BodyContact's choices (the defaults for a PointContact).
  detail::BodyContactChoices contact_choices() const noexcept {
    return body() ? body()->contact_choices() : detail::BodyContactChoices{};
  }

 private:
  const BodyContact<Scalar>* body() const noexcept { return std::get_if<BodyContact<Scalar>>(&kind); }
};

}  // namespace stickslip

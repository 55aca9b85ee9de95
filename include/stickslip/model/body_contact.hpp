#pragma once
/// \file body_contact.hpp
/// \brief A friction contact between a point of a rigid body and a structure point or ground,
/// with a unilateral normal: relation + law + normal (docs/contacts.md, "Rigid bodies").
///
/// Relation: side a is a body point r (body coordinates), side b a material point of the
/// structure (or ground), whose surface has the global unit normal n (pointing from side b's
/// surface towards side a) and the tangent t = (n_y, -n_x) (n turned clockwise by 90 degrees).
/// The relative velocity of a over b,
///     v_rel = (V + omega k x R(theta) r) - u_b',
/// has the sliding velocity v = t . v_rel and the normal velocity v_n = n . v_rel; the gap is
///     g = n . ((x, y) + (R(theta) - I) r - u_b) + g0.
/// Normal: unilateral. While closed (Stick, SlipPositive, SlipNegative) the normal force N is an
/// unknown of the coupled solve that holds v_n' = 0; the contact opens (Separated) when N reaches
/// zero, and closes again when the gap reaches zero, with an impact of restitution e.
/// The forces on side a are N n + f t (and the opposite on side b).
///
/// Side b moving (contact_point = ContactPoint::Moving, the paper's damper, eq. 10): side b is the
/// member point currently under the body point, at the contact coordinate X along the member
/// (X0 = b->coordinate), which the system integrates with X' = (t . u) v (u the member's axis, to
/// which t must be parallel). The rows then hold the member's shapes at X, and the gap's rate
/// adds the member's slope under the moving point (docs/contacts.md, "A moving contact point").
///
/// Options of the paper's damper (docs/contacts.md, "The paper's damper as a body"): a held normal
/// force instead of the unilateral normal (normal_behaviour = Held: N = held_normal_force, the
/// contact never opens and the body is not held along n, so with an opposite load of the same
/// size on the body N does no work on it), a lift-off that stops the run (at_lift_off = Stop),
/// and what a moving side b does at its member's ends (start_end, finish_end).

#include <stickslip/model/contact_point.hpp>
#include <stickslip/model/detail/body_contact_choices.hpp>
#include <stickslip/model/detail/enum_checks.hpp>
#include <stickslip/model/member_end.hpp>
#include <stickslip/model/point_damper.hpp>
#include <stickslip/model/rigid_body.hpp>
#include <stickslip/model/separation.hpp>
#include <stickslip/model/structure_point.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace stickslip {

/// The normal of a BodyContact.
enum class ContactNormal : std::uint8_t {
  /// N is an unknown of the coupled solve holding the gap closed; N = 0 opens the contact.
  Unilateral,
  /// N = BodyContact::held_normal_force, given: along n the sides move freely (no gap held), the
  /// contact never opens (the damper's constant normal load, NormalLoad::Constant).
  Held
};

/// A friction contact of a rigid-body point on a structure point or on ground, with a
/// unilateral normal. Satisfies the contact concept with a body side (contact_concept.hpp).
template <class Scalar_>
struct BodyContact {
  using Scalar = Scalar_;                                   ///< floating-point type
  using Law = FrictionLawVariant<Scalar>;                   ///< friction laws of component 4
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;  ///< modal row

  BodyPoint<Scalar> a;                     ///< side a: a point of a rigid body
  std::optional<StructurePoint<Scalar>> b; ///< side b: a material point of the structure; none: ground
  PlaneDirection<Scalar> normal = PlaneDirection<Scalar>::global_y();  ///< n (global), from b towards a
  Law friction = CoulombLaw<Scalar>(Scalar(0.3), Scalar(0.3));         ///< friction law
  Scalar restitution = Scalar(0);          ///< e in [0, 1] of a landing (0: perfectly plastic)
  Scalar initial_gap = Scalar(0);          ///< g0: the gap with every coordinate zero [m], >= 0
  /// State at the start of a run: Stick, a slip state (closed) or Separated (open).
  ContactState initial_state = ContactState::Stick;
  /// Side b a fixed material point (Fixed) or the member point under the body point, moving
  /// along the member with the sliding (Moving; needs b, with 0 < b->coordinate < length).
  ContactPoint contact_point = ContactPoint::Fixed;
  /// Unilateral (N the solve's unknown) or Held (N = held_normal_force).
  ContactNormal normal_behaviour = ContactNormal::Unilateral;
  /// N [N] of a Held normal, > 0.
  Scalar held_normal_force = Scalar(0);
  /// A unilateral contact whose N reaches zero: opens (Separate) or stops the run (Stop; a state
  /// at t0 that would open it makes make_consistent fail).
  Separation at_lift_off = Separation::Separate;
  /// A moving side b at X = 0 of its member: Default or Stop stops the run, Extend continues
  /// with the end element's shapes continued (EndPolicy::Extrapolate). Wall is not available.
  MemberEnd start_end = MemberEnd::Default;
  /// A moving side b at X = L, as start_end.
  MemberEnd finish_end = MemberEnd::Default;

  /// `point` on ground whose surface has normal `normal`.
  static BodyContact on_ground(BodyPoint<Scalar> point, PlaneDirection<Scalar> normal, Law law,
                               Scalar restitution = Scalar(0)) {
    BodyContact c;
    c.a = point;
    c.normal = normal;
    c.friction = std::move(law);
    c.restitution = restitution;
    return c;
  }
  /// `point` on the structure point `surface` whose surface has normal `normal`.
  static BodyContact on_structure(BodyPoint<Scalar> point, StructurePoint<Scalar> surface,
                                  PlaneDirection<Scalar> normal, Law law, Scalar restitution = Scalar(0)) {
    BodyContact c = on_ground(point, normal, std::move(law), restitution);
    c.b = surface;
    return c;
  }

  /// The friction law.
  const Law& law() const noexcept { return friction; }
  /// N of a Held normal; not read under a unilateral one (N is an unknown of the coupled solve).
  Scalar normal_force(Scalar) const noexcept {
    return normal_behaviour == ContactNormal::Held ? held_normal_force : Scalar(0);
  }
  /// The contact state at the start of a run.
  ContactState start_state() const noexcept { return initial_state; }

  /// The body point of side a.
  const BodyPoint<Scalar>& body_point() const noexcept { return a; }
  /// n.
  PlaneDirection<Scalar> normal_direction() const noexcept { return normal; }
  /// t = (n_y, -n_x).
  PlaneDirection<Scalar> tangent_direction() const noexcept { return {normal.y, -normal.x}; }
  /// e.
  Scalar restitution_coefficient() const noexcept { return restitution; }
  /// g0.
  Scalar gap_at_reference() const noexcept { return initial_gap; }
  /// Whether side b moves along its member.
  ContactPoint side_b_motion() const noexcept { return contact_point; }
  /// Side b (none: ground).
  const std::optional<StructurePoint<Scalar>>& structure_side() const noexcept { return b; }
  /// The options above that change the system's events (detail::BodyContactChoices).
  detail::BodyContactChoices contact_choices() const noexcept {
    return {normal_behaviour == ContactNormal::Held, at_lift_off == Separation::Stop,
            start_end == MemberEnd::Extend, finish_end == MemberEnd::Extend};
  }

  /// The structure's part of the sliding velocity's row: -t . u_b' = row . q' (zero on ground).
  Vector tangential_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                        const std::string& where) const {
    return side_b_row(frame, basis, tangent_direction(), where);
  }
  /// The structure's part of the normal velocity's row: -n . u_b' = row . q' (zero on ground).
  Vector normal_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis, const std::string& where) const {
    return side_b_row(frame, basis, normal, where);
  }

  /// \throws std::invalid_argument naming `where` and the parameter: a normal that is not a
  ///         unit vector, a non-finite body point, a negative body index, a restitution outside
  ///         [0, 1], a negative or non-finite initial gap, an initial state that is not Stick,
  ///         SlipPositive, SlipNegative or Separated, a moving contact point without side b.
  ///         (Whether a.body names a body of the scene is
  ///         checked by the system.)
  void validate(const std::string& where) const {
    normal.validate(where, "normal");
    if (a.body < 0) detail::throw_invalid(where, "a.body must name a body of the scene (index >= 0)", a.body);
    detail::require_finite(where, "a.point", a.point.x());
    detail::require_finite(where, "a.point", a.point.y());
    if (!(restitution >= Scalar(0) && restitution <= Scalar(1)))
      detail::throw_invalid(where, "restitution must lie in [0, 1]", restitution);
    detail::require_non_negative(where, "initial_gap", initial_gap);
    switch (initial_state) {
      case ContactState::Stick:
      case ContactState::SlipPositive:
      case ContactState::SlipNegative:
      case ContactState::Separated:
        break;
      default:
        detail::throw_invalid(where, "initial_state must be Stick, SlipPositive, SlipNegative or Separated",
                              static_cast<int>(initial_state));
    }
    if (contact_point != ContactPoint::Fixed && contact_point != ContactPoint::Moving)
      detail::throw_invalid(where, "contact_point must be Fixed or Moving", static_cast<int>(contact_point));
    if (contact_point == ContactPoint::Moving && !b)
      detail::throw_invalid(where, "contact_point = Moving needs a side b on the structure (b)", 0);
    if (initial_gap > Scalar(0) && initial_state != ContactState::Separated)
      detail::throw_invalid(where, "initial_gap > 0 needs initial_state = Separated", initial_gap);
    detail::require_enumerator(where, "normal_behaviour", "ContactNormal", normal_behaviour, ContactNormal::Held);
    detail::require_enumerator(where, "at_lift_off", "Separation", at_lift_off, Separation::Separate);
    detail::require_enumerator(where, "start_end", "MemberEnd", start_end, MemberEnd::Wall);
    detail::require_enumerator(where, "finish_end", "MemberEnd", finish_end, MemberEnd::Wall);
    if (normal_behaviour == ContactNormal::Held) {
      detail::require_positive(where, "held_normal_force", held_normal_force);
      if (initial_state == ContactState::Separated)
        detail::throw_invalid(where, "initial_state = Separated needs a unilateral normal (normal_behaviour)",
                              static_cast<int>(initial_state));
    }
    if (start_end == MemberEnd::Wall || finish_end == MemberEnd::Wall)
      detail::throw_invalid(where, "start_end and finish_end cannot be Wall (not available on a body contact)",
                            static_cast<int>(MemberEnd::Wall));
  }

 private:
  Vector side_b_row(const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
                    const PlaneDirection<Scalar>& d, const std::string& where) const {
    if (!b) return Vector::Zero(basis.size());
    return -structure_point_row(frame, basis, *b, d, where + ": side b");
  }
};

}  // namespace stickslip

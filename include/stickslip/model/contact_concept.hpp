#pragma once
/// \file contact_concept.hpp
/// \brief The contact concept of ContactSystem: what a kind of contact must supply (docs/contacts.md).
///
/// A contact is a kinematic relation, a friction law and a normal force:
///
///     using Scalar = ...;  using Law = ...;                 // a law of component 4 (or a variant of laws)
///     Vector tangential_row(const FrameModel<Scalar>&, const ModalBasis<Scalar>&,
///                           const std::string& where) const; // w: s = w . q, v = w . q' (once, at assembly)
///     const Law& law() const;                               // friction law
///     Scalar normal_force(Scalar t) const;                  // N(t) > 0, held
///     ContactState start_state() const;                     // state at the start of a run
///     void validate(const std::string& where) const;        // throws std::invalid_argument
///
/// The friction force f on side a along the contact's direction enters the modal equations as
/// the generalised force w f; the system never asks which kind of contact it holds.
///
/// A contact whose side a is a point of a rigid body, with a unilateral normal (BodyContact),
/// supplies five more members (has_body_side_v); its normal force is then an unknown of the
/// coupled solve and normal_force() is not read:
///
///     const BodyPoint<Scalar>& body_point() const;          // side a: body index, point r
///     PlaneDirection<Scalar> tangent_direction() const;     // t (global)
///     PlaneDirection<Scalar> normal_direction() const;      // n (global, from side b towards a)
///     Vector normal_row(frame, basis, where) const;         // structure part of v_n = n . v_rel
///     Scalar restitution_coefficient() const;               // e of a landing
///     Scalar gap_at_reference() const;                      // g0, the gap at zero coordinates
///
/// tangential_row() is then the structure part of the sliding velocity's row; the body part
/// [t, t . (k x R(theta) r)] is added by the system at each evaluation.
///
/// A type that holds contacts of either sort (AnyContact) supplies all of the above and
///
///     bool body_side() const;                               // this contact has the body side
///
/// read once per contact at assembly; without it every contact of a has_body_side_v type has one.
/// A body-side contact whose side b may move along its member (BodyContact) supplies
///
///     ContactPoint side_b_motion() const;                   // Fixed or Moving
///     std::optional<StructurePoint<Scalar>> structure_side() const;  // side b, its X0
/// and may supply its choices (a held normal N = normal_force(t), a lift-off that stops the run,
/// member ends a moving side b continues past; defaults without it):
///
///     detail::BodyContactChoices contact_choices() const;

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/contact/contact_state.hpp>
#include <stickslip/model/contact_point.hpp>
#include <stickslip/modal/modal_basis.hpp>
#include <stickslip/model/rigid_body.hpp>
#include <stickslip/model/structure_point.hpp>

#include <string>
#include <type_traits>
#include <utility>

namespace stickslip {

/// True when C supplies the contact concept above (checked by ContactSystem's static_assert).
template <class C, class = void>
struct is_contact : std::false_type {};

template <class C>
struct is_contact<
    C, std::void_t<typename C::Scalar, typename C::Law,
                   decltype(std::declval<const C&>().tangential_row(
                       std::declval<const FrameModel<typename C::Scalar>&>(),
                       std::declval<const ModalBasis<typename C::Scalar>&>(), std::declval<const std::string&>())),
                   decltype(std::declval<const C&>().law()),
                   decltype(std::declval<const C&>().normal_force(std::declval<typename C::Scalar>())),
                   decltype(std::declval<const C&>().start_state()),
                   decltype(std::declval<const C&>().validate(std::declval<const std::string&>()))>>
    : std::bool_constant<std::is_convertible_v<decltype(std::declval<const C&>().normal_force(
                                                   std::declval<typename C::Scalar>())),
                                               typename C::Scalar> &&
                         std::is_same_v<decltype(std::declval<const C&>().start_state()), ContactState>> {};

/// is_contact<C>::value.
template <class C>
inline constexpr bool is_contact_v = is_contact<C>::value;

/// True when C also supplies the body side above (a rigid-body point with a unilateral normal).
template <class C, class = void>
struct has_body_side : std::false_type {};

template <class C>
struct has_body_side<
    C, std::void_t<decltype(std::declval<const C&>().body_point()),
                   decltype(std::declval<const C&>().normal_row(
                       std::declval<const FrameModel<typename C::Scalar>&>(),
                       std::declval<const ModalBasis<typename C::Scalar>&>(), std::declval<const std::string&>())),
                   decltype(std::declval<const C&>().tangent_direction()),
                   decltype(std::declval<const C&>().normal_direction()),
                   decltype(std::declval<const C&>().restitution_coefficient()),
                   decltype(std::declval<const C&>().gap_at_reference())>>
    : std::bool_constant<
          std::is_convertible_v<decltype(std::declval<const C&>().body_point()), BodyPoint<typename C::Scalar>> &&
          std::is_convertible_v<decltype(std::declval<const C&>().tangent_direction()),
                                PlaneDirection<typename C::Scalar>> &&
          std::is_convertible_v<decltype(std::declval<const C&>().normal_direction()),
                                PlaneDirection<typename C::Scalar>>> {};

/// has_body_side<C>::value.
template <class C>
inline constexpr bool has_body_side_v = has_body_side<C>::value;

namespace detail {

template <class C, class = void>
struct has_body_side_query : std::false_type {};
template <class C>
struct has_body_side_query<C, std::void_t<decltype(std::declval<const C&>().body_side())>> : std::true_type {};

/// Whether contact c has the body side: c.body_side() when C can hold either sort, else
/// has_body_side_v<C>.
template <class C>
bool body_side_of(const C& c) {
  if constexpr (has_body_side_query<C>::value)
    return static_cast<bool>(c.body_side());
  else
    return has_body_side_v<C>;
}

template <class C, class = void>
struct has_moving_side_query : std::false_type {};
template <class C>
struct has_moving_side_query<C, std::void_t<decltype(std::declval<const C&>().side_b_motion()),
                                            decltype(std::declval<const C&>().structure_side())>>
    : std::true_type {};

/// Whether contact c's side b moves along its member (c.side_b_motion() when C supplies it).
template <class C>
bool moving_side_of(const C& c) {
  if constexpr (has_moving_side_query<C>::value)
    return c.side_b_motion() == ContactPoint::Moving;
  else
    return false;
}

}  // namespace detail

}  // namespace stickslip

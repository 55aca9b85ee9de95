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

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/contact/contact_state.hpp>
#include <stickslip/modal/modal_basis.hpp>

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

}  // namespace stickslip

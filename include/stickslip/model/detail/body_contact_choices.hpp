#pragma once
/// \file body_contact_choices.hpp
/// \brief The per-contact choices of a body contact that change ContactSystem's events (a held
/// normal, a lift-off that stops the run, member ends that extend), read once at assembly from a
/// contact that supplies `contact_choices()` (BodyContact, AnyContact); a contact without it has
/// the defaults (unilateral, opens at lift-off, stops at a member end).

#include <type_traits>
#include <utility>

namespace stickslip {
namespace detail {

/// What ContactSystem reads of a contact's choices.
struct BodyContactChoices {
  bool held_normal = false;        ///< N given (normal_force(t)), not an unknown; never opens
  bool stop_at_lift_off = false;   ///< N = 0 stops the run instead of opening the contact
  bool extend_start = false;       ///< a moving side b continues past X = 0
  bool extend_finish = false;      ///< a moving side b continues past X = L
};

template <class C, class = void>
struct has_contact_choices : std::false_type {};
template <class C>
struct has_contact_choices<C, std::void_t<decltype(std::declval<const C&>().contact_choices())>> : std::true_type {};

/// c.contact_choices() when C supplies it, else the defaults.
template <class C>
BodyContactChoices contact_choices_of(const C& c) {
  if constexpr (has_contact_choices<C>::value)
    return c.contact_choices();
  else
    return {};
}

}  // namespace detail
}  // namespace stickslip

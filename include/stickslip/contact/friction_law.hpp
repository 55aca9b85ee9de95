#pragma once
/// \file friction_law.hpp
/// \brief The friction-law concept (what CoulombContact needs from a law) and its trait.
///
/// A friction law is a small copyable class with
///
///     using Scalar = ...;
///     static constexpr bool has_stick_state = ...;
///
/// and, when `has_stick_state` is true (an exact, set-valued law with a stick state, eq. 1):
///
///     Scalar static_coefficient() const;              // mu_s: stick capacity |f| <= mu_s N
///     Scalar kinetic_coefficient(Scalar speed) const; // mu_k(|v|) >= 0, speed >= 0
///
/// or, when it is false (a regularised, single-valued law; no state machine):
///
///     Scalar coefficient(Scalar v) const;             // odd in v; f = -coefficient(v) N
///     Scalar coefficient_derivative(Scalar v) const;  // d coefficient / dv
///
/// See docs/contact.md ("Writing a friction law").

#include <stickslip/detail/validate.hpp>

#include <string>
#include <type_traits>
#include <utility>

namespace stickslip {
namespace detail {

template <class L, class = void>
struct is_exact_friction_law : std::false_type {};
template <class L>
struct is_exact_friction_law<
    L, std::void_t<typename L::Scalar, decltype(L::has_stick_state),
                   decltype(std::declval<const L&>().static_coefficient()),
                   decltype(std::declval<const L&>().kinetic_coefficient(
                       std::declval<typename L::Scalar>()))>>
    : std::bool_constant<L::has_stick_state &&
                         std::is_convertible_v<decltype(std::declval<const L&>()
                                                            .static_coefficient()),
                                               typename L::Scalar> &&
                         std::is_convertible_v<decltype(std::declval<const L&>()
                                                            .kinetic_coefficient(
                                                                std::declval<typename L::Scalar>())),
                                               typename L::Scalar>> {};

template <class L, class = void>
struct is_regularised_friction_law : std::false_type {};
template <class L>
struct is_regularised_friction_law<
    L, std::void_t<typename L::Scalar, decltype(L::has_stick_state),
                   decltype(std::declval<const L&>().coefficient(
                       std::declval<typename L::Scalar>())),
                   decltype(std::declval<const L&>().coefficient_derivative(
                       std::declval<typename L::Scalar>()))>>
    : std::bool_constant<!L::has_stick_state> {};

/// Checks shared by the exact laws: mu_k finite and >= 0, mu_s finite and >= mu_k.
template <class Scalar>
void validate_friction_coefficients(const std::string& where, Scalar mu_s, Scalar mu_k) {
  require_non_negative(where, "mu_k", mu_k);
  require_finite(where, "mu_s", mu_s);
  if (!(mu_s >= mu_k))
    throw_invalid(where, "mu_s must be >= mu_k = " + format_value(mu_k), mu_s);
}

}  // namespace detail

/// True when L is an exact law (has_stick_state, static_coefficient, kinetic_coefficient) or a
/// regularised law (!has_stick_state, coefficient, coefficient_derivative); see the file comment.
template <class L>
inline constexpr bool is_friction_law_v =
    detail::is_exact_friction_law<L>::value || detail::is_regularised_friction_law<L>::value;

}  // namespace stickslip

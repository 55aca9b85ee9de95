#pragma once
/// \file enum_checks.hpp
/// \brief Refusal of enum values that are not enumerators where a scoped enum enters the model's
/// API (a value cast from an integer, a corrupted field): a switch over such a value takes no
/// branch and a comparison chain takes the wrong one, so the model would run something it was
/// never asked for.

#include "stickslip/detail/validate.hpp"

#include <string>
#include <type_traits>

namespace stickslip {
namespace detail {

/// True when `value` lies in [0, last], for an enum whose enumerators are numbered 0, 1, ...,
/// `last` in declaration order (every enum of the model's API).
template <class E>
constexpr bool is_enumerator(E value, E last) noexcept {
  using U = std::underlying_type_t<E>;
  // (a negative value wraps to a huge unsigned one)
  const auto v = static_cast<unsigned long long>(static_cast<long long>(static_cast<U>(value)));
  return v <= static_cast<unsigned long long>(static_cast<long long>(static_cast<U>(last)));
}

/// Throws std::invalid_argument "<where>: <name> is not a <type> enumerator (got <integer>)"
/// unless `value` is one of the enumerators 0 .. `last`.
template <class E>
void require_enumerator(const std::string& where, const std::string& name, const char* type, E value, E last) {
  if (is_enumerator(value, last)) return;
  throw_invalid(where, name + " is not a " + type + " enumerator",
                static_cast<long long>(static_cast<std::underlying_type_t<E>>(value)));
}

}  // namespace detail
}  // namespace stickslip

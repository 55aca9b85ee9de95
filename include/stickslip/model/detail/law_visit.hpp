#pragma once
/// \file law_visit.hpp
/// \brief Calls on a friction law that may be a std::variant of laws (FrictionLawVariant).

#include <type_traits>
#include <utility>
#include <variant>

namespace stickslip::detail {

/// True for a std::variant.
template <class T>
struct is_std_variant : std::false_type {};
template <class... Ts>
struct is_std_variant<std::variant<Ts...>> : std::true_type {};

/// Call f(law) with the concrete law (visiting a std::variant of laws; the same for a variant of
/// anything else, e.g. the contact state machines of ContactSystem).
template <class Law, class F>
decltype(auto) with_law(const Law& law, F&& f) {
  if constexpr (is_std_variant<Law>::value)
    return std::visit(std::forward<F>(f), law);
  else
    return std::forward<F>(f)(law);
}

/// True when the (possibly variant) law has a stick state (exact Coulomb-type laws).
template <class Law>
bool law_has_stick_state(const Law& law) {
  return with_law(law, [](const auto& l) { return std::decay_t<decltype(l)>::has_stick_state; });
}

}  // namespace stickslip::detail

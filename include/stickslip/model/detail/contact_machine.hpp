#pragma once
/// \file contact_machine.hpp
/// \brief The Coulomb state machine (component 4) of a contact whose law may be a std::variant
/// of laws: one CoulombContact per law type, chosen once when the system is assembled.

#include <stickslip/contact/coulomb_contact.hpp>
#include <stickslip/model/detail/law_visit.hpp>

#include <type_traits>
#include <variant>

namespace stickslip::detail {

template <class Law>
struct contact_machine_of {
  using type = CoulombContact<Law>;
};
template <class... Laws>
struct contact_machine_of<std::variant<Laws...>> {
  using type = std::variant<CoulombContact<Laws>...>;
};

/// CoulombContact<Law>, or a std::variant of CoulombContact<L> for a variant of laws L.
template <class Law>
using contact_machine_t = typename contact_machine_of<Law>::type;

/// The state machine of `law` with velocity tolerance `tol`.
template <class Law, class Scalar>
contact_machine_t<Law> make_contact_machine(const Law& law, Scalar tol) {
  if constexpr (std::is_same_v<contact_machine_t<Law>, CoulombContact<Law>>) {
    return CoulombContact<Law>(law, tol);
  } else {
    return std::visit([&](const auto& l) -> contact_machine_t<Law> {
      return CoulombContact<std::decay_t<decltype(l)>>(l, tol);
    }, law);
  }
}

}  // namespace stickslip::detail

#pragma once
/// \file slip_direction.hpp
/// \brief Whether a contact state slips, and its direction: sgn V of SlipPositive / SlipNegative.

#include "stickslip/contact/contact_state.hpp"

namespace stickslip {
namespace detail {

/// True for SlipPositive and SlipNegative.
inline bool is_slipping(ContactState s) noexcept {
  return s == ContactState::SlipPositive || s == ContactState::SlipNegative;
}
/// +1 for SlipPositive, -1 for SlipNegative, 0 otherwise.
inline int slip_sign(ContactState s) noexcept {
  return s == ContactState::SlipPositive ? 1 : (s == ContactState::SlipNegative ? -1 : 0);
}

}  // namespace detail
}  // namespace stickslip

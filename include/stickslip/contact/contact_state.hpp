#pragma once
/// \file contact_state.hpp
/// \brief The discrete state of one friction contact: stick, slip in either direction, lift-off,
/// separated (free flight above the surface).

#include <cstdint>
#include <ostream>

namespace stickslip {

/// State of a friction contact. The slip direction is the sign of the sliding velocity v of the
/// BODY relative to the SURFACE (paper eq. 1: v_rel = 0 stick, v_rel != 0 slip). LiftOff reports
/// a normal force N <= 0, i.e. the paper's permanent-contact assumption has broken (a model that
/// stops there); Separated is the state of a model that lets the contact open: the body flies
/// above the surface (gap > 0) until an impact (docs/contact.md, "Separation and impact").
enum class ContactState : std::uint8_t {
  Stick,         ///< v = 0, |f| <= mu_s N
  SlipPositive,  ///< v > 0, f = -mu_k(|v|) N
  SlipNegative,  ///< v < 0, f = +mu_k(|v|) N
  LiftOff,       ///< N <= 0: no contact force, f = 0
  Separated      ///< gap > 0: the body flies free of the surface, N = 0, f = 0
};

/// Human-readable name of a contact state.
inline const char* to_string(ContactState s) noexcept {
  switch (s) {
    case ContactState::Stick: return "stick";
    case ContactState::SlipPositive: return "slip_positive";
    case ContactState::SlipNegative: return "slip_negative";
    case ContactState::LiftOff: return "lift_off";
    case ContactState::Separated: return "separated";
  }
  return "unknown";
}

/// Writes to_string(s).
inline std::ostream& operator<<(std::ostream& os, ContactState s) { return os << to_string(s); }

/// Sign of the sliding velocity in a state: +1 (SlipPositive), -1 (SlipNegative), 0 otherwise.
constexpr int slip_sign(ContactState s) noexcept {
  return s == ContactState::SlipPositive ? 1 : (s == ContactState::SlipNegative ? -1 : 0);
}

/// True for SlipPositive and SlipNegative.
constexpr bool is_slipping(ContactState s) noexcept { return slip_sign(s) != 0; }

/// True for Stick, SlipPositive and SlipNegative: the surface can push (N > 0 possible).
constexpr bool is_in_contact(ContactState s) noexcept {
  return s != ContactState::LiftOff && s != ContactState::Separated;
}

/// The slip state whose direction is the sign of `direction` (> 0: SlipPositive, else
/// SlipNegative).
template <class Scalar>
constexpr ContactState slip_state(Scalar direction) noexcept {
  return direction > Scalar(0) ? ContactState::SlipPositive : ContactState::SlipNegative;
}

}  // namespace stickslip

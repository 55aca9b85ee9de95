#pragma once
/// \file separation.hpp
/// \brief What a damper does when its normal force reaches zero.

#include <cstdint>

namespace stickslip {

/// What happens when a damper's normal force N reaches zero (docs/model_separation.md, "Separation").
enum class Separation : std::uint8_t {
  /// Stop the run with StopReason::LiftOff (the paper's permanent-contact assumption; default).
  Stop,
  /// The damper leaves the member (ContactState::Separated), flies under its preload and lands
  /// again through an impact with Newton's restitution (PointDamper::restitution).
  Separate
};

/// Name of a choice ("stop", "separate").
inline const char* to_string(Separation s) noexcept {
  return s == Separation::Separate ? "separate" : "stop";
}

}  // namespace stickslip

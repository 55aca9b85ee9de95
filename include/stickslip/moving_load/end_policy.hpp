#pragma once
/// \file end_policy.hpp
/// \brief What a moving-load evaluation does at a coordinate beyond the ends of its member.

#include <cstdint>

namespace stickslip {

/// Treatment of a coordinate eps outside [0, L] of a member (the ends 0 and L themselves are on
/// the member under every policy). See docs/moving_load.md.
enum class EndPolicy : std::uint8_t {
  /// Throw std::invalid_argument naming the member, eps and the valid range (default): a damper
  /// that slides off its platform is reported, never extrapolated.
  Throw,
  /// Evaluate at the nearest end (eps clamped to [0, L]); values and derivatives are those of
  /// the end point.
  Clamp,
  /// Continue the end element's linear (u) and cubic (w) interpolants beyond the end: an explicit
  /// approximation for callers who accept it (the result is no longer a mode of the structure).
  Extrapolate
};

/// Name of a policy ("throw", "clamp", "extrapolate").
inline const char* to_string(EndPolicy policy) noexcept {
  switch (policy) {
    case EndPolicy::Throw: return "throw";
    case EndPolicy::Clamp: return "clamp";
    case EndPolicy::Extrapolate: return "extrapolate";
  }
  return "unknown";
}

}  // namespace stickslip

#pragma once
/// \file member_end.hpp
/// \brief What a damper's contact point does when it reaches an end of its member.

#include <cstdint>

namespace stickslip {

/// Treatment of one end of the member under a moving contact (docs/model_separation.md, "Member ends").
enum class MemberEnd : std::uint8_t {
  /// As ModelOptions::end_policy says: Throw -> Stop, Clamp/Extrapolate -> Extend (default).
  Default,
  /// Stop the run with StopReason::LeftMember.
  Stop,
  /// Continue with the end element's shapes (EndPolicy::Extrapolate, or Clamp when chosen).
  Extend,
  /// A rigid end stop: the sliding velocity reverses, V -> -e V (PointDamper::wall_restitution),
  /// through an impulse between the damper and the member along u.
  Wall
};

/// Name of a choice ("default", "stop", "extend", "wall").
inline const char* to_string(MemberEnd e) noexcept {
  switch (e) {
    case MemberEnd::Default: return "default";
    case MemberEnd::Stop: return "stop";
    case MemberEnd::Extend: return "extend";
    case MemberEnd::Wall: return "wall";
  }
  return "unknown";
}

}  // namespace stickslip

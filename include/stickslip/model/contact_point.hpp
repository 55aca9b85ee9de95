#pragma once
/// \file contact_point.hpp
/// \brief Whether a damper's contact point moves along its member.

namespace stickslip {

/// Whether a damper's contact point moves along the member.
enum class ContactPoint {
  Fixed,  ///< X = X0: the member's shapes at the contact are evaluated once (no X state used)
  Moving  ///< X' = V: the contact slides with the relative motion (moving load, paper eqs 10, 19)
};

}  // namespace stickslip

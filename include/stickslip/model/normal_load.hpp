#pragma once
/// \file normal_load.hpp
/// \brief How a damper's normal contact force is modelled.

namespace stickslip {

/// How the normal contact force is modelled.
enum class NormalLoad {
  Constant,  ///< N = N0: the damper has no vertical inertia (no normal-load variation)
  Inertial   ///< N = N0 - s m y'' with y = w(X, t): the damper follows the member (paper eqs 13-14, 23-24)
};

}  // namespace stickslip

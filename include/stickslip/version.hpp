#pragma once
/// \file version.hpp
/// \brief Version of the stickslip library (semantic versioning).

#define STICKSLIP_VERSION_MAJOR 0
#define STICKSLIP_VERSION_MINOR 1
#define STICKSLIP_VERSION_PATCH 0
/// Single integer for compile-time comparisons: major * 10000 + minor * 100 + patch.
#define STICKSLIP_VERSION (STICKSLIP_VERSION_MAJOR * 10000 + STICKSLIP_VERSION_MINOR * 100 + STICKSLIP_VERSION_PATCH)
#define STICKSLIP_VERSION_STRING "0.1.0"

namespace stickslip {
/// Version of the headers in use, as "major.minor.patch".
inline constexpr const char* version_string() noexcept { return STICKSLIP_VERSION_STRING; }
}  // namespace stickslip

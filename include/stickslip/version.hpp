#pragma once
/// \file version.hpp
/// \brief Version of the stickslip library (semantic versioning).

/// Major version: incremented by incompatible API changes.
#define STICKSLIP_VERSION_MAJOR 0
/// Minor version: incremented by compatible additions.
#define STICKSLIP_VERSION_MINOR 1
/// Patch version: incremented by fixes.
#define STICKSLIP_VERSION_PATCH 0
/// Single integer for compile-time comparisons: major * 10000 + minor * 100 + patch.
#define STICKSLIP_VERSION (STICKSLIP_VERSION_MAJOR * 10000 + STICKSLIP_VERSION_MINOR * 100 + STICKSLIP_VERSION_PATCH)
/// The version as "major.minor.patch".
#define STICKSLIP_VERSION_STRING "0.1.0"

namespace stickslip {
/// Version of the headers in use, as "major.minor.patch".
inline constexpr const char* version_string() noexcept { return STICKSLIP_VERSION_STRING; }
}  // namespace stickslip

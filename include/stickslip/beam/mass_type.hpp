#pragma once
/// \file mass_type.hpp
/// \brief Choice of the element mass matrix.

#include <cstdint>

namespace stickslip {

/// Element mass matrix: the consistent (Hermite/linear shape function) matrix, or the diagonal
/// HRZ-lumped matrix (see FrameElement::local_lumped_mass and docs/beam.md).
enum class MassType : std::uint8_t { Consistent, Lumped };

/// Name of a mass type ("consistent", "lumped").
inline const char* to_string(MassType type) noexcept {
  return type == MassType::Consistent ? "consistent" : "lumped";
}

}  // namespace stickslip

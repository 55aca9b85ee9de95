#pragma once
/// \file section_properties.hpp
/// \brief Material and cross-section data of a straight Euler-Bernoulli frame member.

#include "stickslip/detail/validate.hpp"

#include <string>

namespace stickslip {

/// Material and section of a member (paper eqs. 2-3: E_k, rho_k, A_k, I_k), SI units:
/// E [Pa], rho [kg/m^3], A [m^2], I [m^4] (second moment of area about the bending axis).
template <class Scalar_>
struct SectionProperties {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;

  Scalar E{};    ///< Young's modulus [Pa]
  Scalar rho{};  ///< mass density [kg/m^3]
  Scalar A{};    ///< cross-sectional area [m^2]
  Scalar I{};    ///< second moment of area [m^4]

  /// Throws std::invalid_argument naming `where` and the field when any value is non-finite or
  /// <= 0, or when a rigidity E A, E I or the mass per length rho A overflows to infinity or
  /// underflows to 0 (named as the product, e.g. "section.E * section.I").
  void validate(const std::string& where) const {
    detail::require_positive(where, "section.E", E);
    detail::require_positive(where, "section.rho", rho);
    detail::require_positive(where, "section.A", A);
    detail::require_positive(where, "section.I", I);
    require_representable(where, "section.E * section.A (axial rigidity EA)", axial_rigidity());
    require_representable(where, "section.E * section.I (bending rigidity EI)", bending_rigidity());
    require_representable(where, "section.rho * section.A (mass per length)", mass_per_length());
  }

  Scalar axial_rigidity() const { return E * A; }    ///< EA [N]
  Scalar bending_rigidity() const { return E * I; }  ///< EI [N m^2]
  Scalar mass_per_length() const { return rho * A; } ///< rho A [kg/m]

 private:
  static void require_representable(const std::string& where, const char* product, Scalar value) {
    if (!(value > Scalar(0)) || !detail::is_finite(value))
      detail::throw_invalid(where, std::string(product) + " must be finite and > 0 (the product of "
                                                          "finite factors overflowed or underflowed)",
                            value);
  }
};

}  // namespace stickslip

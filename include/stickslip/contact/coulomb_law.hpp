#pragma once
/// \file coulomb_law.hpp
/// \brief The paper's classical Coulomb law (eq. 1): constant mu_s >= mu_k >= 0.

#include <stickslip/contact/friction_law.hpp>

namespace stickslip {

/// Classical Coulomb friction, paper eq. 1: stick while |f| <= mu_s N, slip with
/// f = -mu_k N sgn(v). Dimensionless coefficients.
/// \throws std::invalid_argument if mu_k < 0, mu_s < mu_k, or either is non-finite.
template <class Scalar_ = double>
class CoulombLaw {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Exact law: set-valued friction at v = 0, so a stick state.
  static constexpr bool has_stick_state = true;

  /// Static coefficient mu_s and kinetic coefficient mu_k, mu_s >= mu_k >= 0.
  CoulombLaw(Scalar mu_s, Scalar mu_k) : mu_s_(mu_s), mu_k_(mu_k) {
    detail::validate_friction_coefficients<Scalar>("CoulombLaw", mu_s, mu_k);
  }

  /// mu_s: stick holds while |f| <= mu_s N (eq 1).
  Scalar static_coefficient() const noexcept { return mu_s_; }
  /// mu_k, independent of the sliding speed.
  Scalar kinetic_coefficient(Scalar /*speed*/) const noexcept { return mu_k_; }

  /// Static coefficient mu_s.
  Scalar mu_s() const noexcept { return mu_s_; }
  /// Kinetic coefficient mu_k.
  Scalar mu_k() const noexcept { return mu_k_; }

 private:
  Scalar mu_s_;
  Scalar mu_k_;
};

}  // namespace stickslip

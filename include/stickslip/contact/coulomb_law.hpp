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
  using Scalar = Scalar_;
  static constexpr bool has_stick_state = true;

  CoulombLaw(Scalar mu_s, Scalar mu_k) : mu_s_(mu_s), mu_k_(mu_k) {
    detail::validate_friction_coefficients<Scalar>("CoulombLaw", mu_s, mu_k);
  }

  Scalar static_coefficient() const noexcept { return mu_s_; }
  /// mu_k, independent of the sliding speed.
  Scalar kinetic_coefficient(Scalar /*speed*/) const noexcept { return mu_k_; }

  Scalar mu_s() const noexcept { return mu_s_; }
  Scalar mu_k() const noexcept { return mu_k_; }

 private:
  Scalar mu_s_;
  Scalar mu_k_;
};

}  // namespace stickslip

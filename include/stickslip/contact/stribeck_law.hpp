#pragma once
/// \file stribeck_law.hpp
/// \brief Coulomb friction with a Stribeck decay of the kinetic coefficient from mu_s to mu_k.

#include <stickslip/contact/friction_law.hpp>

#include <cmath>

namespace stickslip {

/// Coulomb law with Stribeck decay: stick while |f| <= mu_s N; slip with
/// \f$ f = -\mu(|v|) N\,\mathrm{sgn}(v),\ \mu(s) = \mu_k + (\mu_s - \mu_k) e^{-(s/v_s)^\delta} \f$.
/// mu(0) = mu_s, mu(inf) = mu_k. v_s in velocity units, exponent delta dimensionless.
/// \throws std::invalid_argument if mu_k < 0, mu_s < mu_k, v_s <= 0, exponent <= 0, or any
/// argument is non-finite.
template <class Scalar_ = double>
class StribeckLaw {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Exact law: set-valued friction at v = 0, so a stick state.
  static constexpr bool has_stick_state = true;

  /// Coefficients mu_s >= mu_k >= 0, Stribeck velocity v_s > 0, exponent delta > 0 (default 2).
  StribeckLaw(Scalar mu_s, Scalar mu_k, Scalar v_s, Scalar exponent = Scalar(2))
      : mu_s_(mu_s), mu_k_(mu_k), v_s_(v_s), exponent_(exponent) {
    detail::validate_friction_coefficients<Scalar>("StribeckLaw", mu_s, mu_k);
    detail::require_positive("StribeckLaw", "v_s", v_s);
    detail::require_positive("StribeckLaw", "exponent", exponent);
  }

  /// mu_s = mu(0): stick holds while |f| <= mu_s N.
  Scalar static_coefficient() const noexcept { return mu_s_; }

  /// mu(speed) for speed >= 0.
  Scalar kinetic_coefficient(Scalar speed) const {
    using std::exp;
    using std::pow;
    const Scalar r = speed / v_s_;
    const Scalar p = exponent_ == Scalar(2) ? r * r : pow(r, exponent_);
    return mu_k_ + (mu_s_ - mu_k_) * exp(-p);
  }

  /// Static coefficient mu_s.
  Scalar mu_s() const noexcept { return mu_s_; }
  /// Kinetic coefficient at high speed, mu_k = mu(inf).
  Scalar mu_k() const noexcept { return mu_k_; }
  /// Stribeck velocity v_s.
  Scalar v_s() const noexcept { return v_s_; }
  /// Stribeck exponent delta.
  Scalar exponent() const noexcept { return exponent_; }

 private:
  Scalar mu_s_;
  Scalar mu_k_;
  Scalar v_s_;
  Scalar exponent_;
};

}  // namespace stickslip

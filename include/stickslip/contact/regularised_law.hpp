#pragma once
/// \file regularised_law.hpp
/// \brief A smooth (or Lipschitz) single-valued friction law that needs no stick state.

#include <stickslip/contact/friction_law.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

namespace stickslip {

/// Shape of the regularised sign function.
enum class RegularisedShape : std::uint8_t {
  Tanh,            ///< mu tanh(v / v_eps): smooth
  LinearSaturated  ///< mu clamp(v / v_eps, -1, 1): Lipschitz, exact Coulomb for |v| >= v_eps
};

/// Regularised Coulomb friction \f$ f = -\mu\,s(v/v_\varepsilon) N \f$ with s = tanh or a linear
/// ramp saturated at +-1. No stick state: a "stuck" body creeps at |v| ~ v_eps |f|/(mu N), the
/// price of skipping the state machine. mu dimensionless, v_eps in velocity units.
/// \throws std::invalid_argument if mu < 0, v_eps <= 0 or either is non-finite, or v_eps is below
///         min_v_eps(mu) (the slope mu / v_eps at v = 0 would overflow, or v_eps is subnormal).
template <class Scalar_ = double>
class RegularisedLaw {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Single-valued law: no stick state, friction -coefficient(v) N in every contact state.
  static constexpr bool has_stick_state = false;

  /// Coefficient mu >= 0, regularisation velocity v_eps >= min_v_eps(mu), shape of s.
  RegularisedLaw(Scalar mu, Scalar v_eps, RegularisedShape shape = RegularisedShape::Tanh)
      : mu_(mu), v_eps_(v_eps), shape_(shape) {
    detail::require_non_negative("RegularisedLaw", "mu", mu);
    detail::require_positive("RegularisedLaw", "v_eps", v_eps);
    if (!(v_eps >= min_v_eps(mu)))
      detail::throw_invalid("RegularisedLaw", "v_eps must be >= max(smallest normal number, mu / largest "
                                              "finite number) = " + detail::format_value(min_v_eps(mu)) +
                                              ", so that the slope mu / v_eps is finite",
                            v_eps);
  }

  /// Smallest admissible v_eps for a coefficient mu: max(numeric_limits::min(), mu / max()), so
  /// that v / v_eps keeps full precision and the peak slope mu / v_eps of the law is finite.
  static Scalar min_v_eps(Scalar mu) {
    using Limits = std::numeric_limits<Scalar>;
    const Scalar overflow = mu / Limits::max();
    return overflow > Limits::min() ? overflow : Limits::min();
  }

  /// Odd friction coefficient at sliding velocity v: f = -coefficient(v) N.
  Scalar coefficient(Scalar v) const {
    using std::tanh;
    const Scalar r = v / v_eps_;
    if (shape_ == RegularisedShape::Tanh) return mu_ * tanh(r);
    return mu_ * (r > Scalar(1) ? Scalar(1) : (r < Scalar(-1) ? Scalar(-1) : r));
  }

  /// d coefficient / dv (for Jacobians): Tanh (mu / v_eps) (1 - tanh^2(v / v_eps)), exactly 0 once
  /// tanh saturates; LinearSaturated: mu/v_eps for |v| < v_eps, else 0.
  Scalar coefficient_derivative(Scalar v) const {
    using std::abs;
    using std::tanh;
    const Scalar r = v / v_eps_;
    if (shape_ == RegularisedShape::Tanh) {
      const Scalar t = tanh(r);
      return (mu_ * (Scalar(1) - t * t)) / v_eps_;  // never inf * 0: mu (1 - t^2) <= mu
    }
    return abs(r) < Scalar(1) ? mu_ / v_eps_ : Scalar(0);
  }

  /// Saturated coefficient mu (|coefficient(v)| <= mu).
  Scalar mu() const noexcept { return mu_; }
  /// Regularisation velocity v_eps.
  Scalar v_eps() const noexcept { return v_eps_; }
  /// Shape of the regularised sign function.
  RegularisedShape shape() const noexcept { return shape_; }

 private:
  Scalar mu_;
  Scalar v_eps_;
  RegularisedShape shape_;
};

}  // namespace stickslip

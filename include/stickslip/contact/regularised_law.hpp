#pragma once
/// \file regularised_law.hpp
/// \brief A smooth (or Lipschitz) single-valued friction law that needs no stick state.

#include <stickslip/contact/friction_law.hpp>

#include <cmath>
#include <cstdint>

namespace stickslip {

/// Shape of the regularised sign function.
enum class RegularisedShape : std::uint8_t {
  Tanh,            ///< mu tanh(v / v_eps): smooth
  LinearSaturated  ///< mu clamp(v / v_eps, -1, 1): Lipschitz, exact Coulomb for |v| >= v_eps
};

/// Regularised Coulomb friction \f$ f = -\mu\,s(v/v_\varepsilon) N \f$ with s = tanh or a linear
/// ramp saturated at +-1. No stick state: a "stuck" body creeps at |v| ~ v_eps |f|/(mu N), the
/// price of skipping the state machine. mu dimensionless, v_eps in velocity units.
/// \throws std::invalid_argument if mu < 0, v_eps <= 0 or either is non-finite.
template <class Scalar_ = double>
class RegularisedLaw {
 public:
  using Scalar = Scalar_;
  static constexpr bool has_stick_state = false;

  RegularisedLaw(Scalar mu, Scalar v_eps, RegularisedShape shape = RegularisedShape::Tanh)
      : mu_(mu), v_eps_(v_eps), shape_(shape) {
    detail::require_non_negative("RegularisedLaw", "mu", mu);
    detail::require_positive("RegularisedLaw", "v_eps", v_eps);
  }

  /// Odd friction coefficient at sliding velocity v: f = -coefficient(v) N.
  Scalar coefficient(Scalar v) const {
    using std::tanh;
    const Scalar r = v / v_eps_;
    if (shape_ == RegularisedShape::Tanh) return mu_ * tanh(r);
    return mu_ * (r > Scalar(1) ? Scalar(1) : (r < Scalar(-1) ? Scalar(-1) : r));
  }

  /// d coefficient / dv (for Jacobians). LinearSaturated: mu/v_eps for |v| < v_eps, else 0.
  Scalar coefficient_derivative(Scalar v) const {
    using std::abs;
    using std::tanh;
    const Scalar r = v / v_eps_;
    if (shape_ == RegularisedShape::Tanh) {
      const Scalar t = tanh(r);
      return mu_ / v_eps_ * (Scalar(1) - t * t);
    }
    return abs(r) < Scalar(1) ? mu_ / v_eps_ : Scalar(0);
  }

  Scalar mu() const noexcept { return mu_; }
  Scalar v_eps() const noexcept { return v_eps_; }
  RegularisedShape shape() const noexcept { return shape_; }

 private:
  Scalar mu_;
  Scalar v_eps_;
  RegularisedShape shape_;
};

}  // namespace stickslip

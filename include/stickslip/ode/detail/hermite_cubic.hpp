#pragma once
/// \file hermite_cubic.hpp
/// \brief The cubic Hermite interpolant of a value and slope at both ends of an interval, on
/// s in [0, 1] (internal: ExactLinearStepper's guard tests, newton_root's first point).

#include <array>
#include <cmath>
#include <limits>

namespace stickslip {
namespace detail {

/// p(s) = h00(s) p0 + h10(s) m0 + h01(s) p1 + h11(s) m1 with the Hermite basis
/// h00 = 2s^3 - 3s^2 + 1, h10 = s^3 - 2s^2 + s, h01 = -2s^3 + 3s^2, h11 = s^3 - s^2: p(0) = p0,
/// p(1) = p1, p'(0) = m0, p'(1) = m1 (slopes per unit s, i.e. the interval length times d/dt).
template <class Scalar>
struct HermiteCubic {
  Scalar p0, m0, p1, m1;

  /// p(s).
  Scalar operator()(Scalar s) const {
    const Scalar s2 = s * s, s3 = s2 * s;
    return (Scalar(2) * s3 - Scalar(3) * s2 + 1) * p0 + (s3 - Scalar(2) * s2 + s) * m0 +
           (Scalar(-2) * s3 + Scalar(3) * s2) * p1 + (s3 - s2) * m1;
  }

  /// p'(s) = qa s^2 + qb s + qc (coefficients below).
  Scalar derivative(Scalar s) const { return (qa() * s + qb()) * s + qc(); }

  /// The stationary points of p in the open interval (0, 1) (roots of the quadratic p'(s) =
  /// qa s^2 + qb s + qc) into s; returns how many (0 to 2).
  int stationary_points(std::array<Scalar, 2>& s) const {
    const Scalar qa = this->qa(), qb = this->qb(), qc = this->qc();
    int n = 0;
    auto keep = [&](Scalar v) {
      if (v > 0 && v < 1) s[static_cast<std::size_t>(n++)] = v;
    };
    if (std::abs(qa) > std::numeric_limits<Scalar>::min()) {
      const Scalar disc = qb * qb - Scalar(4) * qa * qc;
      if (disc >= 0) {
        const Scalar r = std::sqrt(disc);
        keep((-qb + r) / (Scalar(2) * qa));
        keep((-qb - r) / (Scalar(2) * qa));
      }
    } else if (qb != 0) {
      keep(-qc / qb);
    }
    return n;
  }

  /// max over s in [0, 1] of |p(s) - p0|: the interpolant's largest excursion from its start.
  Scalar excursion() const {
    std::array<Scalar, 2> s{};
    const int n = stationary_points(s);
    Scalar e = std::abs(p1 - p0);
    for (int k = 0; k < n; ++k) e = std::max(e, std::abs((*this)(s[static_cast<std::size_t>(k)]) - p0));
    return e;
  }

 private:
  Scalar qa() const { return Scalar(6) * p0 + Scalar(3) * m0 - Scalar(6) * p1 + Scalar(3) * m1; }
  Scalar qb() const { return Scalar(-6) * p0 - Scalar(4) * m0 + Scalar(6) * p1 - Scalar(2) * m1; }
  Scalar qc() const { return m0; }
};

}  // namespace detail
}  // namespace stickslip

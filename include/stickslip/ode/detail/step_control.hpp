#pragma once
/// \file step_control.hpp
/// \brief Internals shared by the integration methods: the weighted RMS error norm and
/// formatting of run messages.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace stickslip {
namespace detail {

/// RMS of err_i / (atol + rtol * max(|a_i|, |b_i|)) (Hairer, Norsett & Wanner, eq. II.4.11).
template <class Scalar, class E, class A, class B>
Scalar weighted_rms(const Eigen::MatrixBase<E>& err, const Eigen::MatrixBase<A>& a,
                    const Eigen::MatrixBase<B>& b, Scalar rtol, Scalar atol) {
  using std::sqrt;
  // An exactly zero error counts 0 even where the weight is 0 (atol = 0 on a zero component).
  const Scalar sum = (err.array() == Scalar(0))
                         .select(Scalar(0), err.array() / (atol + rtol * a.array().abs().max(b.array().abs())))
                         .square()
                         .sum();
  return sqrt(sum / static_cast<Scalar>(err.size()));
}

/// Short decimal text of a number for run messages ("3.1e-15", "0.01234").
template <class Scalar>
std::string short_number(Scalar v, int digits = 6) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

/// "at t = <t>" with enough digits to locate an event time (15 significant digits).
template <class Scalar>
std::string at_time(Scalar t) {
  return "at t = " + short_number(t, 15);
}

}  // namespace detail
}  // namespace stickslip

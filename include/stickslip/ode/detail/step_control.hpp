#pragma once
/// \file step_control.hpp
/// \brief Internals shared by the integration methods: the weighted RMS error norm and
/// formatting of run messages.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

namespace stickslip {
namespace detail {

/// RMS of err_i / (atol + rtol * max(|a_i|, |b_i|)) (Hairer, Norsett & Wanner, eq. II.4.11).
template <class Scalar, class E, class A, class B>
EIGEN_ALWAYS_INLINE Scalar weighted_rms(const Eigen::MatrixBase<E>& err,
                                        const Eigen::MatrixBase<A>& a,
                                        const Eigen::MatrixBase<B>& b, Scalar rtol, Scalar atol) {
  using std::sqrt;
  const auto weight = atol + rtol * a.array().abs().max(b.array().abs());
  Scalar sum = (err.array() / weight).square().sum();
  // Only a zero weight (atol = 0 on a zero component) can make a finite error give a non-finite
  // sum: recount with an exactly zero error counting 0 there (0/0), keeping NaN and Inf otherwise.
  if (!(std::isfinite(sum)))
    sum = (err.array() == Scalar(0)).select(Scalar(0), err.array() / weight).square().sum();
  return sqrt(sum / static_cast<Scalar>(err.size()));
}

template <class System, class = void>
struct has_controlled_size : std::false_type {};
template <class System>
struct has_controlled_size<System, std::void_t<decltype(std::declval<const System&>().controlled_size())>>
    : std::true_type {};

/// The step's error norm: weighted_rms over the whole state, or over its first
/// sys.controlled_size() components when the system declares that only those are under error
/// control (VariationalSystem with the sensitivities left out: the usual choice of shooting codes).
template <class System, class Scalar, class E, class A, class B>
EIGEN_ALWAYS_INLINE Scalar error_norm(const System& sys, const Eigen::MatrixBase<E>& err,
                                      const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b,
                                      Scalar rtol, Scalar atol) {
  if constexpr (has_controlled_size<System>::value) {
    const Eigen::Index k = sys.controlled_size();
    if (k < err.size()) return weighted_rms(err.head(k), a.head(k), b.head(k), rtol, atol);
  }
  return weighted_rms(err, a, b, rtol, atol);
}

template <class Core, class = void>
struct has_new_mode : std::false_type {};
template <class Core>
struct has_new_mode<Core, std::void_t<decltype(std::declval<Core&>().new_mode())>>
    : std::true_type {};

/// Tell a method's core that a mode starts (run start, after a transition): `new_mode()` when it
/// keeps state across accepted steps (Rosenbrock23's Jacobian), otherwise `new_point()`.
template <class Core>
void start_new_mode(Core& core) noexcept {
  if constexpr (has_new_mode<Core>::value) {
    core.new_mode();
  } else {
    core.new_point();
  }
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

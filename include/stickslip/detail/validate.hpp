#pragma once
/// \file validate.hpp
/// \brief Argument checks shared by all components. Caller errors throw std::invalid_argument
/// with a message that names the function/type, the parameter and the offending value.

#include <Eigen/Core>

#include <cassert>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

/// Internal invariant check (not for caller errors, which throw). Active unless NDEBUG.
#define STICKSLIP_ASSERT(cond) assert(cond)

namespace stickslip {
namespace detail {

/// Format a value for an error message with enough digits to be unambiguous.
template <class T>
std::string format_value(const T& value) {
  std::ostringstream os;
  os.precision(17);
  os << value;
  return os.str();
}

/// Throw std::invalid_argument("<where>: <what> (got <value>)").
template <class T>
[[noreturn]] void throw_invalid(const std::string& where, const std::string& what, const T& value) {
  throw std::invalid_argument(where + ": " + what + " (got " + format_value(value) + ")");
}

/// True when every coefficient of v is finite: the sum of v * 0 is 0 for finite values and NaN as
/// soon as one is infinite or NaN (one vectorised reduction, where Eigen's allFinite() is a
/// coefficient-wise comparison loop). Not valid under -ffast-math, as allFinite() is not.
template <class Derived>
bool all_finite(const Eigen::DenseBase<Derived>& v) {
  using std::isfinite;
  return isfinite((v.derived().array() * typename Derived::Scalar(0)).sum());
}

/// True for a finite scalar (std::isfinite, found by argument-dependent lookup for custom scalars).
template <class Scalar>
bool is_finite(Scalar value) {
  using std::isfinite;
  return isfinite(value);
}

/// Require a finite value.
template <class Scalar>
void require_finite(const std::string& where, const char* name, Scalar value) {
  using std::isfinite;
  if (!isfinite(value)) throw_invalid(where, std::string(name) + " must be finite", value);
}

/// Require a finite, strictly positive value.
template <class Scalar>
void require_positive(const std::string& where, const char* name, Scalar value) {
  using std::isfinite;
  if (!(isfinite(value) && value > Scalar(0)))
    throw_invalid(where, std::string(name) + " must be finite and > 0", value);
}

/// Require a finite, non-negative value.
template <class Scalar>
void require_non_negative(const std::string& where, const char* name, Scalar value) {
  using std::isfinite;
  if (!(isfinite(value) && value >= Scalar(0)))
    throw_invalid(where, std::string(name) + " must be finite and >= 0", value);
}

/// Require indices of a state of size n: each in [0, n) and none repeated
/// ("<where>: <name>: index out of [0, n) (got i)" / "index repeated").
inline void require_indices(const std::string& where, const char* name,
                            const std::vector<Eigen::Index>& v, Eigen::Index n) {
  std::vector<bool> seen(static_cast<std::size_t>(n > 0 ? n : 0), false);
  for (Eigen::Index i : v) {
    if (i < 0 || i >= n)
      throw_invalid(where, std::string(name) + ": index out of [0, " + std::to_string(n) + ")", i);
    if (seen[static_cast<std::size_t>(i)]) throw_invalid(where, std::string(name) + ": index repeated", i);
    seen[static_cast<std::size_t>(i)] = true;
  }
}

}  // namespace detail
}  // namespace stickslip

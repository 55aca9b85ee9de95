#pragma once
/// \file format_frequency.hpp
/// \brief A frequency for messages: "2.56 kHz" from an angular frequency.

#include <sstream>
#include <string>

namespace stickslip {
namespace detail {

/// "2.56 kHz": the frequency omega / (2 pi) of an angular frequency omega [rad/s], 3 digits.
template <class Scalar>
std::string format_frequency(Scalar omega) {
  const double f = static_cast<double>(omega) / (2 * 3.14159265358979323846);
  const char* unit = f >= 1e6 ? " MHz" : (f >= 1e3 ? " kHz" : " Hz");
  const double scaled = f >= 1e6 ? f / 1e6 : (f >= 1e3 ? f / 1e3 : f);
  std::ostringstream os;
  os.precision(3);
  os << scaled << unit;
  return os.str();
}

}  // namespace detail
}  // namespace stickslip

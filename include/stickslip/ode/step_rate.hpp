#pragma once
/// \file step_rate.hpp
/// \brief A rate that limits an explicit fixed step, with the name of what it belongs to.

#include <complex>
#include <string>

namespace stickslip {

/// One eigenvalue lambda [1/s] of a system's (linearised) equations that an explicit fixed step
/// must resolve: one step of a method with stability function R multiplies that component by
/// R(h lambda). `source` names it for messages ("mode 6 (2.56 kHz)", "damper 0 regularised
/// friction slope ...").
template <class Scalar>
struct StepRate {
  std::complex<Scalar> lambda;  ///< the rate [1/s] (eigenvalue of the linearised equations)
  std::string source;           ///< what it belongs to, for messages
};

}  // namespace stickslip

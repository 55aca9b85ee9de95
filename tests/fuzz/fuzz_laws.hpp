#pragma once
// A friction law and a harmonic point load read from a fuzz input, shared by the model and
// separation harnesses.
// Law layout: choice(3); 0 CoulombLaw (mu_s, mu_k); 1 StribeckLaw (mu_s, mu_k, v_s, exponent);
// 2 RegularisedLaw (mu, v_eps, LinearSaturated flag).
// Load layout (after the member): coordinate in [0, L], direction choice(5), amplitude in
// [-max_amplitude, max_amplitude], omega in [0, max_omega], phase in [0, 6.3].
#include "fuzz/fuzz_input.hpp"

#include <stickslip/model.hpp>

namespace stickslip_fuzz {

inline stickslip::FrictionLawVariant<double> read_law(Input& in) {
  using namespace stickslip;
  switch (in.choice(3)) {
    case 0: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      return CoulombLaw<double>(mu_s, mu_k);
    }
    case 1: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      const double v_s = in.real(1e-6, 1.0), exponent = in.real(0.1, 4.0);
      return StribeckLaw<double>(mu_s, mu_k, v_s, exponent);
    }
    default: {
      const double mu = in.real(0.0, 1.0), v_eps = in.real(1e-9, 1e-2);
      return RegularisedLaw<double>(mu, v_eps, in.flag() ? RegularisedShape::LinearSaturated : RegularisedShape::Tanh);
    }
  }
}

inline stickslip::PointLoad<double> read_load(Input& in, stickslip::MemberId member, double length,
                                             double max_amplitude, double max_omega) {
  using namespace stickslip;
  const double at = in.real(0.0, length);
  const auto direction = static_cast<LoadDirection>(in.choice(5));
  const double amplitude = in.real(-max_amplitude, max_amplitude), omega = in.real(0.0, max_omega);
  const double phase = in.real(0.0, 6.3);
  return PointLoad<double>::harmonic(member, at, direction, amplitude, omega, phase);
}

}  // namespace stickslip_fuzz

// Fuzz harness: the friction laws (CoulombLaw, StribeckLaw, RegularisedLaw) and CoulombContact
// (friction force, guards, decide) on extreme inputs. Layout of an input (tests/fuzz/fuzz_input.hpp
// encoding; make_corpus.py writes it): law choice(3), its parameters (Coulomb: mu_s, mu_k;
// Stribeck: mu_s, mu_k, v_s, exponent; regularised: mu, v_eps, shape choice(2)), the velocity
// tolerance, then up to 8 probes of (state choice(4), v, N, f_required, watch_lift_off flag).
//
// Rules checked besides the exception types: for finite inputs of moderate size (|.| <= 1e150,
// so that products of two stay finite) and friction coefficients <= 1e6, the coefficients, their
// derivative, the friction force and the guards are finite; an exact law's kinetic coefficient lies in [mu_k, mu_s]; a regularised
// coefficient is odd with |c| <= mu and a derivative >= 0; decide() obeys eq. 1 where the rules
// leave no choice (N <= 0 -> lift-off; a stick decision has |f_required| <= mu_s N; a slip
// decision goes with v when |v| exceeds the tolerance, else against f_required beyond capacity).
#include "fuzz/fuzz_input.hpp"

#include <stickslip/contact.hpp>

#include <cmath>

namespace contact_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;

bool moderate(double v) { return std::isfinite(v) && std::abs(v) <= 1e150; }

/// Friction coefficients up to 1e6 count as physical: beyond, products with forces may overflow.
template <class Law>
bool physical(const Law& law) {
  if constexpr (Law::has_stick_state)
    return law.static_coefficient() <= 1e6;
  else
    return law.mu() <= 1e6;
}

template <class Law>
void probe_law(const Law& law, double v) {
  if (!moderate(v) || !physical(law)) return;
  if constexpr (Law::has_stick_state) {
    const double mu = law.kinetic_coefficient(std::abs(v));
    const double mu_s = law.static_coefficient();
    require(std::isfinite(mu), "kinetic_coefficient(" + str(std::abs(v)) + ") = " + str(mu));
    // mu_k <= mu(s) <= mu_s up to the rounding of mu_k + (mu_s - mu_k) e^-p.
    require(mu <= mu_s * (1 + 4e-16) && mu >= 0,
            "kinetic_coefficient(" + str(std::abs(v)) + ") = " + str(mu) + " outside [0, mu_s]");
  } else {
    const double c = law.coefficient(v), cm = law.coefficient(-v);
    const double d = law.coefficient_derivative(v);
    require(std::isfinite(c) && std::isfinite(d),
            "coefficient(" + str(v) + ") = " + str(c) + ", coefficient_derivative = " + str(d) +
                " (mu = " + str(law.mu()) + ", v_eps = " + str(law.v_eps()) + ")");
    require(c == -cm, "coefficient not odd at v = " + str(v));
    require(std::abs(c) <= law.mu() && d >= 0,
            "coefficient(" + str(v) + ") = " + str(c) + " |c| > mu or derivative " + str(d) + " < 0");
  }
}

template <class Law>
void probe_contact(stickslip_fuzz::Input& in, const Law& law) {
  const CoulombContact<Law> contact(law, in.real(0.0, 1e-6));
  const double tol = contact.velocity_tolerance();
  for (int k = 0; k < 8 && !in.empty(); ++k) {
    const auto s = static_cast<ContactState>(in.choice(4));
    const double v = in.real(-1.0, 1.0), N = in.real(-1.0, 100.0), f = in.real(-100.0, 100.0);
    const bool watch = in.flag();
    probe_law(law, v);
    const bool inputs_moderate = moderate(v) && moderate(N) && moderate(f) && physical(law);
    const double force = contact.friction_force(s, v, N, f);
    if (inputs_moderate) require(std::isfinite(force), "friction_force non-finite: " + str(force));
    double g[CoulombContact<Law>::max_guards];
    const Eigen::Index ng = CoulombContact<Law>::num_guards(s, watch);
    require(ng >= 0 && ng <= CoulombContact<Law>::max_guards, "num_guards out of range");
    contact.guards(s, v, N, f, watch, g);
    for (Eigen::Index i = 0; i < ng; ++i) {
      if (inputs_moderate) require(std::isfinite(g[i]), "guard " + std::to_string(i) + " non-finite");
      static_cast<void>(CoulombContact<Law>::guard_direction(s, i, watch));
    }
    ContactState to;
    try {
      to = contact.decide(s, v, N, f);
    } catch (const std::invalid_argument&) {
      require(!(std::isfinite(v) && std::isfinite(N) && std::isfinite(f)),
              "decide threw on finite inputs");
      continue;
    }
    require(std::isfinite(v) && std::isfinite(N) && std::isfinite(f),
            "decide accepted a non-finite input");
    const std::string at = " (v = " + str(v) + ", N = " + str(N) + ", f_required = " + str(f) +
                           ", tol = " + str(tol) + ")";
    if (!(N > 0)) {
      require(to == ContactState::LiftOff, std::string("N <= 0 not lift-off: ") + to_string(to) + at);
      continue;
    }
    require(to != ContactState::LiftOff, "lift-off with N > 0" + at);
    const int with_v = v > 0 ? 1 : -1, against_f = f > 0 ? -1 : 1;
    if constexpr (Law::has_stick_state) {
      const double capacity = law.static_coefficient() * N;
      if (to == ContactState::Stick)
        require(std::abs(f) <= capacity, "stick beyond capacity" + at);
      else if (std::abs(v) <= tol)
        require(slip_sign(to) == against_f && std::abs(f) > capacity,
                std::string("slip from rest not against f_required beyond capacity: ") +
                    to_string(to) + at);
      else
        require(slip_sign(to) == with_v || (slip_sign(to) == against_f && std::abs(f) > capacity),
                std::string("slip in neither the direction of v nor against f_required: ") +
                    to_string(to) + at);
    } else if (is_slipping(to)) {
      require(std::abs(v) > tol && slip_sign(to) == with_v,
              std::string("regularised law slip state against v: ") + to_string(to) + at);
    }
  }
}

void run(stickslip_fuzz::Input& in) {
  switch (in.choice(3)) {
    case 0: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      probe_contact(in, CoulombLaw<double>(mu_s, mu_k));
      break;
    }
    case 1: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      const double v_s = in.real(1e-6, 1.0), exponent = in.real(0.1, 4.0);
      probe_contact(in, StribeckLaw<double>(mu_s, mu_k, v_s, exponent));
      break;
    }
    default: {
      const double mu = in.real(0.0, 1.0), v_eps = in.real(1e-9, 1e-2);
      const auto shape = in.flag() ? RegularisedShape::LinearSaturated : RegularisedShape::Tanh;
      probe_contact(in, RegularisedLaw<double>(mu, v_eps, shape));
      break;
    }
  }
}

}  // namespace contact_fuzz

STICKSLIP_FUZZ_ENTRY(contact, contact_fuzz::run)

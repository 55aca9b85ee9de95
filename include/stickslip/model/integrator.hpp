#pragma once
/// \file integrator.hpp
/// \brief The integrators simulate() runs (Integrator), and the rule by which Integrator::Auto
/// picks one of them for a system (choose_integrator).

#include "stickslip/detail/validate.hpp"
#include "stickslip/ode/detail/step_control.hpp"
#include "stickslip/ode/linear_part.hpp"
#include "stickslip/ode/mode_residence.hpp"
#include "stickslip/ode/step_rate.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// Integrators of component 5, selectable at run time.
enum class Integrator : std::uint8_t {
  RungeKutta4,      ///< fixed step StepperOptions::fixed_step (the paper's method)
  DormandPrince54,  ///< adaptive explicit 5(4) with dense output
  Rosenbrock23,     ///< adaptive linearly implicit, stiffly stable
  /// ExactLinearStepper: exp(A_m delta) where the mode is linear (LinearPart::exact), Lawson
  /// Dormand-Prince 5(4) with StepperOptions::rtol/atol where it is not; needs a system with
  /// linear_part (has_linear_part_v). Grid: ExactLinearStepper::samples_per_period per shortest
  /// period, at most StepperOptions::max_step.
  Exponential,
  /// One of the above per run, by what the system declares (choose_integrator): Exponential where
  /// every mode is exactly linear, Rosenbrock23 where its step rates are stiff, DormandPrince54
  /// otherwise. The result names the method and the reason (HybridResult::method_reason).
  Auto
};

/// "rk4", "dopri5", "rosenbrock23", "exponential", "auto".
inline const char* to_string(Integrator i) noexcept {
  switch (i) {
    case Integrator::RungeKutta4: return "rk4";
    case Integrator::DormandPrince54: return "dopri5";
    case Integrator::Rosenbrock23: return "rosenbrock23";
    case Integrator::Exponential: return "exponential";
    case Integrator::Auto: return "auto";
  }
  return "unknown";
}

/// Parses "rk4" | "dopri5" | "rosenbrock23" | "exponential" (also "exact") | "auto";
/// throws std::invalid_argument otherwise.
inline Integrator parse_integrator(const std::string& name) {
  if (name == "rk4") return Integrator::RungeKutta4;
  if (name == "dopri5" || name == "dopri") return Integrator::DormandPrince54;
  if (name == "rosenbrock23" || name == "rosenbrock" || name == "stiff") return Integrator::Rosenbrock23;
  if (name == "exponential" || name == "exact") return Integrator::Exponential;
  if (name == "auto") return Integrator::Auto;
  detail::throw_invalid("parse_integrator",
                        "integrator must be rk4, dopri5, rosenbrock23, exponential or auto", name);
}

/// What Integrator::Auto runs, and why (one sentence naming the rule and the quantities it read).
struct IntegratorChoice {
  Integrator integrator = Integrator::DormandPrince54;  ///< never Auto
  std::string reason;                                   ///< why
};

namespace detail {

/// Detects every_mode_exact() (FrictionDampedSystem): true when linear_part is exact in every
/// mode the system can reach.
template <class System, class = void>
struct has_every_mode_exact : std::false_type {};
template <class System>
struct has_every_mode_exact<System, std::void_t<decltype(bool(std::declval<const System&>().every_mode_exact()))>>
    : std::true_type {};

template <class System, class = void>
struct has_linear_rates : std::false_type {};
template <class System>
struct has_linear_rates<System, std::void_t<decltype(std::declval<const System&>().linear_rates())>>
    : std::true_type {};

/// Detects step_rates() (rates with names, StepRate), preferred to linear_rates().
template <class System, class = void>
struct has_step_rates : std::false_type {};
template <class System>
struct has_step_rates<System, std::void_t<decltype(std::declval<const System&>().step_rates())>>
    : std::true_type {};

/// The system's rates: step_rates() when it has them, else linear_rates() named "linear rate k".
template <class System>
std::vector<StepRate<typename System::Scalar>> named_step_rates(const System& system) {
  if constexpr (has_step_rates<System>::value) {
    return system.step_rates();
  } else {
    std::vector<StepRate<typename System::Scalar>> rates;
    for (const auto& lambda : system.linear_rates())
      rates.push_back({lambda, "linear rate " + std::to_string(rates.size())});
    return rates;
  }
}

/// Dormand-Prince 5(4)'s stability boundary on the negative real axis: h |lambda| <= ~3.3.
constexpr double kDopriRealStability = 3.3;
/// Largest order d of the linear part (LinearPart::size(), the x_L = (z, z') of twice the modes)
/// for which Auto takes the exponential method. Its set-up per new mode (an eigen-decomposition,
/// two Padé exponentials and about 8 squarings of order d) costs O(d^3) and each of its grid steps
/// O(d^2) products (the quadratures' Gauss-Legendre nodes: ~60 per step), against six right-hand
/// sides per Dormand-Prince step. Measured on the bladed disk with its energy audit at rtol 1e-6
/// (docs/measurements/disk_cost.md): Dormand-Prince was 3-4x cheaper at d = 12 to 48 and 17x
/// (d = 72) to 116x (d = 288) cheaper above, where modes change every few tens of grid steps.
constexpr Eigen::Index kExponentialMaxOrder = 64;
/// How many times fewer steps Rosenbrock23 must take to be chosen: its step costs a Jacobian (the
/// system's or n finite differences), an LU factorisation and two solves, against six RHS
/// evaluations of a Dormand-Prince step.
constexpr double kImplicitStepCost = 10.0;

}  // namespace detail

/// The rule of Integrator::Auto for `system` starting in `mode` at (t0, x0), run to t_end:
///  1. Exponential when the system has linear_part, its linear part is of order d <=
///     detail::kExponentialMaxOrder (64; beyond, the propagators of each new mode, O(d^3), and
///     the grid steps' products, O(d^2), cost more than Dormand-Prince's steps) and every mode is
///     exactly linear: its
///     every_mode_exact() when it has one (FrictionDampedSystem: no time_function load, every
///     contact fixed and every law a CoulombLaw), else linear_part of the start mode reports
///     exact. Within a mode the method is then exact; its cost does not depend on the tolerance.
///     Also Exponential when not every mode is exact but the start mode is, with affine guards
///     that mode_residence proves positive until t_end (a scene that stays stuck, from its forced
///     response and a bound of its free response): the run never leaves that mode. Costs one
///     eigen-decomposition of the mode's A.
///  2. Rosenbrock23 when the system reports rates (step_rates(), else linear_rates()) and the
///     fastest one that decays without oscillating (Re lambda < 0, |Im lambda| <= |Re lambda|),
///     |lambda_d|, holds Dormand-Prince 10x below the step Rosenbrock23 needs for accuracy:
///     10 * 3.3 / |lambda_d| < rtol^(1/3) / |lambda_r|, with lambda_r the fastest of the other
///     rates (the oscillations the solution has to resolve; at least 1 / (t_end - t0)) and
///     rtol^(1/3) / |lambda_r| the step at which Rosenbrock23's local error (h lambda_r)^3
///     reaches rtol. Then the explicit method's step is set by stability, not accuracy, and the
///     implicit one takes 10x fewer steps (detail::kImplicitStepCost: its step is dearer): the
///     problem is stiff at this tolerance.
///  3. DormandPrince54 otherwise.
/// Costs one linear_part call (rule 1 without every_mode_exact, rule 1b with it, and rule 1 with
/// it when the state has more than 64 components), one eigen-decomposition (rule 1b) and one
/// rates call.
template <class System>
IntegratorChoice choose_integrator(System& system, const typename System::Mode& mode,
                                   typename System::Scalar t0, const typename System::State& x0,
                                   typename System::Scalar t_end, typename System::Scalar rtol) {
  using Scalar = typename System::Scalar;
  IntegratorChoice c;
  if constexpr (has_linear_part_v<System>) {
    bool exact = false;
    std::string why;
    if constexpr (detail::has_every_mode_exact<System>::value) {
      exact = system.every_mode_exact();
      why = exact ? "every mode is exactly linear (fixed contacts, Coulomb laws, harmonic loads)"
                  : "not every mode is exactly linear (a moving contact, a regularised law or a "
                    "time_function load)";
    } else {
      LinearPart<Scalar> lp;
      exact = system.linear_part(mode, t0, x0, lp) && lp.exact;
      why = exact ? "the start mode's linear part is exact"
                  : "the start mode's linear part is not exact";
    }
    // The linear part's order d (<= the state's size: a linear_part call only where that is
    // above the limit).
    Eigen::Index order = x0.size();
    if (order > detail::kExponentialMaxOrder) {
      LinearPart<Scalar> lp;
      lp.want_inexact_guards = false;
      if (system.linear_part(mode, t0, x0, lp)) order = lp.size();
    }
    const bool small = order <= detail::kExponentialMaxOrder;
    if (exact && small) {
      c.integrator = Integrator::Exponential;
      c.reason = why + ": exponential method";
      return c;
    }
    if (!small)
      why += ", but the linear part's order " + std::to_string(order) + " is above " +
             std::to_string(detail::kExponentialMaxOrder) +
             " (the exponential method's propagators of each new mode cost O(d^3))";
    if constexpr (detail::has_every_mode_exact<System>::value) {
      // Rule 1b: the run provably stays in an exact start mode (a stuck scene).
      LinearPart<Scalar> lp;
      lp.want_inexact_guards = false;  // only an exact mode's guards are used
      if (small && !exact && system.linear_part(mode, t0, x0, lp) && lp.exact) {
        const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> start = x0.head(lp.size());
        const ModeResidence<Scalar> stay = mode_residence<Scalar>(lp, t0, start, t_end);
        if (stay.stays) {
          c.integrator = Integrator::Exponential;
          c.reason = why + ", but the start mode is exactly linear and its guards stay positive until "
                     "t_end (lowest bound " + detail::short_number(stay.lower[stay.tightest]) +
                     ", guard " + std::to_string(stay.tightest) + "): exponential method";
          return c;
        }
        why += stay.bounded ? "; the start mode is exact but guard " + std::to_string(stay.tightest) +
                                  " may fire (bound " + detail::short_number(stay.lower[stay.tightest]) + ")"
                            : "; the start mode is exact (" + stay.why_not + ")";
      }
    }
    c.reason = why;
  } else {
    c.reason = "no linear part";
  }
  if constexpr (detail::has_step_rates<System>::value || detail::has_linear_rates<System>::value) {
    using std::abs;
    const Scalar span = t_end - t0;
    Scalar resolved = span > 0 ? Scalar(1) / span : Scalar(0);
    Scalar fastest_decay = 0;
    std::string decay_source, resolved_source = "the run's length";
    for (const auto& r : detail::named_step_rates(system)) {
      const Scalar re = r.lambda.real(), im = r.lambda.imag(), mag = std::abs(r.lambda);
      if (re < 0 && abs(im) <= abs(re)) {
        if (mag > fastest_decay) {
          fastest_decay = mag;
          decay_source = r.source;
        }
      } else if (mag > resolved) {
        resolved = mag;
        resolved_source = r.source;
      }
    }
    using std::cbrt;
    const Scalar ratio = resolved > 0 ? fastest_decay / resolved : Scalar(0);
    // 10 * 3.3 / |lambda_d| < rtol^(1/3) / |lambda_r|  <=>  |lambda_d| / |lambda_r| > 33 / rtol^(1/3)
    const Scalar limit = Scalar(detail::kImplicitStepCost * detail::kDopriRealStability) /
                         cbrt(std::max(rtol, Scalar(1e-15)));
    if (fastest_decay > 0 && ratio > limit) {
      c.integrator = Integrator::Rosenbrock23;
      c.reason += "; stiff: " + decay_source + " decays at |lambda| = " +
                  detail::short_number(fastest_decay) + " 1/s, " + detail::short_number(ratio) +
                  " x the fastest rate to resolve (" + resolved_source + "), above 33 / rtol^(1/3) = " +
                  detail::short_number(limit) + ": Rosenbrock23";
      return c;
    }
    c.reason += "; not stiff (decay / resolved rate " + detail::short_number(ratio) +
                " <= 33 / rtol^(1/3) = " + detail::short_number(limit) + ")";
  }
  c.integrator = Integrator::DormandPrince54;
  c.reason += ": Dormand-Prince 5(4)";
  return c;
}

}  // namespace stickslip

#pragma once
/// \file simulate.hpp
/// \brief Run a hybrid system with an integrator chosen at run time (command lines, sweeps).

#include "stickslip/detail/validate.hpp"
#include "stickslip/ode.hpp"
#include "stickslip/ode/exact_linear_stepper.hpp"

#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

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
  Exponential
};

/// "rk4", "dopri5", "rosenbrock23".
inline const char* to_string(Integrator i) noexcept {
  switch (i) {
    case Integrator::RungeKutta4: return "rk4";
    case Integrator::DormandPrince54: return "dopri5";
    case Integrator::Rosenbrock23: return "rosenbrock23";
    case Integrator::Exponential: return "exponential";
  }
  return "unknown";
}

/// Parses "rk4" | "dopri5" | "rosenbrock23" | "exponential" (also "exact");
/// throws std::invalid_argument otherwise.
inline Integrator parse_integrator(const std::string& name) {
  if (name == "rk4") return Integrator::RungeKutta4;
  if (name == "dopri5" || name == "dopri") return Integrator::DormandPrince54;
  if (name == "rosenbrock23" || name == "rosenbrock" || name == "stiff") return Integrator::Rosenbrock23;
  if (name == "exponential" || name == "exact") return Integrator::Exponential;
  detail::throw_invalid("parse_integrator",
                        "integrator must be rk4, dopri5, rosenbrock23 or exponential", name);
}

/// Integrator and stepper options of one run.
template <class Scalar>
struct RunOptions {
  Integrator integrator = Integrator::DormandPrince54;
  StepperOptions<Scalar> stepper{};
  /// With RungeKutta4: refuse (std::invalid_argument) a fixed step above RK4's stability limit
  /// for the system's linear rates, when the system reports them (linear_rates()). Switch off
  /// only to study what an unstable step does.
  bool check_stability_limit = true;
};

namespace detail {

/// Detects an optional system hook validate_state(mode, x, where) that throws
/// std::invalid_argument on a state or mode of the wrong size (FrictionDampedSystem).
template <class System, class = void>
struct has_validate_state : std::false_type {};
template <class System>
struct has_validate_state<System, std::void_t<decltype(std::declval<const System&>().validate_state(
                                      std::declval<const typename System::Mode&>(),
                                      std::declval<const typename System::State&>(), "simulate"))>>
    : std::true_type {};

template <class System, class = void>
struct has_linear_rates : std::false_type {};
template <class System>
struct has_linear_rates<System, std::void_t<decltype(std::declval<const System&>().linear_rates())>>
    : std::true_type {};

/// |R(z)| of the classical Runge-Kutta method, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24: one step
/// multiplies the solution of y' = lambda y by R(h lambda).
template <class Scalar>
Scalar rk4_amplification(std::complex<Scalar> z) {
  return std::abs(Scalar(1) + z * (Scalar(1) + z * (Scalar(0.5) + z * (Scalar(1) / 6 + z / Scalar(24)))));
}

/// Throws std::invalid_argument naming options.fixed_step when |R(h lambda)| > 1 for a rate of
/// `rates` (the step would amplify that component at every step). The message names the binding
/// rate and the largest stable step: the smallest, over the offending rates, of the step where
/// |R| reaches 1 along the ray h lambda (found by bisection; RK4's region meets each ray of the
/// left half-plane in one interval).
template <class Scalar, class Rates>
void require_rk4_stable(const Rates& rates, Scalar h) {
  const Scalar slack = 1 + 64 * std::numeric_limits<Scalar>::epsilon();  // round-off at |R| = 1
  Scalar h_stable = h;
  std::complex<Scalar> binding{};
  for (const auto& lambda : rates) {
    if (!(rk4_amplification(h * lambda) > slack)) continue;
    Scalar lo = 0, hi = h;
    for (int it = 0; it < 80; ++it) {
      const Scalar mid = (lo + hi) / 2;
      (rk4_amplification(mid * lambda) > slack ? hi : lo) = mid;
    }
    if (lo < h_stable) {
      h_stable = lo;
      binding = lambda;
    }
  }
  if (h_stable == h) return;
  throw_invalid("simulate",
                "options.stepper.fixed_step is above RungeKutta4's stability limit for the linear "
                "rate |lambda| = " + format_value(std::abs(binding)) + " 1/s (|R(h lambda)| = " +
                    format_value(rk4_amplification(h * binding)) + " > 1; stable up to h = " +
                    format_value(h_stable) + " s): use a smaller step, fewer modes, damping of the "
                    "high modes or an adaptive method, or set RunOptions::check_stability_limit = false",
                h);
}

}  // namespace detail

/// Integrates `system` from (t0, x0) in `mode` to t_end with the chosen integrator.
/// With RungeKutta4 and a system that reports linear_rates() (FrictionDampedSystem), a fixed step
/// above the stability limit of one of those rates throws std::invalid_argument before any step
/// (see RunOptions::check_stability_limit). A system with a validate_state(mode, x, where) hook
/// (FrictionDampedSystem) checks the sizes of x0 and mode first (std::invalid_argument).
/// Integrator::Exponential throws std::invalid_argument ("options.integrator") for a system
/// without linear_part.
template <class System, class Observer>
HybridResult<typename System::Scalar, typename System::State, typename System::Mode> simulate(
    System& system, typename System::Mode mode, typename System::Scalar t0,
    const typename System::State& x0, typename System::Scalar t_end,
    const RunOptions<typename System::Scalar>& options, Observer& observer) {
  if constexpr (detail::has_validate_state<System>::value) system.validate_state(mode, x0, "simulate");
  switch (options.integrator) {
    case Integrator::RungeKutta4: {
      if constexpr (detail::has_linear_rates<System>::value) {
        if (options.check_stability_limit && options.stepper.fixed_step > 0)
          detail::require_rk4_stable(system.linear_rates(), options.stepper.fixed_step);
      }
      HybridStepper<System, RungeKutta4> stepper(system, options.stepper);
      return stepper.integrate(mode, t0, x0, t_end, observer);
    }
    case Integrator::Rosenbrock23: {
      HybridStepper<System, Rosenbrock23> stepper(system, options.stepper);
      return stepper.integrate(mode, t0, x0, t_end, observer);
    }
    case Integrator::Exponential: {
      if constexpr (has_linear_part_v<System>) {
        ExactLinearStepper<System> stepper(system, options.stepper);
        return stepper.integrate(mode, t0, x0, t_end, observer);
      } else {
        detail::throw_invalid("simulate",
                              "options.integrator Exponential needs a system with linear_part",
                              std::string(to_string(options.integrator)));
      }
    }
    case Integrator::DormandPrince54: break;
  }
  HybridStepper<System, DormandPrince54> stepper(system, options.stepper);
  return stepper.integrate(mode, t0, x0, t_end, observer);
}

}  // namespace stickslip

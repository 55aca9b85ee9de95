#pragma once
/// \file simulate.hpp
/// \brief Run a hybrid system with an integrator chosen at run time (command lines, sweeps).

#include "stickslip/detail/validate.hpp"
#include "stickslip/model/detail/enum_checks.hpp"
#include "stickslip/ode.hpp"
#include "stickslip/ode/exact_linear_stepper.hpp"
#include "stickslip/ode/observer_ref.hpp"

#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
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
  /// Integrator of the run (default DormandPrince54; RungeKutta4 steps by stepper.fixed_step).
  Integrator integrator = Integrator::DormandPrince54;
  /// Tolerances, step sizes, output interval and Zeno limits (stickslip/ode/stepper_options.hpp).
  StepperOptions<Scalar> stepper{};
  /// With RungeKutta4: refuse (std::invalid_argument) a fixed step above RK4's stability limit
  /// for the system's rates, when the system reports them (step_rates(), else linear_rates());
  /// the message names the binding rate. Switch off only to study what an unstable step does.
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

/// Detects validate_start(mode, t0, x0, where) (FrictionDampedSystem): the start's checks,
/// preferred to validate_state.
template <class System, class = void>
struct has_validate_start : std::false_type {};
template <class System>
struct has_validate_start<System, std::void_t<decltype(std::declval<const System&>().validate_start(
                                      std::declval<const typename System::Mode&>(),
                                      std::declval<typename System::Scalar>(),
                                      std::declval<const typename System::State&>(), "simulate"))>>
    : std::true_type {};

/// Detects load_fault() (FrictionDampedSystem): the last non-finite load value, named in a
/// NonFiniteState status.
template <class System, class = void>
struct has_load_fault : std::false_type {};
template <class System>
struct has_load_fault<System, std::void_t<decltype(std::declval<const System&>().load_fault().count)>>
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

/// |R(z)| of the classical Runge-Kutta method, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24: one step
/// multiplies the solution of y' = lambda y by R(h lambda).
template <class Scalar>
Scalar rk4_amplification(std::complex<Scalar> z) {
  return std::abs(Scalar(1) + z * (Scalar(1) + z * (Scalar(0.5) + z * (Scalar(1) / 6 + z / Scalar(24)))));
}

/// Throws std::invalid_argument naming options.fixed_step when |R(h lambda)| > 1 (or is not
/// finite) for a rate of `rates` (StepRate: the step would amplify that component at every
/// step). The message names the binding rate's source and the largest stable step: the
/// smallest, over the offending rates, of the step where |R| reaches 1 along the ray h lambda
/// (found by bisection; RK4's region meets each ray of the left half-plane in one interval).
template <class Scalar>
void require_rk4_stable(const std::vector<StepRate<Scalar>>& rates, Scalar h) {
  const Scalar slack = 1 + 64 * std::numeric_limits<Scalar>::epsilon();  // round-off at |R| = 1
  auto amplified = [slack](std::complex<Scalar> z) { return !(rk4_amplification(z) <= slack); };
  Scalar h_stable = h;
  const StepRate<Scalar>* binding = nullptr;
  for (const auto& rate : rates) {
    if (!amplified(h * rate.lambda)) continue;
    Scalar lo = 0, hi = h;
    for (int it = 0; it < 80; ++it) {
      const Scalar mid = (lo + hi) / 2;
      (amplified(mid * rate.lambda) ? hi : lo) = mid;
    }
    if (binding == nullptr || lo < h_stable) {
      h_stable = lo;
      binding = &rate;
    }
  }
  if (binding == nullptr) return;
  throw_invalid("simulate",
                "options.stepper.fixed_step is above RungeKutta4's stability limit for " +
                    binding->source + ": rate lambda = " + format_value(binding->lambda) +
                    ", |lambda| = " + format_value(std::abs(binding->lambda)) + " 1/s (|R(h lambda)| = " +
                    format_value(rk4_amplification(h * binding->lambda)) + " > 1; stable up to h = " +
                    format_value(h_stable) + " s): use a smaller step, fewer modes, damping of the "
                    "high modes, a wider regularisation or an adaptive method, or set "
                    "RunOptions::check_stability_limit = false",
                h);
}

/// The system's rates for the RK4 check: step_rates() when it has them, else linear_rates()
/// named "linear rate k".
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

}  // namespace detail

/// The result of simulate() on `System`.
template <class System>
using SimulationResult =
    HybridResult<typename System::Scalar, typename System::State, typename System::Mode>;

/// The observer reference simulate() passes to the steppers (ObserverRef).
template <class System>
using SimulationObserver =
    ObserverRef<typename System::Scalar, typename System::State, typename System::Mode>;

namespace detail {

/// One run of HybridStepper<System, Method> (the part of simulate() compiled once per system type
/// and method, for every observer; instantiated ahead of time by stickslip::compiled).
template <class System, class Method>
SimulationResult<System> simulate_with(System& system, typename System::Mode mode,
                                       typename System::Scalar t0, const typename System::State& x0,
                                       typename System::Scalar t_end,
                                       const StepperOptions<typename System::Scalar>& options,
                                       SimulationObserver<System> observer) {
  HybridStepper<System, Method> stepper(system, options);
  return stepper.integrate(std::move(mode), t0, x0, t_end, observer);
}

/// One run of ExactLinearStepper<System>; a system without linear_part gets
/// std::invalid_argument naming options.integrator.
template <class System>
SimulationResult<System> simulate_exponential(System& system, typename System::Mode mode,
                                              typename System::Scalar t0,
                                              const typename System::State& x0,
                                              typename System::Scalar t_end,
                                              const StepperOptions<typename System::Scalar>& options,
                                              SimulationObserver<System> observer) {
  if constexpr (has_linear_part_v<System>) {
    ExactLinearStepper<System> stepper(system, options);
    return stepper.integrate(std::move(mode), t0, x0, t_end, observer);
  } else {
    (void)system, (void)mode, (void)t0, (void)x0, (void)t_end, (void)options, (void)observer;
    throw_invalid("simulate", "options.integrator Exponential needs a system with linear_part",
                  std::string(to_string(Integrator::Exponential)));
  }
}

template <class System>
SimulationResult<System> simulate_method(System& system, typename System::Mode mode,
                                         typename System::Scalar t0, const typename System::State& x0,
                                         typename System::Scalar t_end,
                                         const RunOptions<typename System::Scalar>& options,
                                         SimulationObserver<System> observer);

/// simulate() after its observer became a SimulationObserver: checks (t0, t_end, the
/// integrator, and the system's validate_start or validate_state), then the chosen method; a
/// NonFiniteState status names a load whose value was not finite (load_fault()).
template <class System>
SimulationResult<System> simulate_dispatch(System& system, typename System::Mode mode,
                                           typename System::Scalar t0,
                                           const typename System::State& x0,
                                           typename System::Scalar t_end,
                                           const RunOptions<typename System::Scalar>& options,
                                           SimulationObserver<System> observer) {
  require_finite("simulate", "t0", t0);
  require_finite("simulate", "t_end", t_end);
  if (!(t_end >= t0)) throw_invalid("simulate", "t_end must be >= t0", t_end);
  require_enumerator("simulate", "options.integrator", "Integrator", options.integrator, Integrator::Exponential);
  if constexpr (has_validate_start<System>::value)
    system.validate_start(mode, t0, x0, "simulate");
  else if constexpr (has_validate_state<System>::value)
    system.validate_state(mode, x0, "simulate");
  if constexpr (has_load_fault<System>::value) {  // name a load whose value was not finite
    const long faults = system.load_fault().count;
    SimulationResult<System> r = simulate_method(system, std::move(mode), t0, x0, t_end, options, observer);
    if (r.status == Status::NonFiniteState && system.load_fault().count != faults) {
      const auto& f = system.load_fault();
      r.message = "PointLoad[" + std::to_string(f.load) + "] is not finite at t = " + format_value(f.t) +
                  " (F = " + format_value(f.value) + "): " + r.message;
    }
    return r;
  } else {
    return simulate_method(system, std::move(mode), t0, x0, t_end, options, observer);
  }
}

/// The chosen method of simulate_dispatch, after its checks.
template <class System>
SimulationResult<System> simulate_method(System& system, typename System::Mode mode,
                                         typename System::Scalar t0, const typename System::State& x0,
                                         typename System::Scalar t_end,
                                         const RunOptions<typename System::Scalar>& options,
                                         SimulationObserver<System> observer) {
  switch (options.integrator) {
    case Integrator::RungeKutta4:
      if constexpr (has_step_rates<System>::value || has_linear_rates<System>::value) {
        if (options.check_stability_limit && options.stepper.fixed_step > 0)
          require_rk4_stable(named_step_rates(system), options.stepper.fixed_step);
      }
      return simulate_with<System, RungeKutta4>(system, std::move(mode), t0, x0, t_end,
                                                options.stepper, observer);
    case Integrator::Rosenbrock23:
      return simulate_with<System, Rosenbrock23>(system, std::move(mode), t0, x0, t_end,
                                                 options.stepper, observer);
    case Integrator::Exponential:
      return simulate_exponential(system, std::move(mode), t0, x0, t_end, options.stepper, observer);
    case Integrator::DormandPrince54: break;
  }
  return simulate_with<System, DormandPrince54>(system, std::move(mode), t0, x0, t_end,
                                                options.stepper, observer);
}

}  // namespace detail

/// Integrates `system` from (t0, x0) in `mode` to t_end with the chosen integrator, calling
/// `observer` (any observer of docs/ode.md, passed on as an ObserverRef, so that the steppers are
/// compiled once per system type whatever the observer).
/// With RungeKutta4 and a system that reports step_rates() or linear_rates()
/// (FrictionDampedSystem), a fixed step above the stability limit of one of those rates throws
/// std::invalid_argument before any step, naming the binding rate's source and the largest stable
/// step (see RunOptions::check_stability_limit). A system with a validate_state(mode, x, where) hook
/// (FrictionDampedSystem) checks the sizes of x0 and mode first (std::invalid_argument).
/// Integrator::Exponential throws std::invalid_argument ("options.integrator") for a system
/// without linear_part.
template <class System, class Observer>
SimulationResult<System> simulate(System& system, typename System::Mode mode,
                                  typename System::Scalar t0, const typename System::State& x0,
                                  typename System::Scalar t_end,
                                  const RunOptions<typename System::Scalar>& options,
                                  Observer& observer) {
  return detail::simulate_dispatch(system, std::move(mode), t0, x0, t_end, options,
                                   SimulationObserver<System>(observer));
}

/// simulate() without an observer: the result (final state, status, statistics) only.
template <class System>
SimulationResult<System> simulate(System& system, typename System::Mode mode,
                                  typename System::Scalar t0, const typename System::State& x0,
                                  typename System::Scalar t_end,
                                  const RunOptions<typename System::Scalar>& options = {}) {
  NullObserver none;
  return simulate(system, std::move(mode), t0, x0, t_end, options, none);
}

}  // namespace stickslip

#ifdef STICKSLIP_COMPILED
#include "stickslip/model/detail/compiled_simulate.hpp"
#endif

#pragma once
/// \file simulate.hpp
/// \brief Run a hybrid system with an integrator chosen at run time (command lines, sweeps).

#include "stickslip/detail/validate.hpp"
#include "stickslip/model/detail/enum_checks.hpp"
#include "stickslip/model/integrator.hpp"
#include "stickslip/ode.hpp"
#include "stickslip/ode/exact_linear_stepper.hpp"
#include "stickslip/ode/observer_ref.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// Integrator and stepper options of one run.
template <class Scalar>
struct RunOptions {
  /// Integrator of the run (default Auto: chosen per run by choose_integrator, the choice and
  /// its reason reported in the result; RungeKutta4 steps by stepper.fixed_step).
  Integrator integrator = Integrator::Auto;
  /// Tolerances, step sizes, output interval and Zeno limits (stickslip/ode/stepper_options.hpp).
  StepperOptions<Scalar> stepper{};
  /// With RungeKutta4: refuse (std::invalid_argument) a fixed step above RK4's stability limit
  /// for the system's rates, when the system reports them (step_rates(), else linear_rates());
  /// the message names the binding rate. Switch off only to study what an unstable step does.
  bool check_stability_limit = true;
  /// Repeat the run at rtol / 10 and atol / 10 (RungeKutta4: fixed_step / 10) on a copy of the
  /// system, without observer, and report in the result's sequence_check whether the two
  /// sequences of switches agree and the time of the first that differs. Costs the tighter run:
  /// 1.6x (Dormand-Prince, steps ~ tol^(-1/5)) to 2.2x (Rosenbrock23, tol^(-1/3)) the run's
  /// steps, 10x with RungeKutta4, ~1x with the exponential method on exact modes, plus a copy
  /// of the system and a record of both runs' switches.
  bool check_event_sequence = false;
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

/// True when modes compare with == (the event-sequence check compares them).
template <class Mode, class = void>
struct has_mode_equality : std::false_type {};
template <class Mode>
struct has_mode_equality<Mode, std::void_t<decltype(bool(std::declval<const Mode&>() == std::declval<const Mode&>()))>>
    : std::true_type {};

/// Records a run's switches (times, from- and to-modes), forwarding every call to `forward`
/// (none when null).
template <class System>
struct SwitchRecorder {
  using Scalar = typename System::Scalar;
  using State = typename System::State;
  using Mode = typename System::Mode;
  const SimulationObserver<System>* forward = nullptr;
  std::vector<Scalar> times;
  std::vector<std::pair<Mode, Mode>> switches;
  bool on_step(Scalar t, const State& x, const Mode& m) {
    return forward == nullptr || forward->on_step(t, x, m);
  }
  void on_event(const EventRecord<Scalar, Mode>& record, const State& x_after) {
    times.push_back(record.t);
    switches.emplace_back(record.from, record.to);
    if (forward != nullptr) forward->on_event(record, x_after);
  }
  bool on_sample(Scalar t, const State& x, const Mode& m) {
    return forward == nullptr || forward->on_sample(t, x, m);
  }
};

/// The check of a run's switches `a` against those of the tighter run `b` (EventSequenceCheck).
template <class System>
EventSequenceCheck<typename System::Scalar> compare_switches(const SwitchRecorder<System>& a,
                                                            const SwitchRecorder<System>& b) {
  EventSequenceCheck<typename System::Scalar> c;
  c.checked = true;
  c.events = static_cast<long>(a.switches.size());
  c.events_tight = static_cast<long>(b.switches.size());
  const std::size_t common = std::min(a.switches.size(), b.switches.size());
  for (std::size_t k = 0; k < common; ++k) {
    if (a.switches[k].first == b.switches[k].first && a.switches[k].second == b.switches[k].second)
      continue;
    c.agree = false;
    c.first_difference = std::min(a.times[k], b.times[k]);
    return c;
  }
  if (a.switches.size() != b.switches.size()) {
    c.agree = false;
    c.first_difference = a.switches.size() > common ? a.times[common] : b.times[common];
  }
  return c;
}

/// simulate_method after Integrator::Auto is resolved (choose_integrator), with the
/// event-sequence check when asked; names the method and the reason in the result.
template <class System>
SimulationResult<System> simulate_resolved(System& system, typename System::Mode mode,
                                           typename System::Scalar t0,
                                           const typename System::State& x0,
                                           typename System::Scalar t_end,
                                           const RunOptions<typename System::Scalar>& options,
                                           SimulationObserver<System> observer) {
  RunOptions<typename System::Scalar> run = options;
  std::string reason = "options.integrator";
  if (run.integrator == Integrator::Auto) {
    IntegratorChoice choice = choose_integrator(system, mode, t0, x0, t_end, run.stepper.rtol);
    run.integrator = choice.integrator;
    reason = std::move(choice.reason);
  }
  SimulationResult<System> r;
  if (!run.check_event_sequence) {
    r = simulate_method(system, std::move(mode), t0, x0, t_end, run, observer);
  } else if constexpr (std::is_copy_constructible_v<System> && has_mode_equality<typename System::Mode>::value) {
    System tight_system = system;  // the tighter run starts from the system as the run does
    SwitchRecorder<System> main_switches;
    main_switches.forward = &observer;
    r = simulate_method(system, mode, t0, x0, t_end, run, SimulationObserver<System>(main_switches));
    RunOptions<typename System::Scalar> tight = run;
    tight.check_event_sequence = false;
    tight.stepper.rtol /= 10;
    tight.stepper.atol /= 10;
    if (run.integrator == Integrator::RungeKutta4) tight.stepper.fixed_step /= 10;
    tight.stepper.output_interval = 0;
    SwitchRecorder<System> tight_switches;
    const SimulationResult<System> rt = simulate_method(tight_system, std::move(mode), t0, x0, t_end,
                                                        tight, SimulationObserver<System>(tight_switches));
    r.sequence_check = compare_switches(main_switches, tight_switches);
    r.sequence_check.rtol_tight =
        run.integrator == Integrator::RungeKutta4 ? tight.stepper.fixed_step : tight.stepper.rtol;
    if (rt.status != r.status || rt.t != r.t) {  // the tighter run ended elsewhere: not converged
      r.sequence_check.agree = false;
      if (!(r.sequence_check.first_difference <= std::min(r.t, rt.t)))
        r.sequence_check.first_difference = std::min(r.t, rt.t);
    }
  } else {
    throw_invalid("simulate",
                  "options.check_event_sequence needs a copy-constructible system whose modes compare with ==",
                  std::string("check_event_sequence"));
  }
  r.method = to_string(run.integrator);
  r.method_reason = std::move(reason);
  return r;
}

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
  require_enumerator("simulate", "options.integrator", "Integrator", options.integrator, Integrator::Auto);
  if constexpr (has_validate_start<System>::value)
    system.validate_start(mode, t0, x0, "simulate");
  else if constexpr (has_validate_state<System>::value)
    system.validate_state(mode, x0, "simulate");
  if constexpr (has_load_fault<System>::value) {  // name a load whose value was not finite
    const long faults = system.load_fault().count;
    SimulationResult<System> r = simulate_resolved(system, std::move(mode), t0, x0, t_end, options, observer);
    if (r.status == Status::NonFiniteState && system.load_fault().count != faults) {
      const auto& f = system.load_fault();
      r.message = "PointLoad[" + std::to_string(f.load) + "] is not finite at t = " + format_value(f.t) +
                  " (F = " + format_value(f.value) + "): " + r.message;
    }
    return r;
  } else {
    return simulate_resolved(system, std::move(mode), t0, x0, t_end, options, observer);
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
    case Integrator::DormandPrince54:
    case Integrator::Auto:  // (resolved before, by simulate_resolved)
      break;
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
/// without linear_part. Integrator::Auto (the default) runs choose_integrator's pick; the
/// result's method and method_reason name the method that ran and why. With
/// RunOptions::check_event_sequence the result's sequence_check compares the run's switches with
/// those of a tighter run (its cost: see that option).
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

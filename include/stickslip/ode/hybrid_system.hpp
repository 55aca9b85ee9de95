#pragma once
/// \file hybrid_system.hpp
/// \brief The hybrid (piecewise-smooth) system concept, and the types a run reports with.
///
/// A hybrid system has a discrete mode `m` and a continuous state `x` (an Eigen column vector,
/// fixed or dynamic size). In each mode it supplies
///
///     void rhs(const Mode& m, Scalar t, const State& x, State& dxdt);          // dx/dt = f_m(t, x)
///     Eigen::Index num_guards(const Mode& m) const;                           // size of g
///     void guards(const Mode& m, Scalar t, const State& x, GuardVector& g);   // g_m(t, x)
///     CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const;
///     TransitionAction transition(Mode& m, const TriggeredGuards& which, Scalar t, State& x);
///
/// An event happens when a guard component crosses zero in its direction. At the event the
/// stepper calls `transition`, which picks the next mode (and may reset x, e.g. a velocity jump),
/// or asks the run to stop with a reason. `GuardVector` is `Eigen::Matrix<Scalar, Dynamic, 1>`,
/// sized by the stepper to `num_guards(m)` before each call (no allocation when the capacity
/// suffices). See docs/ode.md.

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// Direction in which a guard's zero crossing is an event.
enum class CrossingDirection : std::uint8_t {
  Rising,   ///< g goes from negative to positive
  Falling,  ///< g goes from positive to negative
  Either    ///< both directions
};

/// Indices of the guards that triggered together at one event (earliest crossing, plus all
/// others within the event time tolerance). Capacity is reserved once; no allocation per event
/// while the number of guards does not grow.
using TriggeredGuards = std::vector<Eigen::Index>;

/// What a system's `transition` asks of the stepper.
struct TransitionAction {
  bool stop = false;    ///< end the run with Status::StoppedBySystem
  std::string reason;   ///< why (kept in HybridResult::message)

  /// Continue the run in the (possibly new) mode.
  static TransitionAction proceed() { return {}; }
  /// Stop the run with Status::StoppedBySystem and the message `why`.
  static TransitionAction halt(std::string why) { return {true, std::move(why)}; }
};

/// How a run ended.
enum class Status : std::uint8_t {
  Success,            ///< reached t_end
  MaxSteps,           ///< the step budget ran out
  StepSizeUnderflow,  ///< the step fell below min_step (or the fixed step cannot satisfy events)
  NonFiniteState,     ///< the right-hand side or the state became NaN/Inf
  ZenoGuard,          ///< more events per unit time than allowed (chattering / Zeno)
  StoppedByObserver,  ///< an observer returned false
  StoppedBySystem     ///< the system's transition asked to stop (reason in the message)
};

/// Human-readable name of a status.
inline const char* to_string(Status s) noexcept {
  switch (s) {
    case Status::Success: return "success";
    case Status::MaxSteps: return "max_steps";
    case Status::StepSizeUnderflow: return "step_size_underflow";
    case Status::NonFiniteState: return "non_finite_state";
    case Status::ZenoGuard: return "zeno_guard";
    case Status::StoppedByObserver: return "stopped_by_observer";
    case Status::StoppedBySystem: return "stopped_by_system";
  }
  return "unknown";
}

/// Counters of one run.
struct StepperStats {
  /// Accepted steps (those of fixed-step methods included).
  long accepted_steps = 0;
  /// Rejected step attempts (error too large, or a non-finite stage).
  long rejected_steps = 0;
  /// Right-hand-side evaluations made by the stepper (stages, event location, finite-difference
  /// Jacobians).
  long rhs_evaluations = 0;
  /// Guard-vector evaluations.
  long guard_evaluations = 0;
  /// Jacobians formed (Rosenbrock23: the system's jacobian() or finite differences).
  long jacobian_evaluations = 0;
  long factorisations = 0;  ///< LU factorisations of the iteration matrix (Rosenbrock23)
  /// Located events: one per call of the system's transition(), however many guards fired
  /// and whatever it did (FrictionDampedSystem::events() logs one entry per damper switched).
  long events = 0;
  /// Steps cut back to an interior guard sample (StepperOptions::guard_samples) at which a guard
  /// had crossed.
  long guard_sample_cuts = 0;
  /// Of rhs_evaluations, those spent on the state at events (HybridStepper: the steps re-taken to
  /// a located event time, bisection sub-steps). The root search on the dense output costs guard
  /// evaluations only.
  long event_state_rhs_evaluations = 0;
  /// Of rhs_evaluations, those spent restarting after events (HybridStepper: the new mode's
  /// right-hand side at the event time).
  long restart_rhs_evaluations = 0;
};

/// One located event as reported to observers.
template <class Scalar, class Mode>
struct EventRecord {
  Scalar t;                             ///< located event time
  Mode from;                            ///< mode before the transition
  Mode to;                              ///< mode after the transition
  const TriggeredGuards* triggered;     ///< guards that fired together (valid during the call)
};

namespace detail {
/// Whether observer O has on_event(const Rec&, const X& x_after) (else on_event(const Rec&)).
template <class O, class Rec, class X, class = void>
struct has_on_event_with_state : std::false_type {};
template <class O, class Rec, class X>
struct has_on_event_with_state<
    O, Rec, X,
    std::void_t<decltype(std::declval<O&>().on_event(std::declval<const Rec&>(),
                                                     std::declval<const X&>()))>>
    : std::true_type {};

/// observer.on_event(record, x_after) when the observer has it, else on_event(record).
template <class Observer, class Scalar, class Mode, class State>
void notify_event(Observer& obs, const EventRecord<Scalar, Mode>& record, const State& x_after) {
  if constexpr (has_on_event_with_state<Observer, EventRecord<Scalar, Mode>, State>::value) {
    obs.on_event(record, x_after);
  } else {
    obs.on_event(record);
  }
}
}  // namespace detail

/// Whether a run's sequence of switches is converged in the tolerance (simulate() with
/// RunOptions::check_event_sequence): the run is repeated at a tighter tolerance and the two
/// sequences of transitions (from-mode, to-mode), in order, compared.
template <class Scalar>
struct EventSequenceCheck {
  bool checked = false;  ///< the check ran
  bool agree = true;     ///< same number of transitions, each with the same from and to modes
  /// Time of the first transition that differs (the earlier of the two runs' times at that
  /// index; a transition only one run has counts), NaN when they agree.
  Scalar first_difference = std::numeric_limits<Scalar>::quiet_NaN();
  long events = 0;        ///< transitions of the run
  long events_tight = 0;  ///< transitions of the tighter run
  Scalar rtol_tight = 0;  ///< the tighter run's rtol (RK4: its fixed_step)
};

/// Result of HybridStepper::integrate.
template <class Scalar, class State, class Mode>
struct HybridResult {
  /// How the run ended.
  Status status = Status::Success;
  Scalar t{};            ///< time reached (the failure time when status != Success)
  State x;               ///< state at t
  Mode mode{};           ///< mode at t
  std::string message;   ///< empty on success; otherwise what happened and where
  /// Counters of the run.
  StepperStats stats;
  /// simulate(): the integrator that ran ("dopri5", ...); empty from a stepper called directly.
  std::string method;
  /// simulate(): why that integrator ran (Integrator::Auto's rule, or "options.integrator");
  /// empty from a stepper called directly.
  std::string method_reason;
  /// simulate() with RunOptions::check_event_sequence: the switch sequence against a tighter run.
  EventSequenceCheck<Scalar> sequence_check{};
  /// status == Status::Success.
  bool ok() const noexcept { return status == Status::Success; }
};

/// Observer that records nothing; inherit from it and override what you need.
/// `on_step` after each accepted step, `on_event` after each transition, `on_sample` at each
/// output time (fixed output rate through the dense output). Returning false stops the run.
struct NullObserver {
  template <class Scalar, class State, class Mode>
  /// After each accepted step: continue.
  bool on_step(Scalar, const State&, const Mode&) { return true; }
  template <class Scalar, class Mode>
  /// After each transition: nothing.
  void on_event(const EventRecord<Scalar, Mode>&) {}
  template <class Scalar, class State, class Mode>
  /// At each output time: continue.
  bool on_sample(Scalar, const State&, const Mode&) { return true; }
};

namespace detail {
template <class S, class = void>
struct is_hybrid_system : std::false_type {};
template <class S>
struct is_hybrid_system<
    S, std::void_t<typename S::Scalar, typename S::State, typename S::Mode,
                   decltype(std::declval<S&>().rhs(std::declval<const typename S::Mode&>(),
                                                   std::declval<typename S::Scalar>(),
                                                   std::declval<const typename S::State&>(),
                                                   std::declval<typename S::State&>())),
                   decltype(std::declval<const S&>().num_guards(
                       std::declval<const typename S::Mode&>())),
                   decltype(std::declval<S&>().guards(
                       std::declval<const typename S::Mode&>(), std::declval<typename S::Scalar>(),
                       std::declval<const typename S::State&>(),
                       std::declval<Eigen::Matrix<typename S::Scalar, Eigen::Dynamic, 1>&>())),
                   decltype(std::declval<const S&>().guard_direction(
                       std::declval<const typename S::Mode&>(), Eigen::Index{})),
                   decltype(std::declval<S&>().transition(
                       std::declval<typename S::Mode&>(), std::declval<const TriggeredGuards&>(),
                       std::declval<typename S::Scalar>(), std::declval<typename S::State&>()))>>
    : std::true_type {};
}  // namespace detail

/// True when S models the hybrid system concept above.
template <class S>
inline constexpr bool is_hybrid_system_v = detail::is_hybrid_system<S>::value;

}  // namespace stickslip

#pragma once
/// \file stepper_options.hpp
/// \brief Run-time options of HybridStepper: step control, event location, Zeno guard, output.

#include <stickslip/detail/validate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace stickslip {

/// How a guard crossing inside an accepted step is located in time.
enum class EventLocation : std::uint8_t {
  DenseRootFinding,  ///< Illinois (modified regula falsi) on the method's dense output
  Bisection          ///< halve the step, re-integrating sub-steps from the step start (the paper)
};

/// Which state an event hands to the transition, once its time is located on the dense output.
enum class EventState : std::uint8_t {
  DenseOutput,  ///< the dense output at the located time (no further right-hand-side evaluation)
  Reintegrate,  ///< one step of the method from the step start to the event, its root refined on it
  /// Adaptive methods of HybridStepper: one step of the method from the step start to the located
  /// time estimates the dense output's error there (their difference); within the tolerances
  /// (error norm <= 1) the dense output is handed, otherwise the root is refined as Reintegrate.
  /// Elsewhere (RK4, ExactLinearStepper) as Reintegrate.
  Checked
};

/// Human-readable name of an event-state choice.
inline const char* to_string(EventState e) noexcept {
  switch (e) {
    case EventState::DenseOutput: return "dense_output";
    case EventState::Reintegrate: return "reintegrate";
    case EventState::Checked: return "checked";
  }
  return "unknown";
}

/// Human-readable name of an event location strategy.
inline const char* to_string(EventLocation e) noexcept {
  return e == EventLocation::Bisection ? "bisection" : "dense_root_finding";
}

/// Options of HybridStepper. Times in the system's time unit (seconds in stickslip's models).
///
/// Step control (adaptive methods): a step is accepted when the RMS of
/// err_i / (atol + rtol * max(|x_i(t)|, |x_i(t+h)|)) is <= 1.
/// The step fails with Status::StepSizeUnderflow when it would have to go below
/// `min_step * max(1, |t|)` (relative to |t| for large t, absolute below |t| = 1).
///
/// Time resolution: HybridStepper::integrate rejects (std::invalid_argument) an RK4 `fixed_step`
/// below `min_step * max(1, |t|)` over [t0, t_end] (t + h would not advance t, or only by a few
/// ulps), an `output_interval` that does not separate sample times at max(|t0|, |t_end|), and more
/// than `max_samples` samples in [t0, t_end].
///
/// Zeno guard: the run ends with Status::ZenoGuard when more than `zeno_max_events` events fall
/// inside any window of length `zeno_window`, or when more than `zeno_max_immediate_events`
/// consecutive events are *immediate* events (a guard that started the mode at zero left it
/// straight into its triggering direction; see docs/ode.md).
template <class Scalar>
struct StepperOptions {
  Scalar fixed_step = Scalar(1e-4);    ///< RK4 step (and the largest step RK4 takes)
  Scalar initial_step = 0;             ///< first trial step of adaptive methods; 0 = automatic
  Scalar rtol = Scalar(1e-6);          ///< relative tolerance of adaptive methods
  Scalar atol = Scalar(1e-9);          ///< absolute tolerance of adaptive methods
  Scalar safety = Scalar(0.9);         ///< step-size safety factor in (0, 1]
  Scalar min_step = Scalar(1e-14);     ///< smallest step, relative to max(1, |t|)
  Scalar max_step = std::numeric_limits<Scalar>::infinity();  ///< largest step (adaptive)
  long max_steps = 100'000'000;        ///< budget of step attempts (accepted + rejected)
  /// How a guard crossing is located in time (default: root finding on the dense output).
  EventLocation event_location = EventLocation::DenseRootFinding;
  EventState event_state = EventState::Checked;  ///< state at a root-found event (not bisection); see docs/ode.md
  Scalar event_time_tolerance = Scalar(1e-12);  ///< width of the final bracket of an event time
  Scalar guard_zero_tolerance = Scalar(1e-12);  ///< |g| below this at a mode start counts as zero
  /// Guard values checked on the dense output at this many equally spaced interior points of
  /// every accepted step besides its end (0: the step-end sign test only). A guard that crosses
  /// and crosses back inside one step is then seen when a sample falls inside the excursion; the
  /// step is cut back to that sample and the event located in it. HybridStepper only (the
  /// exponential stepper brackets its guards in closed form). See docs/ode.md.
  long guard_samples = 0;
  long zeno_max_events = 1000;         ///< more events than this inside zeno_window -> ZenoGuard
  Scalar zeno_window = Scalar(1e-6);   ///< length of the sliding window of the event-rate cap
  long zeno_max_immediate_events = 100;  ///< consecutive immediate events allowed
  Scalar output_interval = 0;          ///< > 0: on_sample at t0, t0 + dt, ... via dense output
  long max_samples = 100'000'000;      ///< largest number of samples a run may ask for

  /// The smallest step a run takes at time t: min_step * max(1, |t|) (below it t + h does not
  /// resolve h, or only to a few ulps).
  Scalar smallest_step(Scalar t) const {
    using std::abs;
    return min_step * std::max(Scalar(1), abs(t));
  }

  /// Throws std::invalid_argument("<where>: <option> ...") for an option out of range.
  void validate(const std::string& where) const {
    using detail::require_non_negative;
    using detail::require_positive;
    require_positive(where, "options.fixed_step", fixed_step);
    require_non_negative(where, "options.initial_step", initial_step);
    require_non_negative(where, "options.rtol", rtol);
    require_non_negative(where, "options.atol", atol);
    if (!(rtol > 0 || atol > 0))
      detail::throw_invalid(where, "options.rtol and options.atol must not both be 0", rtol);
    if (!(safety > 0 && safety <= 1))
      detail::throw_invalid(where, "options.safety must be in (0, 1]", safety);
    require_positive(where, "options.min_step", min_step);
    if (!(max_step > 0)) detail::throw_invalid(where, "options.max_step must be > 0", max_step);
    if (max_steps <= 0) detail::throw_invalid(where, "options.max_steps must be > 0", max_steps);
    require_positive(where, "options.event_time_tolerance", event_time_tolerance);
    require_non_negative(where, "options.guard_zero_tolerance", guard_zero_tolerance);
    constexpr long guard_samples_limit = 1000;
    if (guard_samples < 0 || guard_samples > guard_samples_limit)
      detail::throw_invalid(where, "options.guard_samples must be in [0, " + std::to_string(guard_samples_limit) + "]",
                            guard_samples);
    // The event-rate cap keeps the times of the last zeno_max_events events (one Scalar each):
    // 1e6 of them are 8 MB, while 1e9 would allocate 8 GB before the first step.
    constexpr long zeno_events_limit = 1'000'000;
    if (zeno_max_events <= 0 || zeno_max_events > zeno_events_limit)
      detail::throw_invalid(where, "options.zeno_max_events must be in [1, " +
                                       std::to_string(zeno_events_limit) + "] (limit of the event-time ring buffer)",
                            zeno_max_events);
    require_non_negative(where, "options.zeno_window", zeno_window);
    if (zeno_max_immediate_events <= 0)
      detail::throw_invalid(where, "options.zeno_max_immediate_events must be > 0",
                            zeno_max_immediate_events);
    require_non_negative(where, "options.output_interval", output_interval);
    if (max_samples <= 0) detail::throw_invalid(where, "options.max_samples must be > 0", max_samples);
  }
};

}  // namespace stickslip

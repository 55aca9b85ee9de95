#pragma once
/// \file stall_diagnosis.hpp
/// \brief Why Newton's method on the period map G(x0) = x(t0 + T; x0) - x0 stalled: the
/// mechanisms of a hybrid orbit that make G nonsmooth, detected from the runs of the iteration,
/// and the option that addresses each. Used by the failure messages of Shooting and Continuation.

#include <stickslip/detail/validate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace stickslip {

/// A mechanism that makes the period map nonsmooth where Newton stalled.
enum class StallMechanism : std::uint8_t {
  None,                    ///< nothing detected (a quasi-periodic or chaotic response, a far guess)
  EventAtPeriodStart,      ///< an event lies within a small fraction of a period of t0
  Grazing,                 ///< an event pair appears or vanishes between iterates, or tangent flow
  PeriodMapDiscontinuity   ///< the residual jumps: no fraction of the Newton step lowers it
};

/// Human-readable name of a stall mechanism.
inline const char* to_string(StallMechanism m) noexcept {
  switch (m) {
    case StallMechanism::None: return "none";
    case StallMechanism::EventAtPeriodStart: return "event_at_period_start";
    case StallMechanism::Grazing: return "grazing";
    case StallMechanism::PeriodMapDiscontinuity: return "period_map_discontinuity";
  }
  return "unknown";
}

/// What the runs of one Newton iteration (Shooting, or one corrector of Continuation) showed,
/// gathered run by run with note_run() and note_residual().
///
/// - Event at the period start: an event of the last run at a phase within
///   `start_window` (2 % of T) of t0 or t0 + T. Where an event crosses t0 between iterates, the
///   start mode is right for one iterate and wrong for the next: G kinks there.
/// - Grazing: the number of events per period changed between two runs (an event pair, e.g. a
///   stick phase, appears or vanishes: its guard touches zero without crossing at the boundary),
///   or the variational run met an event with a flow tangent to its switching surface (no
///   saltation). G is continuous but not differentiable there.
/// - Discontinuity of the period map: a residual that rises between iterations, or that no
///   fraction of the Newton step (down to 1/32) lowers: G jumps near the iterate.
template <class Scalar>
struct StallEvidence {
  /// Events of a run within this fraction of a period of t0 (or t0 + T) count as "at the start".
  static constexpr double start_window = 0.02;
  /// The nearest event of the last run to t0 (mod T), in periods (infinity: no event).
  Scalar nearest_event = std::numeric_limits<Scalar>::infinity();
  Scalar nearest_event_time = 0;  ///< its time
  int events_last = -1;           ///< the number of events of the last run (-1: no run yet)
  int events_changed_from = -1;   ///< event counts of two runs that differed (-1: never)
  int events_changed_to = -1;     ///< ... and the later count
  long grazing_events = 0;        ///< tangent events of the variational runs
  Scalar jump_from = 0;           ///< the residual before the largest jump
  Scalar jump_to = 0;             ///< ... and after it (jump_to > jump_from: a jump was seen)

  /// A run from t0 over T with `events` (anything with .t) and `grazing` tangent events.
  template <class Events>
  void note_run(Scalar t0, Scalar T, const Events& events, long grazing) {
    using std::fmod;
    nearest_event = std::numeric_limits<Scalar>::infinity();
    for (const auto& e : events) {
      Scalar f = fmod((e.t - t0) / T, Scalar(1));
      if (f < 0) f += 1;
      const Scalar d = std::min(f, Scalar(1) - f);
      if (d < nearest_event) {
        nearest_event = d;
        nearest_event_time = e.t;
      }
    }
    const int count = static_cast<int>(events.size());
    if (events_last >= 0 && count != events_last) {
      events_changed_from = events_last;
      events_changed_to = count;
    }
    events_last = count;
    grazing_events += grazing;
  }
  /// The residual went from `before` to `after` (after >= before: a jump).
  void note_residual(Scalar before, Scalar after) {
    if (after >= before && after - before >= jump_to - jump_from) {
      jump_from = before;
      jump_to = after;
    }
  }
  /// The mechanism detected, the most specific first.
  StallMechanism mechanism() const {
    if (nearest_event <= Scalar(start_window)) return StallMechanism::EventAtPeriodStart;
    // A residual that more than doubles: a jump (an event appearing at a finite distance, e.g.
    // a stick phase of finite length where static friction exceeds kinetic friction).
    if (jump_to > 2 * jump_from) return StallMechanism::PeriodMapDiscontinuity;
    if (events_changed_from >= 0 || grazing_events > 0) return StallMechanism::Grazing;
    if (jump_to > jump_from) return StallMechanism::PeriodMapDiscontinuity;
    return StallMechanism::None;
  }
  /// The mechanism in words with what it means and the option that addresses it. `continuation`:
  /// the corrector of Continuation (its options are named), with its section_margin.
  std::string describe(bool continuation, Scalar section_margin = 0) const {
    using detail::format_value;
    switch (mechanism()) {
      case StallMechanism::EventAtPeriodStart:
        return "an event at the period start: an event at t = " + format_value(nearest_event_time) +
               " lies " + format_value(nearest_event) +
               " periods from the section t0; the start mode flips between iterates and the period "
               "map kinks there. " +
               (continuation ? std::string("Set ContinuationOptions::section_margin above ") +
                                   format_value(nearest_event) + " (now " + format_value(section_margin) +
                                   ") to move the section away from the events"
                             : std::string("Start the orbit from another t0, away from the events (run "
                                           "the guess on by part of a period); Continuation does so "
                                           "along a branch with ContinuationOptions::section_margin"));
      case StallMechanism::Grazing:
        return std::string("a grazing: ") +
               (events_changed_from >= 0
                    ? "the events per period changed from " + std::to_string(events_changed_from) +
                          " to " + std::to_string(events_changed_to) + " between iterates"
                    : std::to_string(grazing_events) + " event(s) met their switching surface tangentially") +
               " (a guard touching zero without crossing: a stick phase or contact appearing or "
               "vanishing), where the period map is not differentiable. " +
               (continuation
                    ? "Set ContinuationOptions::max_corrector_distance (e.g. 2) so that a point "
                      "landing on the other side is refused and the step halves, and a small "
                      "min_step to approach the grazing"
                    : "Use ShootingOptions::monodromy = FiniteDifference (a secant Jacobian across "
                      "the kink), or a guess closer to the orbit (a longer transient)");
      case StallMechanism::PeriodMapDiscontinuity:
        return "a discontinuity of the period map: the residual jumped from " + format_value(jump_from) +
               " to " + format_value(jump_to) +
               " along the Newton step (no fraction of the step lowers it). " +
               (continuation
                    ? std::string("Set ContinuationOptions::max_corrector_distance (e.g. 2) and a "
                                  "smaller max_step so that the corrector stays on one side of the jump")
                    : std::string("Use a guess closer to the orbit (a longer transient), or "
                                  "ShootingOptions::monodromy = FiniteDifference"));
      case StallMechanism::None: break;
    }
    return "no event at the period start, grazing or jump of the residual seen: the response may be "
           "quasi-periodic or chaotic, or the guess too far from a periodic orbit";
  }
};

}  // namespace stickslip

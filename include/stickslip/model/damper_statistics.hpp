#pragma once
/// \file damper_statistics.hpp
/// \brief Per-damper statistics over a time window of a run (stick fraction, switches, regime),
/// accumulated by an observer without storing the history.

#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/friction_damped_system.hpp"
#include "stickslip/ode/hybrid_system.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// What a damper did over a window.
enum class DamperRegime : std::uint8_t {
  Stick,       ///< stuck at least 99.9 % of the time
  StickSlip,   ///< in between
  GrossSlip,   ///< stuck less than 5 % of the time (at most brief stops at velocity reversals)
  NotReached,  ///< the run did not reach the window (no statistics)
  /// Separated from the member (free flight, Separation::Separate) at least 1 % of the time
  IntermittentContact
};

/// "stick", "stick-slip", "gross slip", "not reached".
inline const char* to_string(DamperRegime r) noexcept {
  switch (r) {
    case DamperRegime::Stick: return "stick";
    case DamperRegime::StickSlip: return "stick-slip";
    case DamperRegime::GrossSlip: return "gross slip";
    case DamperRegime::NotReached: return "not reached";
    case DamperRegime::IntermittentContact: return "intermittent contact";
  }
  return "unknown";
}

/// classify_regime: a damper stuck at least this fraction of the window sticks.
inline constexpr double regime_stick_from = 0.999;
/// classify_regime: a damper stuck less than this fraction of the window is in gross slip.
inline constexpr double regime_gross_slip_below = 0.05;

/// The one regime rule (that of examples/blade_damper and docs/blade_damper.md, which use these
/// thresholds): stick fraction >= regime_stick_from (0.999) is Stick, < regime_gross_slip_below
/// (0.05) GrossSlip, anything between StickSlip; NaN (no time observed in the window) NotReached.
template <class Scalar>
DamperRegime classify_regime(Scalar stick_fraction) noexcept {
  using std::isnan;
  if (isnan(stick_fraction)) return DamperRegime::NotReached;
  if (stick_fraction >= Scalar(regime_stick_from)) return DamperRegime::Stick;
  if (stick_fraction < Scalar(regime_gross_slip_below)) return DamperRegime::GrossSlip;
  return DamperRegime::StickSlip;
}

/// classify_regime: a damper separated from its member (in flight) at least this fraction of the
/// window is in intermittent contact, whatever its stick fraction.
inline constexpr double regime_intermittent_from = 0.01;

/// The rule with separation: separated_fraction >= regime_intermittent_from (0.01) is
/// IntermittentContact; otherwise classify_regime(stick_fraction). NaN stick fraction (nothing
/// observed) NotReached.
template <class Scalar>
DamperRegime classify_regime(Scalar stick_fraction, Scalar separated_fraction) noexcept {
  using std::isnan;
  if (isnan(stick_fraction)) return DamperRegime::NotReached;
  if (separated_fraction >= Scalar(regime_intermittent_from)) return DamperRegime::IntermittentContact;
  return classify_regime(stick_fraction);
}

/// The window [t_start, t_end] of DamperStatistics and the excitation period the switches are
/// counted per [s].
template <class Scalar>
struct StatisticsWindow {
  Scalar t_start{};  ///< start of the window [s]
  Scalar t_end{};    ///< end of the window [s] (> t_start)
  Scalar period{};   ///< excitation period the switches are counted per [s] (> 0)
};

/// One damper's statistics over the observed part of the window.
template <class Scalar>
struct DamperWindowStatistics {
  Scalar observed_time{};         ///< time of the window the run covered [s]
  Scalar stick_time{};            ///< time stuck within it [s]
  Scalar stick_fraction{};        ///< stick_time / observed_time (NaN when nothing was observed)
  Eigen::Index switches = 0;      ///< contact-state changes (stick <-> slip, slip reversals) in the window
  Scalar switches_per_period{};   ///< switches * period / observed_time (NaN when nothing observed)
  Scalar separated_time{};        ///< time separated from the member (in flight) within the window [s]
  Scalar separated_fraction{};    ///< separated_time / observed_time (NaN when nothing was observed)
  Eigen::Index bounces = 0;       ///< impacts in the window after which the damper flew again
  Eigen::Index landings = 0;      ///< impacts in the window after which it stayed in contact
  Eigen::Index wall_impacts = 0;  ///< impacts on a member-end wall (MemberEnd::Wall) in the window
  /// times in the window the damper came to rest at a wall (its mode gained a wall mark,
  /// DamperStates::wall: a stick there, or held there in flight)
  Eigen::Index wall_rests = 0;
  Scalar wall_time{};             ///< time resting at a wall (a wall mark) within the window [s]
  /// classify_regime(stick_fraction, separated_fraction)
  DamperRegime regime = DamperRegime::NotReached;
};

/// Observer (docs/ode.md) accumulating, per damper of a FrictionDampedSystem, the time stuck and
/// the number of switches over a window, for simulate(): memory O(dampers), nothing stored per
/// step, nothing allocated after construction.
///
/// A damper with a stick state (Coulomb, Stribeck) is stuck while its contact state is Stick:
/// the mode is constant over every step (events end steps), so its stick time is exact; its
/// switches are the events whose record changes its state. A damper with a regularised law
/// (no stick state, its state stays slip+ forever) counts as stuck while |V| < v_eps (its law's
/// v_eps()), V from system.evaluate(mode, t, x).V at every step end (one evaluation per step,
/// usually the cached one of the stepper's last stage); between two step ends V is taken
/// linear, which places each crossing of |V| = v_eps to O(h^2) and catches a reversal inside a
/// step; each crossing is a switch.
///
/// Construct it with the run's start (mode, t0, x0); the window may start before t0 or end after
/// the run (only the covered part counts: observed_time). To combine it with an observer of
/// your own, call its on_step / on_event from yours.
/// \throws std::invalid_argument (constructor) when window.t_end <= window.t_start, or
///         window.period is not > 0 and finite
template <class System>
class DamperStatistics {
 public:
  using Scalar = typename System::Scalar;  ///< the system's scalar
  using State = typename System::State;    ///< the system's state vector
  using Mode = typename System::Mode;      ///< DamperStates
  using Index = Eigen::Index;              ///< damper index
  using Statistics = DamperWindowStatistics<Scalar>;  ///< one damper's result

  /// Observes a run of `system` that starts from (mode0, t0, x0), accumulating over `window`.
  DamperStatistics(System& system, const Mode& mode0, Scalar t0, const State& x0,
                   StatisticsWindow<Scalar> window)
      : system_(system), window_(window), prev_t_(t0) {
    static const char* where = "DamperStatistics";
    detail::require_finite(where, "window.t_start", window.t_start);
    detail::require_finite(where, "window.t_end", window.t_end);
    if (!(window.t_end > window.t_start))
      detail::throw_invalid(where, "window.t_end must be > window.t_start", window.t_end);
    detail::require_positive(where, "window.period", window.period);
    detail::require_finite(where, "window.period", window.period);
    const std::size_t D = system.dampers().size();
    v_eps_.resize(D);
    stick_time_.assign(D, Scalar(0));
    separated_time_.assign(D, Scalar(0));
    bounces_.assign(D, 0);
    landings_.assign(D, 0);
    wall_impacts_.assign(D, 0);
    wall_rests_.assign(D, 0);
    wall_time_.assign(D, Scalar(0));
    impacts_seen_ = system.impacts().size();
    switches_.assign(D, 0);
    prev_V_.assign(D, Scalar(0));
    for (std::size_t i = 0; i < D; ++i) {
      v_eps_[i] = detail::with_law(system.dampers()[i].law, [](const auto& l) -> Scalar {
        if constexpr (std::decay_t<decltype(l)>::has_stick_state)
          return std::numeric_limits<Scalar>::quiet_NaN();
        else
          return l.v_eps();
      });
      regularised_ = regularised_ || !std::isnan(v_eps_[i]);
    }
    if (regularised_) read_velocities(mode0, t0, x0);
  }

  /// After each accepted step over [previous step end, t], in `mode` (the mode of the whole step).
  bool on_step(Scalar t, const State& x, const Mode& mode) {
    using std::max;
    using std::min;
    const Scalar a = max(prev_t_, window_.t_start), b = min(t, window_.t_end);
    if (b > a) observed_ += b - a;
    const typename System::Evaluation* e = regularised_ ? &system_.evaluate(mode, t, x) : nullptr;
    for (std::size_t i = 0; i < v_eps_.size(); ++i) {
      if (b > a && mode.wall(static_cast<Index>(i)) != WallRest::None) wall_time_[i] += b - a;
      if (mode[static_cast<Index>(i)] == ContactState::Separated) {  // in flight: neither stuck nor sliding on it
        if (b > a) separated_time_[i] += b - a;
        if (e) prev_V_[i] = e->V[static_cast<Index>(i)];
        continue;
      }
      if (std::isnan(v_eps_[i])) {
        if (b > a && mode[static_cast<Index>(i)] == ContactState::Stick) stick_time_[i] += b - a;
        continue;
      }
      const Scalar V = e->V[static_cast<Index>(i)];
      regularised_step(i, prev_t_, prev_V_[i], t, V, a, b);
      prev_V_[i] = V;
    }
    prev_t_ = t;
    return true;
  }

  /// After each transition: a damper whose state changed switched (when t is in the window);
  /// the impacts the system logged in it (FrictionDampedSystem::impacts) are wall impacts,
  /// bounces or landings; a damper whose mode gained a wall mark came to rest at a wall.
  void on_event(const EventRecord<Scalar, Mode>& record, const State& x_after) {
    const bool inside = record.t >= window_.t_start && record.t <= window_.t_end;
    const auto& impacts = system_.impacts();
    if (impacts.size() < impacts_seen_) impacts_seen_ = 0;  // the log was cleared
    for (; impacts_seen_ < impacts.size(); ++impacts_seen_) {
      const auto& hit = impacts[impacts_seen_];
      if (!(hit.t >= window_.t_start && hit.t <= window_.t_end)) continue;
      auto& count = hit.wall ? wall_impacts_ : (hit.to == ContactState::Separated ? bounces_ : landings_);
      ++count[static_cast<std::size_t>(hit.damper)];
    }
    for (std::size_t i = 0; i < v_eps_.size(); ++i) {
      const Index ii = static_cast<Index>(i);
      if (std::isnan(v_eps_[i]) && inside && record.from[ii] != record.to[ii]) ++switches_[i];
      if (inside && record.from.wall(ii) == WallRest::None && record.to.wall(ii) != WallRest::None)
        ++wall_rests_[i];
    }
    if (regularised_) read_velocities(record.to, record.t, x_after);  // a reset may change V
  }

  /// Samples are not needed (the statistics come from steps and events); always continues.
  bool on_sample(Scalar, const State&, const Mode&) { return true; }

  /// Number of dampers observed.
  Index num_dampers() const noexcept { return static_cast<Index>(v_eps_.size()); }

  /// Damper i's statistics over the part of the window observed so far.
  Statistics statistics(Index i) const {
    if (i < 0 || i >= num_dampers()) detail::throw_invalid("DamperStatistics::statistics", "damper index", i);
    const std::size_t iu = static_cast<std::size_t>(i);
    Statistics s;
    const Scalar none = std::numeric_limits<Scalar>::quiet_NaN();
    s.observed_time = observed_;
    s.stick_time = stick_time_[iu];
    s.switches = switches_[iu];
    s.stick_fraction = observed_ > 0 ? stick_time_[iu] / observed_ : none;
    s.switches_per_period = observed_ > 0 ? Scalar(switches_[iu]) * window_.period / observed_ : none;
    s.separated_time = separated_time_[iu];
    s.separated_fraction = observed_ > 0 ? separated_time_[iu] / observed_ : none;
    s.bounces = bounces_[iu];
    s.landings = landings_[iu];
    s.wall_impacts = wall_impacts_[iu];
    s.wall_rests = wall_rests_[iu];
    s.wall_time = wall_time_[iu];
    s.regime = classify_regime(s.stick_fraction, s.separated_fraction);
    return s;
  }

 private:
  void read_velocities(const Mode& mode, Scalar t, const State& x) {
    const auto& e = system_.evaluate(mode, t, x);
    for (std::size_t i = 0; i < v_eps_.size(); ++i) prev_V_[i] = e.V[static_cast<Index>(i)];
  }

  /// Regularised damper i over the step [t0, t1] with V linear from V0 to V1: the part of the
  /// step where |V| < v_eps (an interval, V being monotone) within [a, b] is stick time, and its
  /// ends inside the step and the window are switches.
  void regularised_step(std::size_t i, Scalar t0, Scalar V0, Scalar t1, Scalar V1, Scalar a, Scalar b) {
    using std::abs;
    using std::max;
    using std::min;
    const Scalar eps = v_eps_[i], h = t1 - t0;
    if (!(h > 0)) return;
    Scalar s_lo = 0, s_hi = 1;  // fractions of the step with |V| < eps
    if (V1 == V0) {
      if (!(abs(V0) < eps)) return;
    } else {
      s_lo = (-eps - V0) / (V1 - V0);
      s_hi = (eps - V0) / (V1 - V0);
      if (s_lo > s_hi) std::swap(s_lo, s_hi);
      s_lo = max(s_lo, Scalar(0));
      s_hi = min(s_hi, Scalar(1));
      if (!(s_hi > s_lo)) return;
    }
    const Scalar enter = t0 + s_lo * h, leave = t0 + s_hi * h;
    const Scalar in = max(enter, a), out = min(leave, b);
    if (out > in) stick_time_[i] += out - in;
    const auto in_window = [&](Scalar tc) { return tc >= window_.t_start && tc <= window_.t_end; };
    if (s_lo > 0 && in_window(enter)) ++switches_[i];
    if (s_hi < 1 && in_window(leave)) ++switches_[i];
  }

  System& system_;
  StatisticsWindow<Scalar> window_;
  Scalar prev_t_;
  Scalar observed_ = 0;
  bool regularised_ = false;
  std::vector<Scalar> v_eps_;  // NaN for a damper with a stick state
  std::vector<Scalar> stick_time_, prev_V_, separated_time_, wall_time_;
  std::vector<Index> switches_, bounces_, landings_, wall_impacts_, wall_rests_;
  std::size_t impacts_seen_ = 0;  // entries of system.impacts() already counted
};

}  // namespace stickslip

#pragma once
/// \file poincare.hpp
/// \brief Poincaré sections of a forced response: the state at t0 + nT after a transient, and the
/// smallest k for which the sections repeat (a period-k response), or none (quasi-periodic or
/// chaotic). The brute-force view of a steady state where shooting a period-1 orbit fails.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/dormand_prince54.hpp>
#include <stickslip/ode/hybrid_stepper.hpp>
#include <stickslip/steady_state/interrupt.hpp>
#include <stickslip/steady_state/shooting_options.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace stickslip {

/// Options of poincare_sections.
template <class Scalar>
struct PoincareOptions {
  int transient_periods = 100;  ///< whole forcing periods integrated before the first section
  int record_periods = 32;      ///< sections recorded after the transient (>= 2 max_period)
  int max_period = 8;           ///< largest k looked for
  /// The recurrence tolerance: the relative recurrence r_k = max_n |x_P(n) - x_P(n - k)| /
  /// max_n |x_P(n)| (infinity norms over the components `periodic`) is compared with
  /// tol = max(tolerance, 100 (stepper.rtol + stepper.atol / max_n |x_P(n)|)): the sections are
  /// runs' end states, whose global error (the step sequence of each period's run changes with
  /// its start) lies within ~100 times the local tolerance, below which no recurrence is resolved.
  Scalar tolerance = Scalar(1e-5);
  /// The margin of the verdict: r_k <= tol / undecided_factor is periodic, r_k > tol
  /// undecided_factor is not, between them the verdict is Undecided (default 10: one order of
  /// magnitude each way: the uncertainty of the runs' global error against their tolerance, and
  /// what the rest of a transient decaying by |mu| = 0.9 per period changes over the 22 periods
  /// that a record of 32 sections spans after k = 8, 0.9^22 = 0.1).
  Scalar undecided_factor = Scalar(10);
  /// Components compared (e.g. the mechanical states; quadratures grow); empty: all.
  std::vector<Eigen::Index> periodic;
  /// Options of the runs (HybridStepper with DormandPrince54).
  StepperOptions<Scalar> stepper{};
  /// Asked after every step of the runs (empty: never); true stops them: status
  /// IntegrationFailed, the message starting "interrupted" (see InterruptCheck).
  InterruptCheck interrupt;

  /// Throws std::invalid_argument("<where>: options.<name> ...") for an option out of range,
  /// for state size n.
  void validate(const std::string& where, Eigen::Index n) const {
    stepper.validate(where);
    if (transient_periods < 0)
      detail::throw_invalid(where, "options.transient_periods must be >= 0", transient_periods);
    if (max_period < 1) detail::throw_invalid(where, "options.max_period must be >= 1", max_period);
    if (static_cast<long long>(record_periods) < 2LL * max_period)  // (2 max_period may overflow int)
      detail::throw_invalid(where, "options.record_periods must be >= 2 options.max_period",
                            record_periods);
    detail::require_positive(where, "options.tolerance", tolerance);
    if (!(undecided_factor >= 1) || !detail::is_finite(undecided_factor))
      detail::throw_invalid(where, "options.undecided_factor must be finite and >= 1", undecided_factor);
    detail::require_indices(where, "options.periodic", periodic, n);
  }
};

/// How poincare_sections ended.
enum class PoincareStatus : std::uint8_t {
  Periodic,          ///< the sections repeat with period k = period (k = 1: a period-1 response)
  NotPeriodic,       ///< no k <= max_period: quasi-periodic, chaotic, or still transient
  IntegrationFailed, ///< a run failed (message says where)
  /// The smallest recurrence within the margin lies within a factor undecided_factor of the
  /// tolerance: neither verdict is safe (a response still settling, or one near a bifurcation);
  /// `period` is the candidate k (e.g. shoot k T from the last section and let Newton decide).
  Undecided
};

/// Human-readable name of a Poincaré status.
inline const char* to_string(PoincareStatus s) noexcept {
  switch (s) {
    case PoincareStatus::Periodic: return "periodic";
    case PoincareStatus::NotPeriodic: return "not_periodic";
    case PoincareStatus::IntegrationFailed: return "integration_failed";
    case PoincareStatus::Undecided: return "undecided";
  }
  return "unknown";
}

/// The record of poincare_sections.
template <class System>
struct PoincareSections {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  PoincareStatus status = PoincareStatus::NotPeriodic;  ///< how it ended
  std::string message;                 ///< why a run failed (empty otherwise)
  int period = 0;                      ///< k when Periodic, the candidate k when Undecided, else 0
  /// The tolerance tol used (PoincareOptions::tolerance, raised to the integration's floor).
  Scalar tolerance = 0;
  /// Per k = 1 .. max_period: max_n |x_P(n) - x_P(n - k)| / max_n |x_P(n)| over the record.
  std::vector<Scalar> recurrence;
  Scalar t0 = 0;                       ///< time of the first section (t0 of the call + transient)
  Scalar period_time = 0;              ///< the forcing period T
  std::vector<typename System::State> states;  ///< the sections x(t0 + nT), n = 0 .. record - 1
  std::vector<typename System::Mode> modes;    ///< the mode at each section
  /// status == Periodic.
  bool periodic() const noexcept { return status == PoincareStatus::Periodic; }
};

/// Poincaré sections of the response of `system` from (mode, t0, x0) under forcing of period T:
/// integrates options.transient_periods periods, then records the state at the next
/// options.record_periods multiples of T, and with the relative recurrences
///
///     r_k = max_n |x_P(n) - x_P(n - k)|_inf / max_n |x_P(n)|_inf   (n over the record),
///
/// tol (PoincareOptions::tolerance, at least the integration's floor) and the margin m =
/// options.undecided_factor, the smallest k <= max_period with r_k <= m tol decides: r_k <=
/// tol / m is a period-k response (Periodic; a subharmonic of order k for k > 1), else Undecided
/// with candidate k; no such k: NotPeriodic. `observer` sees the recorded periods only (steps, events, samples), e.g. to take
/// the amplitude per period. A period-k section state is a good guess for Shooting::forced with
/// period k T. Throws std::invalid_argument for T <= 0, empty or non-finite input or bad options.
template <class System, class Observer = NullObserver>
PoincareSections<System> poincare_sections(System& system, const typename System::Mode& mode,
                                           typename System::Scalar t0,
                                           const typename System::State& x0,
                                           typename System::Scalar T,
                                           const PoincareOptions<typename System::Scalar>& options,
                                           Observer&& observer = Observer{}) {
  using Scalar = typename System::Scalar;
  static const std::string where = "poincare_sections";
  detail::require_finite(where, "t0", t0);
  detail::require_positive(where, "T", T);
  if (x0.size() == 0) throw std::invalid_argument(where + ": x0 must not be empty");
  if (!detail::all_finite(x0)) throw std::invalid_argument(where + ": x0 must be finite");
  options.validate(where, x0.size());
  detail::require_resolved_period(
      where, "T", t0, T, options.stepper,
      Scalar(options.transient_periods + options.record_periods + 1) * T);
  std::vector<Eigen::Index> P = options.periodic;
  if (P.empty()) P = ShootingOptions<Scalar>::first(x0.size());

  PoincareSections<System> out;
  out.period_time = T;
  HybridStepper<System, DormandPrince54> stepper(system, options.stepper);
  typename System::Mode m = mode;
  typename System::State x = x0;
  Scalar t = t0;
  // Period by period (a section at each whole period, as a sampled run would only approach it).
  auto run = [&](auto& inner) {
    detail::InterruptibleObserver<std::remove_reference_t<decltype(inner)>> obs{inner, options.interrupt};
    const auto r = stepper.integrate(m, t, x, t + T, obs);
    if (!r.ok()) {
      out.status = PoincareStatus::IntegrationFailed;
      out.message = obs.interrupted ? detail::interrupted_message(r.t)
                                    : "the run over [" + detail::format_value(t) + ", " +
                                          detail::format_value(t + T) + "] failed: " + r.message;
      return false;
    }
    t += T;
    x = r.x;
    m = r.mode;
    return true;
  };
  NullObserver quiet;
  for (int n = 0; n < options.transient_periods; ++n)
    if (!run(quiet)) return out;
  out.t0 = t;
  out.states.reserve(static_cast<std::size_t>(options.record_periods));
  for (int n = 0; n < options.record_periods; ++n) {
    out.states.push_back(x);
    out.modes.push_back(m);
    if (n + 1 < options.record_periods && !run(observer)) return out;
  }
  // Infinity norms over the compared components (Eigen's indexed view x(P)).
  Scalar scale = 0;
  for (const auto& s : out.states) scale = std::max(scale, s(P).cwiseAbs().maxCoeff());
  if (!(scale > 0)) scale = Scalar(1);  // the rest state: every k repeats it
  const auto N = out.states.size();
  using std::max;
  const Scalar tol = max(options.tolerance,
                         Scalar(100) * (options.stepper.rtol + options.stepper.atol / scale));
  const Scalar margin = options.undecided_factor;
  out.tolerance = tol;
  out.status = PoincareStatus::NotPeriodic;
  for (int k = 1; k <= options.max_period; ++k) {
    const auto K = static_cast<std::size_t>(k);
    Scalar worst = 0;
    for (std::size_t n = K; n < N; ++n)
      worst = std::max(worst, (out.states[n](P) - out.states[n - K](P)).cwiseAbs().maxCoeff());
    const Scalar r = worst / scale;
    out.recurrence.push_back(r);
    if (out.period == 0 && r <= margin * tol) {
      out.period = k;
      out.status = r <= tol / margin ? PoincareStatus::Periodic : PoincareStatus::Undecided;
    }
  }
  return out;
}

}  // namespace stickslip

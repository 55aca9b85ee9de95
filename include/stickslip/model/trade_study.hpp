#pragma once
/// \file trade_study.hpp
/// \brief trade_study(): the speed/accuracy trade of model and integrator variants on the
/// caller's own scene, each variant measured against a validated tight reference.

#include "stickslip/detail/cpu_time.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace stickslip {

/// What a variant runs: its system, the initial mode and the initial state at TradeStudyOptions::t0.
template <class System>
struct TradeSetup {
  System system;                ///< the variant's system
  typename System::Mode mode;   ///< initial discrete mode
  typename System::State x0;    ///< initial state
};

/// One variant of a trade study: a name, a factory building its scene (so that model choices -
/// modes, friction law, normal load, contact - are variants like integrator choices are) and the
/// run options. The factory is called once per repeat, outside the timed part.
template <class System>
struct TradeVariant {
  std::string name;                           ///< row name
  std::function<TradeSetup<System>()> setup;  ///< builds the scene of one run
  RunOptions<typename System::Scalar> run{};  ///< integrator and stepper options
};

/// Options of trade_study().
template <class System>
struct TradeStudyOptions {
  using Scalar = typename System::Scalar;  ///< the system's scalar
  Scalar t0 = 0;                ///< start time of every run
  Scalar t_end = 1;             ///< end time of every run
  /// Common sample grid t0, t0 + dt, ... of the compared output; overrides each variant's
  /// RunOptions::stepper.output_interval.
  Scalar output_interval = Scalar(1e-3);
  int repeats = 3;              ///< runs per variant; the reported CPU time is their median
  /// The compared output y(system, t, x) at each sample (e.g. a tip displacement). Required.
  std::function<Scalar(const System&, Scalar, const typename System::State&)> output;
  /// Optional energy residual of a finished run (e.g. an energy audit's closing error), called
  /// with the system of the last repeat and its result; empty: reported as NaN.
  std::function<Scalar(System&, const SimulationResult<System>&)> energy_residual;
  /// The reference is validated by a rerun with rtol and atol divided by this factor (adaptive
  /// and exponential integrators) or with the fixed step divided by it (RungeKutta4).
  Scalar validation_factor = 100;
};

/// One row of a trade study: cost and error of a run against the reference.
/// Errors are NaN when the run did not reach t_end (status != Success or it did not start).
template <class Scalar>
struct TradeRow {
  std::string name;                 ///< the variant's name
  bool started = false;             ///< false: building or starting the run threw (see message)
  Status status = Status::Success;  ///< how the run ended (meaningful when started)
  std::string message;              ///< the run's message, or the exception's what()
  Scalar t_reached = std::numeric_limits<Scalar>::quiet_NaN();  ///< time the run reached
  double cpu_seconds = 0;           ///< median over the repeats of the run's CPU time (its thread's: detail::thread_cpu_seconds)
  long rhs_evaluations = 0;         ///< right-hand-side evaluations of the last repeat
  long events = 0;                  ///< events (transitions) of the last repeat
  /// max_k |y_k - y_ref,k| / max_k |y_ref,k| over the common sample grid.
  Scalar output_error_max = std::numeric_limits<Scalar>::quiet_NaN();
  /// sqrt(mean_k (y_k - y_ref,k)^2) / max_k |y_ref,k|.
  Scalar output_error_rms = std::numeric_limits<Scalar>::quiet_NaN();
  /// Largest |t - t_ref| over the matched switches (0 when none matched).
  Scalar switch_time_error = std::numeric_limits<Scalar>::quiet_NaN();
  long missed_switches = 0;  ///< reference switches without a partner in the run
  long extra_switches = 0;   ///< switches of the run without a partner in the reference
  /// Flag: the run's sequence of switches (from, to) differs from the reference's (a missed or
  /// an extra switch), e.g. a short stick phase one of them resolved and the other did not.
  bool sequence_differs = false;
  /// Time of the first switch without a partner (of the run or of the reference), NaN when
  /// the sequences agree.
  Scalar first_sequence_difference = std::numeric_limits<Scalar>::quiet_NaN();
  /// The integrator that ran (the variant's, or Integrator::Auto's choice).
  std::string method;
  /// Why that integrator ran (Integrator::Auto's rule, or the variant's explicit choice).
  std::string method_reason;
  /// TradeStudyOptions::energy_residual of the run (NaN without one)
  Scalar energy_residual = std::numeric_limits<Scalar>::quiet_NaN();
  /// A finished run (started and status Success).
  bool ok() const noexcept { return started && status == Status::Success; }
};

/// The result of trade_study(): the reference row, its validation and one row per variant.
template <class Scalar>
struct TradeStudyResult {
  TradeRow<Scalar> reference;   ///< the reference run (errors 0 by definition)
  /// The tightened rerun of the reference compared with it: its output_error_max is the bound
  /// of the reference's own error that the variants' errors should stand well above.
  TradeRow<Scalar> validation;
  std::string validation_method;  ///< how the reference was validated, in words
  std::vector<TradeRow<Scalar>> rows;  ///< one per variant, in order (empty if the reference failed)
};

namespace detail {

/// The samples of the compared output and the switches (time, from, to) of one run.
template <class System>
struct TradeRecord {
  using Scalar = typename System::Scalar;
  using Mode = typename System::Mode;
  struct Switch {
    Scalar t;
    Mode from, to;
  };
  const System* system = nullptr;
  const std::function<Scalar(const System&, Scalar, const typename System::State&)>* output = nullptr;
  std::vector<Scalar> samples;
  std::vector<Switch> switches;

  template <class S, class X, class M>
  bool on_step(S, const X&, const M&) { return true; }
  template <class S, class M>
  void on_event(const EventRecord<S, M>& r) { switches.push_back(Switch{r.t, r.from, r.to}); }
  template <class S, class X, class M>
  bool on_sample(S t, const X& x, const M&) {
    samples.push_back((*output)(*system, t, x));
    return true;
  }
};

/// A run of `variant` repeated `options.repeats` times: row with the median CPU time, counters,
/// status and energy residual; `record` holds the last repeat's samples and switches. Exceptions
/// (invalid options, a throwing factory) become a row with started = false.
template <class System>
TradeRow<typename System::Scalar> run_trade_variant(const TradeVariant<System>& variant,
                                                     const TradeStudyOptions<System>& options,
                                                     TradeRecord<System>& record) {
  using Scalar = typename System::Scalar;
  TradeRow<Scalar> row;
  row.name = variant.name;
  RunOptions<Scalar> run = variant.run;
  run.stepper.output_interval = options.output_interval;
  const auto expected_samples =
      static_cast<std::size_t>((options.t_end - options.t0) / options.output_interval) + 2;
  std::vector<double> cpu;
  try {
    for (int rep = 0; rep < options.repeats; ++rep) {
      TradeSetup<System> setup = variant.setup();
      record.system = &setup.system;
      record.output = &options.output;
      record.samples.clear();
      record.samples.reserve(expected_samples);  // no reallocation inside the run's steps
      record.switches.clear();
      const double start = detail::thread_cpu_seconds();
      const auto result = simulate(setup.system, setup.mode, options.t0, setup.x0, options.t_end, run, record);
      cpu.push_back(detail::thread_cpu_seconds() - start);
      row.started = true;
      row.status = result.status;
      row.message = result.message;
      row.t_reached = result.t;
      row.rhs_evaluations = result.stats.rhs_evaluations;
      row.events = result.stats.events;
      row.method = result.method;
      row.method_reason = result.method_reason;
      if (options.energy_residual) row.energy_residual = options.energy_residual(setup.system, result);
      if (!result.ok()) break;  // a failed run fails again: one repeat is enough
    }
  } catch (const std::exception& e) {
    row.started = false;
    row.message = e.what();
    record.samples.clear();
    record.switches.clear();
  }
  if (!cpu.empty()) {
    std::sort(cpu.begin(), cpu.end());
    row.cpu_seconds = cpu[cpu.size() / 2];
  }
  return row;
}

/// Fills the error columns of `row` (record `run`) against the reference record `ref`.
/// Switches are matched in time order by their (from, to) pair, two cursors walking both lists:
/// equal pairs match; otherwise the earlier of the two is unmatched (missed when it is the
/// reference's, extra when it is the run's).
template <class System>
void compare_trade_records(TradeRow<typename System::Scalar>& row, const TradeRecord<System>& run,
                           const TradeRecord<System>& ref) {
  using Scalar = typename System::Scalar;
  if (!row.ok() || run.samples.size() != ref.samples.size() || ref.samples.empty()) return;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const Eigen::Index n = static_cast<Eigen::Index>(ref.samples.size());
  const Eigen::Map<const Vector> y(run.samples.data(), n), y_ref(ref.samples.data(), n);
  Scalar scale = y_ref.cwiseAbs().maxCoeff();
  if (!(scale > 0)) scale = 1;  // an identically zero output: absolute errors
  row.output_error_max = (y - y_ref).cwiseAbs().maxCoeff() / scale;
  row.output_error_rms = (y - y_ref).norm() / std::sqrt(static_cast<Scalar>(n)) / scale;

  row.switch_time_error = 0;
  row.missed_switches = row.extra_switches = 0;
  row.sequence_differs = false;
  row.first_sequence_difference = std::numeric_limits<Scalar>::quiet_NaN();
  auto unmatched = [&row](Scalar t) {
    if (!row.sequence_differs) row.first_sequence_difference = t;
    row.sequence_differs = true;
  };
  std::size_t i = 0, j = 0;
  const auto& a = ref.switches;
  const auto& b = run.switches;
  while (i < a.size() && j < b.size()) {
    if (a[i].from == b[j].from && a[i].to == b[j].to) {
      row.switch_time_error = std::max(row.switch_time_error, Scalar(std::abs(a[i].t - b[j].t)));
      ++i, ++j;
    } else if (a[i].t <= b[j].t) {
      unmatched(a[i].t);
      ++row.missed_switches, ++i;
    } else {
      unmatched(b[j].t);
      ++row.extra_switches, ++j;
    }
  }
  if (i < a.size()) unmatched(a[i].t);
  if (j < b.size()) unmatched(b[j].t);
  row.missed_switches += static_cast<long>(a.size() - i);
  row.extra_switches += static_cast<long>(b.size() - j);
}

/// The reference's options tightened by `factor` (see TradeStudyOptions::validation_factor) and
/// the method in words.
template <class Scalar>
std::pair<RunOptions<Scalar>, std::string> tightened(RunOptions<Scalar> run, Scalar factor) {
  std::string how;
  if (run.integrator == Integrator::RungeKutta4) {
    run.stepper.fixed_step /= factor;
    how = "rerun with the fixed step divided by " + format_value(factor);
  } else {
    run.stepper.rtol /= factor;
    run.stepper.atol /= factor;
    how = "rerun with rtol and atol divided by " + format_value(factor);
  }
  return {run, how};
}

}  // namespace detail

/// Measures each variant against `reference` on the caller's scene: runs the reference, validates
/// it by a tightened rerun (TradeStudyOptions::validation_factor; the difference is
/// TradeStudyResult::validation, the reference's own error bound), then each variant
/// `options.repeats` times. Row k: median CPU time, RHS evaluations, events, status,
/// max and RMS error of options.output on the common grid relative to max |y_ref|, switch-time
/// error and missed/extra switches (matched by (from, to) mode pair in time order; a variant
/// with any is flagged TradeRow::sequence_differs, with the time of the first), energy
/// residual, and the method that ran. A variant that fails or throws becomes a row with its status or message; when the
/// reference itself fails, `rows` is empty and `reference` says why. Writes nothing.
/// Throws std::invalid_argument naming options.t_end, options.output_interval, options.repeats,
/// options.output or options.validation_factor when out of range.
template <class System>
TradeStudyResult<typename System::Scalar> trade_study(const TradeVariant<System>& reference,
                                                      const std::vector<TradeVariant<System>>& variants,
                                                      const TradeStudyOptions<System>& options) {
  using Scalar = typename System::Scalar;
  const std::string where = "trade_study";
  detail::require_finite(where, "options.t0", options.t0);
  if (!(options.t_end > options.t0 && detail::is_finite(options.t_end)))
    detail::throw_invalid(where, "options.t_end must be finite and > options.t0", options.t_end);
  detail::require_positive(where, "options.output_interval", options.output_interval);
  if (options.repeats < 1) detail::throw_invalid(where, "options.repeats must be >= 1", options.repeats);
  if (!options.output) detail::throw_invalid(where, "options.output must be set", "empty");
  if (!(options.validation_factor > 1 && detail::is_finite(options.validation_factor)))
    detail::throw_invalid(where, "options.validation_factor must be finite and > 1",
                          options.validation_factor);

  TradeStudyResult<Scalar> result;
  detail::TradeRecord<System> ref_record, record;
  result.reference = detail::run_trade_variant(reference, options, ref_record);
  detail::compare_trade_records(result.reference, ref_record, ref_record);
  if (!result.reference.ok()) return result;

  TradeVariant<System> tight = reference;
  std::tie(tight.run, result.validation_method) = detail::tightened(reference.run, options.validation_factor);
  tight.name = reference.name + " (validation)";
  TradeStudyOptions<System> once = options;
  once.repeats = 1;
  result.validation = detail::run_trade_variant(tight, once, record);
  detail::compare_trade_records(result.validation, record, ref_record);

  for (const auto& variant : variants) {
    result.rows.push_back(detail::run_trade_variant(variant, options, record));
    detail::compare_trade_records(result.rows.back(), record, ref_record);
  }
  return result;
}

/// Writes `rows` as CSV with a header line (name, status, message, t_reached, cpu_seconds,
/// rhs_evaluations, events, output_error_max, output_error_rms, switch_time_error,
/// missed_switches, extra_switches, energy_residual). status is "not_started" for a variant that
/// threw. The caller chooses the stream (and so the file).
template <class Scalar>
void write_trade_csv(std::ostream& os, const std::vector<TradeRow<Scalar>>& rows) {
  auto quoted = [](const std::string& s) {
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  os << "name,status,message,t_reached,cpu_seconds,rhs_evaluations,events,output_error_max,"
        "output_error_rms,switch_time_error,missed_switches,extra_switches,energy_residual\n";
  const auto precision = os.precision(10);
  for (const auto& r : rows) {
    os << quoted(r.name) << ',' << (r.started ? to_string(r.status) : "not_started") << ','
       << quoted(r.message) << ',' << r.t_reached << ',' << r.cpu_seconds << ',' << r.rhs_evaluations
       << ',' << r.events << ',' << r.output_error_max << ',' << r.output_error_rms << ','
       << r.switch_time_error << ',' << r.missed_switches << ',' << r.extra_switches << ','
       << r.energy_residual << '\n';
  }
  os.precision(precision);
}

}  // namespace stickslip

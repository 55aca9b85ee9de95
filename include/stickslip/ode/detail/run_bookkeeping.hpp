#pragma once
/// \file run_bookkeeping.hpp
/// \brief Pieces of a hybrid run that do not depend on the method: argument checks, the Zeno
/// guard (consecutive immediate events, event-rate cap), the event notification of observers and
/// the Result of a finished run. Shared by HybridStepper and ExactLinearStepper.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/hybrid_system.hpp>
#include <stickslip/ode/stepper_options.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {
namespace detail {

/// Throws std::invalid_argument("<where>: ...") for non-finite t0/t_end, t_end < t0, an empty or
/// non-finite x0.
template <class Scalar, class State>
void check_run_arguments(const std::string& where, Scalar t0, const State& x0, Scalar t_end) {
  require_finite(where, "t0", t0);
  require_finite(where, "t_end", t_end);
  if (!(t_end >= t0)) throw_invalid(where, "t_end must be >= t0", t_end);
  if (x0.size() == 0) throw_invalid(where, "x0 must not be empty", x0.size());
  if (!x0.allFinite()) throw_invalid(where, "x0 must be finite", x0.transpose());
}

/// Throws std::invalid_argument("<where>: options.output_interval ...") when samples are asked
/// for (output_interval > 0) and the sample times t0 + k dt cannot advance at the magnitude of t
/// (dt <= 4 eps max(|t0|, |t_end|)), or when they would be more than options.max_samples. Shared
/// by every stepper that emits samples, so that no run loops on samples that never advance or
/// fills memory with more than the caller allowed.
template <class Scalar>
void check_sample_times(const std::string& where, Scalar t0, Scalar t_end,
                        const StepperOptions<Scalar>& opt) {
  const Scalar dt = opt.output_interval;
  if (!(dt > 0)) return;
  using std::abs;
  const Scalar t_max = std::max(abs(t0), abs(t_end));
  const Scalar resolution = Scalar(4) * std::numeric_limits<Scalar>::epsilon() * t_max;
  if (!(dt > resolution))
    throw_invalid(where,
                  "options.output_interval must exceed the time resolution 4 eps |t| = " +
                      format_value(resolution) + " at |t| = " + format_value(t_max) +
                      ", or the sample times t0 + k dt do not advance",
                  dt);
  using std::floor;
  const Scalar samples = floor((t_end - t0) / dt) + Scalar(1);
  if (!(samples <= static_cast<Scalar>(opt.max_samples)))
    throw_invalid(where,
                  "options.output_interval asks for " + format_value(samples) +
                      " samples over [t0, t_end] = [" + format_value(t0) + ", " +
                      format_value(t_end) + "], more than options.max_samples = " +
                      std::to_string(opt.max_samples),
                  dt);
}

/// Fill r with the outcome of a run and return it.
template <class Result, class Scalar, class State, class Mode>
Result finish_run(Result& r, Status s, Scalar t, const State& x, const Mode& m,
                  std::string message) {
  r.status = s;
  r.t = t;
  r.x = x;
  r.mode = m;
  r.message = std::move(message);
  return std::move(r);
}

/// The Zeno guard of StepperOptions: more than zeno_max_immediate_events consecutive immediate
/// events, or more than zeno_max_events events inside a window of zeno_window.
template <class Scalar>
class ZenoGuard {
 public:
  /// Start a run (allocates the ring of event times once).
  void reset(const StepperOptions<Scalar>& opt) {
    opt_ = &opt;
    ring_.assign(opt.zeno_window > 0 ? static_cast<std::size_t>(opt.zeno_max_events) + 1 : 0,
                 Scalar(0));
    pos_ = 0;
    immediate_run_ = 0;
  }
  /// Record the events-th event at t; false (with the reason in message) when the guard trips.
  bool record(Scalar t, bool immediate, long events, std::string& message) {
    immediate_run_ = immediate ? immediate_run_ + 1 : 0;
    if (immediate_run_ > opt_->zeno_max_immediate_events) {
      message = "Zeno guard: " + std::to_string(immediate_run_) +
                " consecutive immediate events (a guard leaving zero straight into its "
                "triggering direction) " +
                at_time(t);
      return false;
    }
    if (ring_.empty()) return true;
    ring_[pos_] = t;
    pos_ = (pos_ + 1) % ring_.size();
    if (events > opt_->zeno_max_events && t - ring_[pos_] <= opt_->zeno_window) {
      message = "Zeno guard: more than " + std::to_string(opt_->zeno_max_events) +
                " events within " + short_number(opt_->zeno_window) + " " + at_time(t);
      return false;
    }
    return true;
  }

 private:
  const StepperOptions<Scalar>* opt_ = nullptr;
  std::vector<Scalar> ring_;
  std::size_t pos_ = 0;
  long immediate_run_ = 0;
};

}  // namespace detail
}  // namespace stickslip

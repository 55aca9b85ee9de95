#pragma once
/// \file hybrid_stepper.hpp
/// \brief HybridStepper: integrates a hybrid system (see hybrid_system.hpp) with one of the
/// methods RungeKutta4, DormandPrince54, Rosenbrock23, locating guard crossings (events) by
/// bisection or by root finding on the dense output, and applying the system's transitions.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/detail/run_bookkeeping.hpp>
#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/dormand_prince54.hpp>
#include <stickslip/ode/event_locator.hpp>
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

/// Integrator of a hybrid system with event location.
///
/// `System` models the hybrid system concept (`is_hybrid_system_v`); `Method` is one of the tags
/// RungeKutta4, DormandPrince54 (default), Rosenbrock23. Usage:
///
///     HybridStepper<Ball, DormandPrince54> stepper(ball, options);
///     auto result = stepper.integrate(mode, t0, x0, t_end, observer);
///
/// The run never throws for numerical outcomes: the Result carries the Status, the time, a
/// message and the statistics. Throws std::invalid_argument for invalid options (constructor) or
/// arguments (integrate: non-finite t0/t_end, t_end < t0, empty or non-finite x0).
/// With a fixed-size State, a step and an event perform no heap allocation: workspace is sized at
/// the start of integrate, and guard vectors once per distinct guard count of the modes visited.
template <class System, class Method = DormandPrince54>
class HybridStepper {
  static_assert(is_hybrid_system_v<System>,
                "HybridStepper: System needs Scalar, State, Mode, rhs(mode, t, x, dxdt), "
                "num_guards(mode), guards(mode, t, x, g), guard_direction(mode, i) and "
                "transition(mode, triggered, t, x); see docs/ode.md");

 public:
  /// Floating-point type of the system.
  using Scalar = typename System::Scalar;
  /// Continuous state type of the system.
  using State = typename System::State;
  /// Discrete mode type of the system.
  using Mode = typename System::Mode;
  /// Result of a run (status, final state, counters).
  using Result = HybridResult<Scalar, State, Mode>;
  /// Run-time options.
  using Options = StepperOptions<Scalar>;
  /// Guard values of a mode.
  using GuardVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// The method's stage workspace and step for this system.
  using Core = typename Method::template Core<System>;

  /// Keeps a reference to `system` (it must outlive the stepper). Throws std::invalid_argument
  /// ("HybridStepper: options.<name> ...") for options out of range.
  explicit HybridStepper(System& system, StepperOptions<Scalar> options = {})
      : sys_(system), opt_(options) {
    opt_.validate("HybridStepper");
  }

  /// Integrate from (mode, t0, x0) to t_end >= t0, calling observer.on_step after each accepted
  /// step, observer.on_event after each transition (or on_event(record, x_after) when the
  /// observer has it), observer.on_sample at the output times. See docs/ode.md.
  template <class Observer>
  Result integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end, Observer& observer);

  /// Integrate without observer.
  Result integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end) {
    NullObserver none;
    return integrate(std::move(mode), t0, x0, t_end, none);
  }

  /// The options in use.
  const StepperOptions<Scalar>& options() const { return opt_; }

 private:
  static constexpr bool adaptive_ = Method::adaptive;

  bool finite(const State& v) const { return detail::all_finite(v); }

  bool eval_rhs(const Mode& m, Scalar t, const State& x, State& f, StepperStats& st) {
    sys_.rhs(m, t, x, f);
    ++st.rhs_evaluations;
    return detail::all_finite(f);
  }

  void eval_guards(const Mode& m, Scalar t, const State& x, GuardVector& g, StepperStats& st) {
    if (g.size() == 0) return;
    sys_.guards(m, t, x, g);
    ++st.guard_evaluations;
  }

  // f and guards at the start of a mode (run start or after a transition); false when f or g is
  // not finite.
  bool start_mode(const Mode& m, Scalar t, StepperStats& st) {
    detail::start_new_mode(core_);
    if (!eval_rhs(m, t, x_, f_, st)) return false;
    use_guard_count(sys_.num_guards(m));
    guarded_ = ga_.size() > 0;
    eval_guards(m, t, x_, ga_, st);
    if (!detail::all_finite(ga_)) return false;
    monitor_.start_mode(ga_, [&](Eigen::Index i) { return sys_.guard_direction(m, i); },
                        opt_.guard_zero_tolerance);
    return true;
  }

  // Make ga_, gb_, gt_ vectors of ng guards. The vectors of each guard count seen are kept:
  // those of the current count are parked in their slot and those of ng taken out (swapping Eigen
  // vectors exchanges buffers), so a mode change allocates only the first time its count appears.
  void use_guard_count(Eigen::Index ng) {
    const Eigen::Index current = ga_.size();
    if (current == ng) return;
    const auto slots = static_cast<std::size_t>(std::max(current, ng)) + 1;
    if (guard_sets_.size() < slots) guard_sets_.resize(slots);
    for (Eigen::Index count : {current, ng}) {
      GuardSet& slot = guard_sets_[static_cast<std::size_t>(count)];
      ga_.swap(slot.a);
      gb_.swap(slot.b);
      gt_.swap(slot.t);
    }
    if (ga_.size() != ng) {  // first visit of this count
      ga_.resize(ng);
      gb_.resize(ng);
      gt_.resize(ng);
    }
    if (roots_.size() < ng) roots_.resize(ng);
  }

  // Throws std::invalid_argument when the run cannot advance its clock or its samples.
  void check_time_resolution(Scalar t0, Scalar t_end) const;

  Scalar initial_step(const Mode& m, Scalar t, Scalar hmax, StepperStats& st);

  // Locate the earliest crossing in the accepted trial step [t, t1]; on return xe_ holds the
  // state at the event time (returned) and triggered_ the guards. When event_on_step_ is true the
  // core's dense output of [t, t1] (x1_, f1_) covers [t, t_event]; otherwise the core's dense
  // output is that of the step [t, t_event], ending at step_end() with f = fe_ there.
  // EventState::Checked on an adaptive method: the re-taken step to the dense output's root
  // estimates the dense output's error there; within the tolerances the dense state is handed
  // (xe_; the re-taken step's end in xr_), otherwise the root is refined on re-taken steps.
  Scalar locate_event(const Mode& m, Scalar t, Scalar h, Scalar t1, StepperStats& st);

  // After locate_event placed an event at te: when a guard that fired was disarmed but lies more
  // than the zero tolerance on its safe side at a point tc of the dense output inside (t, te), it
  // left zero and came back within the step, a new crossing rather than an immediate one. The
  // step is then cut back to tc (re-taken with the method, x1_, f1_, gb_ at tc), so that it ends
  // where the guard is armed, and true is returned.
  bool cut_back_to_rearm(const Mode& m, Scalar t, Scalar& h, Scalar& t1, Scalar te,
                         StepperStats& st);

  // The end of the step whose dense output covers [t, t_event] when event_on_step_ is false.
  const State& step_end() const { return dense_handed_ ? xr_ : xe_; }

  template <class Observer>
  bool emit_samples(Observer& obs, const Mode& m, Scalar a, Scalar h, Scalar upto,
                    const State& xa, const State& fa, const State& xb, const State& fb);

  static Result finish(Result& r, Status s, Scalar t, const State& x, const Mode& m,
                       std::string message) {
    return detail::finish_run(r, s, t, x, m, std::move(message));
  }

  System& sys_;
  Options opt_;
  Core core_;
  detail::GuardMonitor<Scalar> monitor_;
  State x_, f_, x1_, f1_, xe_, fe_, xs_, xr_;
  GuardVector ga_, gb_, gt_, roots_;
  struct GuardSet {
    GuardVector a, b, t;
  };
  std::vector<GuardSet> guard_sets_;  // parked guard vectors, indexed by guard count
  TriggeredGuards triggered_;
  bool event_on_step_ = false;
  bool dense_handed_ = false;  // Checked: xe_ is the dense output, xr_ the re-taken step's end
  detail::ZenoGuard<Scalar> zeno_;
  Scalar t0_ = 0;
  long next_sample_ = 0;
  bool guarded_ = false;  // the current mode has guards (a mode without skips all guard work)
};

template <class System, class Method>
void HybridStepper<System, Method>::check_time_resolution(Scalar t0, Scalar t_end) const {
  static const std::string where = "HybridStepper::integrate";
  const Scalar t_max = std::max(std::abs(t0), std::abs(t_end));
  if (!adaptive_) {
    // RK4 takes no step below min_step * max(1, |t|), the bound an adaptive method fails at.
    const Scalar hmin = opt_.smallest_step(t_max);
    if (!(opt_.fixed_step >= hmin))
      detail::throw_invalid(where,
                            "options.fixed_step must be >= options.min_step * max(1, |t|) = " +
                                detail::format_value(hmin) + " for t in [" +
                                detail::format_value(t0) + ", " + detail::format_value(t_end) +
                                "], or t + h does not resolve the step",
                            opt_.fixed_step);
  }
  detail::check_sample_times(where, t0, t_end, opt_);
}

template <class System, class Method>
auto HybridStepper<System, Method>::initial_step(const Mode& m, Scalar t, Scalar hmax,
                                                 StepperStats& st) -> Scalar {
  // Hairer, Norsett & Wanner, Solving ODEs I, Sec. II.4 "Starting step size".
  using std::pow;
  if (opt_.initial_step > 0) return std::min(opt_.initial_step, hmax);
  // Over the components under error control only (detail::error_norm): a system that leaves some
  // out of it (VariationalSystem without control of the sensitivities) starts with the step of a
  // run of the controlled ones alone, and then takes that run's steps.
  Eigen::Index nc = x_.size();
  if constexpr (detail::has_controlled_size<System>::value)
    nc = std::min<Eigen::Index>(nc, sys_.controlled_size());
  const auto scale = opt_.atol + opt_.rtol * x_.head(nc).array().abs();
  const Scalar n = static_cast<Scalar>(nc);
  // An exactly zero component counts 0 even where its scale is 0 (atol = 0): no 0/0.
  auto rms = [&](const auto& v) {
    return std::sqrt(
        (v.head(nc).array() == Scalar(0)).select(Scalar(0), v.head(nc).array() / scale).square().sum() / n);
  };
  const Scalar d0 = rms(x_);
  const Scalar d1 = rms(f_);
  Scalar h0 = (d0 < Scalar(1e-5) || d1 < Scalar(1e-5)) ? Scalar(1e-6) : Scalar(0.01) * d0 / d1;
  // rtol and atol so small that the scale underflows to 0: d0 = d1 = inf, h0 = NaN, and a NaN
  // step is never below min_step (the run spun until max_steps); start at 1e-6 instead.
  if (!(h0 > 0 && std::isfinite(h0))) h0 = Scalar(1e-6);
  h0 = std::min(h0, hmax);
  x1_.noalias() = x_ + h0 * f_;
  if (!eval_rhs(m, t + h0, x1_, f1_, st)) return h0;
  const Scalar d2 = rms(f1_ - f_) / h0;
  const Scalar dm = std::max(d1, d2);
  const Scalar h1 = dm <= Scalar(1e-15)
                        ? std::max(Scalar(1e-6), h0 * Scalar(1e-3))
                        : pow(Scalar(0.01) / dm, Scalar(1) / Scalar(Method::order + 1));
  const Scalar h = std::min({Scalar(100) * h0, h1, hmax});
  // A zero-scale component with a non-zero rate (pure relative control) gives h = 0 or NaN:
  // start small and let the error control (and min_step) decide.
  return (h > 0 && std::isfinite(h)) ? h : std::min(Scalar(1e-6), hmax);
}

template <class System, class Method>
auto HybridStepper<System, Method>::locate_event(const Mode& m, Scalar t, Scalar h, Scalar t1,
                                                 StepperStats& st) -> Scalar {
  const Scalar tol = opt_.event_time_tolerance;
  const Eigen::Index ng = gb_.size();
  triggered_.clear();
  event_on_step_ = false;
  dense_handed_ = false;
  const long rhs_before = st.rhs_evaluations;
  struct CountEventRhs {  // the re-taken steps' evaluations, however locate_event returns
    StepperStats& st;
    long before;
    ~CountEventRhs() { st.event_state_rhs_evaluations += st.rhs_evaluations - before; }
  } count{st, rhs_before};
  if (opt_.event_location == EventLocation::Bisection) {
    // The paper's way: halve [lo, hi], re-integrating one step from t to the midpoint.
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    const Scalar tol_eff = std::max(tol, Scalar(4) * eps * std::max(std::abs(t), std::abs(t1)));
    Scalar lo = t, hi = t1;
    bool core_at_hi = true;  // the core's stages belong to the step [t, hi]
    xe_ = x1_;
    fe_ = f1_;
    while (hi - lo > tol_eff) {
      const Scalar mid = lo + (hi - lo) / Scalar(2);
      core_.step(sys_, m, t, x_, f_, mid - t, xs_, f1_, opt_.rtol, opt_.atol, st);
      eval_guards(m, mid, xs_, gt_, st);
      if (monitor_.any_crossed(gt_)) {
        hi = mid;
        xe_ = xs_;
        fe_ = f1_;
        gb_ = gt_;
        core_at_hi = true;
      } else {
        lo = mid;
        core_at_hi = false;
      }
    }
    if (!core_at_hi) core_.step(sys_, m, t, x_, f_, hi - t, xe_, fe_, opt_.rtol, opt_.atol, st);
    for (Eigen::Index i = 0; i < ng; ++i)
      if (monitor_.crossed(i, gb_[i])) triggered_.push_back(i);
    return hi;
  }

  // Root finding on the dense output, guard by guard; the earliest crossing wins.
  Scalar first = t1;
  Eigen::Index first_guard = -1;
  for (Eigen::Index i = 0; i < ng; ++i) {
    roots_[i] = std::numeric_limits<Scalar>::infinity();
    if (!monitor_.crossed(i, gb_[i])) continue;
    auto phi = [&](Scalar tc) {
      core_.dense((tc - t) / h, h, x_, f_, x1_, f1_, xs_);
      eval_guards(m, tc, xs_, gt_, st);
      return monitor_.distance(i, gt_[i]);
    };
    const auto br = detail::illinois_root(phi, t, monitor_.distance(i, ga_[i]), t1,
                                          monitor_.distance(i, gb_[i]), tol);
    roots_[i] = br.hi;
    if (first_guard < 0 || br.hi < first) {
      first = br.hi;
      first_guard = i;
    }
  }
  for (Eigen::Index i = 0; i < ng; ++i)
    if (roots_[i] <= first + tol) triggered_.push_back(i);
  if (first >= t1 || opt_.event_state == EventState::DenseOutput) {
    // The state on the dense output at the right end of the root's bracket: the guard that fired
    // is past zero there by at most |g'| event_time_tolerance.
    event_on_step_ = true;
    if (first >= t1) {
      xe_ = x1_;
    } else {
      core_.dense((first - t) / h, h, x_, f_, x1_, f1_, xe_);
    }
    return first;
  }
  // Re-integrate [t, first] with the method itself (full order at the event; the core's dense
  // output then covers [t, first]). The step's own guard and the dense output's differ by the
  // dense-output error, so the root on the step lies on either side of `first`: refine it on
  // re-integrated steps, so that the state handed to the transition lies on the switching surface
  // to within |g'| event_time_tolerance, not to within the dense-output error.
  // Slope of the dense output's guard at `first` (before the re-integration replaces the core's
  // stages): near the root the step's guard is the dense one plus a nearly constant offset.
  const Scalar w = std::min(first - t, std::max(Scalar(16) * tol, Scalar(1e-6) * h));
  auto dense_distance = [&](Scalar tc) {
    core_.dense((tc - t) / h, h, x_, f_, x1_, f1_, xs_);
    eval_guards(m, tc, xs_, gt_, st);
    return monitor_.distance(first_guard, gt_[first_guard]);
  };
  const Scalar slope = (dense_distance(first) - dense_distance(first - w)) / w;
  auto step_to = [&](Scalar tau) {
    core_.step(sys_, m, t, x_, f_, tau - t, xe_, fe_, opt_.rtol, opt_.atol, st);
    eval_guards(m, tau, xe_, gt_, st);
    return monitor_.distance(first_guard, gt_[first_guard]);
  };
  // Checked: the dense state at `first` (before the re-taken step replaces the core's stages),
  // then the method's own step to `first`, of the method's full order; their difference estimates
  // the dense output's error at the event.
  const bool check = adaptive_ && opt_.event_state == EventState::Checked;
  if (check) core_.dense((first - t) / h, h, x_, f_, x1_, f1_, xr_);
  const Scalar d_first = step_to(first);
  if (check && detail::error_norm(sys_, xe_ - xr_, x_, xe_, opt_.rtol, opt_.atol) <= Scalar(1)) {
    // Within the tolerances: hand the dense state (on the dense output's switching surface, past
    // zero by at most |g'| event_time_tolerance), as DenseOutput; the core keeps the re-taken
    // step [t, first], whose end moves to xr_.
    xe_.swap(xr_);
    dense_handed_ = true;
    return first;
  }
  // The last step it takes is to br.hi (re-stepping to t1 reproduces x1 exactly).
  const auto br = detail::refine_root_on_steps_from(
      step_to, first, d_first, slope, t, monitor_.distance(first_guard, ga_[first_guard]), t1,
      monitor_.distance(first_guard, gb_[first_guard]), tol);
  // Fired: every guard crossed at the handed state, and every guard whose dense-output root lies
  // within the event time tolerance of the first one (guards that cross together, such as those
  // of two mirror-image contacts, fire together although round-off leaves one of them a hair
  // short of zero at the refined time).
  triggered_.clear();
  for (Eigen::Index i = 0; i < ng; ++i)
    if (monitor_.crossed(i, gt_[i]) || roots_[i] <= first + tol) triggered_.push_back(i);
  return br.hi;
}

template <class System, class Method>
bool HybridStepper<System, Method>::cut_back_to_rearm(const Mode& m, Scalar t, Scalar& h,
                                                      Scalar& t1, Scalar te, StepperStats& st) {
  bool disarmed = false;
  for (Eigen::Index i : triggered_) disarmed = disarmed || monitor_.disarmed(i);
  if (!disarmed || !(te > t)) return false;
  // The dense output covering [t, te] (see locate_event); the excursion of a guard that leaves
  // zero and returns within [t, te] peaks inside it, sampled at its middle and quarter points.
  const Scalar span = event_on_step_ ? h : te - t;
  const State& xb = event_on_step_ ? x1_ : step_end();
  const State& fb = event_on_step_ ? f1_ : fe_;
  for (const Scalar frac : {Scalar(0.5), Scalar(0.25), Scalar(0.75)}) {
    const Scalar tc = t + frac * (te - t);
    if (!(tc > t && tc < te)) continue;
    core_.dense((tc - t) / span, span, x_, f_, xb, fb, xs_);
    eval_guards(m, tc, xs_, gt_, st);
    bool out = true;
    for (Eigen::Index i : triggered_)
      out = out && (!monitor_.disarmed(i) || monitor_.out_of_zero(i, gt_[i]));
    if (!out) continue;
    h = tc - t;
    t1 = tc;
    core_.step(sys_, m, t, x_, f_, h, x1_, f1_, opt_.rtol, opt_.atol, st);
    eval_guards(m, t1, x1_, gb_, st);
    return true;
  }
  return false;
}

template <class System, class Method>
template <class Observer>
bool HybridStepper<System, Method>::emit_samples(Observer& obs, const Mode& m, Scalar a, Scalar h,
                                                 Scalar upto, const State& xa, const State& fa,
                                                 const State& xb, const State& fb) {
  if (!(opt_.output_interval > 0)) return true;
  for (;;) {
    const Scalar ts = t0_ + static_cast<Scalar>(next_sample_) * opt_.output_interval;
    if (ts > upto) return true;
    ++next_sample_;
    if (ts < a) continue;
    const Scalar theta = h > 0 ? (ts - a) / h : Scalar(1);
    if (theta >= Scalar(1)) {
      xs_ = xb;
    } else {
      core_.dense(theta, h, xa, fa, xb, fb, xs_);
    }
    if (!obs.on_sample(ts, xs_, m)) return false;
  }
}

/// The run loop of integrate(mode, t0, x0, t_end, observer), declared in the class.
template <class System, class Method>
template <class Observer>
auto HybridStepper<System, Method>::integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end,
                                              Observer& obs) -> Result {
  static const std::string where = "HybridStepper::integrate";
  detail::check_run_arguments(where, t0, x0, t_end);
  check_time_resolution(t0, t_end);

  Result r;
  StepperStats& st = r.stats;
  x_ = x0;
  for (State* v : {&f_, &x1_, &f1_, &xe_, &fe_, &xs_, &xr_}) v->resizeLike(x0);
  core_.initialize(x0);
  triggered_.clear();
  triggered_.reserve(static_cast<std::size_t>(std::max<Eigen::Index>(sys_.num_guards(mode), 8)));
  zeno_.reset(opt_);
  t0_ = t0;
  next_sample_ = 0;

  Scalar t = t0;
  if (!start_mode(mode, t, st))
    return finish(r, Status::NonFiniteState, t, x_, mode,
                  "right-hand side or guards not finite " + detail::at_time(t));
  if (!emit_samples(obs, mode, t, Scalar(0), t, x_, f_, x_, f_))
    return finish(r, Status::StoppedByObserver, t, x_, mode,
                  "stopped by observer " + detail::at_time(t));

  const Scalar hmax = adaptive_ ? opt_.max_step : opt_.fixed_step;
  Scalar h = adaptive_ ? initial_step(mode, t, std::min(hmax, t_end - t), st) : opt_.fixed_step;
  bool after_reject = false;  // no step growth right after a rejection
  bool nan_recovery = false;  // RK4: keep the reduced step after a non-finite trial step
  long attempts = 0;
  // RK4 steps end on the grid grid_t0 + k fixed_step (restarted at each event), and the step
  // taken is the difference of two grid times: t and x advance by the same h, and t does not
  // accumulate the rounding of t + h over millions of steps.
  Scalar grid_t0 = t0;
  long grid_k = 0;
  using std::pow;

  while (t < t_end) {
    if (attempts >= opt_.max_steps)
      return finish(r, Status::MaxSteps, t, x_, mode,
                    "max_steps " + std::to_string(opt_.max_steps) + " reached " +
                        detail::at_time(t));
    const Scalar hmin = opt_.smallest_step(t);
    // An adaptive step below min_step (a small initial step at large |t|) could round t + h to t.
    h = adaptive_ ? std::min(std::max(h, hmin), hmax) : std::min(h, hmax);
    const bool on_grid = !adaptive_ && !nan_recovery;
    Scalar t1 = on_grid ? grid_t0 + static_cast<Scalar>(grid_k + 1) * opt_.fixed_step : t + h;
    if (t_end - t1 <= Scalar(0.01) * h) t1 = t_end;
    h = t1 - t;
    ++attempts;
    const Scalar err = core_.step(sys_, mode, t, x_, f_, h, x1_, f1_, opt_.rtol, opt_.atol, st);
    // An infinite error norm of a finite step is a rejection (e.g. atol = 0 on a zero component).
    bool ok = !std::isnan(err) && detail::all_finite(x1_) && detail::all_finite(f1_);
    if (ok && guarded_) {
      eval_guards(mode, t1, x1_, gb_, st);
      ok = detail::all_finite(gb_);
    }
    if (!ok) {
      // Shrink towards the first non-finite point; report it once the step is below min_step.
      ++st.rejected_steps;
      h /= Scalar(2);
      after_reject = true;
      nan_recovery = true;
      if (h < hmin)
        return finish(r, Status::NonFiniteState, t, x_, mode,
                      "right-hand side, state or guards became non-finite " +
                          detail::at_time(t) + " (a step of " +
                          detail::short_number(h * Scalar(2)) + " already fails)");
      continue;
    }
    if (adaptive_ && err > Scalar(1)) {
      ++st.rejected_steps;
      h *= std::max(Scalar(0.2),
                    opt_.safety * pow(err, Scalar(-1) / Scalar(Method::error_order + 1)));
      after_reject = true;
      if (h < hmin)
        return finish(r, Status::StepSizeUnderflow, t, x_, mode,
                      "step size " + detail::short_number(h) + " fell below min_step " +
                          detail::short_number(hmin) + " " + detail::at_time(t));
      continue;
    }
    ++st.accepted_steps;
    // The step the controller proposes after this one (used as is after an event: the step size
    // is kept across the transition, as for a step without event, rather than restarted small).
    Scalar fac = 1;
    if (adaptive_) {
      fac = err > 0 ? opt_.safety * pow(err, Scalar(-1) / Scalar(Method::error_order + 1))
                    : Scalar(5);
      fac = std::min(Scalar(5), std::max(Scalar(0.2), fac));
      if (after_reject) fac = std::min(fac, Scalar(1));
    }
    const Scalar h_next = h * fac;

    // Interior guard samples (options.guard_samples): a guard that has crossed at a sample but
    // not (or no longer) at the step end cuts the step back to that sample, re-taken with the
    // method itself, so that the event is located in it as at any step end.
    bool cut_back = false;
    if (guarded_ && opt_.guard_samples > 0 && !monitor_.any_crossed(gb_)) {
      const Scalar parts = static_cast<Scalar>(opt_.guard_samples + 1);
      for (long k = 1; k <= opt_.guard_samples; ++k) {
        const Scalar theta = static_cast<Scalar>(k) / parts;
        core_.dense(theta, h, x_, f_, x1_, f1_, xs_);
        eval_guards(mode, t + theta * h, xs_, gt_, st);
        if (!monitor_.any_crossed(gt_)) continue;
        h = theta * h;
        t1 = t + h;
        ++st.guard_sample_cuts;
        core_.step(sys_, mode, t, x_, f_, h, x1_, f1_, opt_.rtol, opt_.atol, st);
        eval_guards(mode, t1, x1_, gb_, st);
        // (a shorter step of a method that passed on the longer one: its error is smaller; a
        // non-finite one cannot come from a finite longer step's sub-interval in practice, and
        // is caught at the next step's check)
        cut_back = true;
        break;
      }
    }

    bool event = guarded_ && monitor_.any_crossed(gb_);
    Scalar te = t1;
    if (event) {
      te = locate_event(mode, t, h, t1, st);
      if (cut_back_to_rearm(mode, t, h, t1, te, st)) {
        // (the shorter step ends before the located crossing; a guard crossed at its end after
        // all, by the re-step's difference from the dense output, is located again in it)
        cut_back = true;
        event = monitor_.any_crossed(gb_);
        if (event) te = locate_event(mode, t, h, t1, st);
      }
    }
    if (event) {
      const bool sampled =
          event_on_step_ ? emit_samples(obs, mode, t, h, te, x_, f_, x1_, f1_)
                         : emit_samples(obs, mode, t, te - t, te, x_, f_, step_end(), fe_);
      if (!sampled)
        return finish(r, Status::StoppedByObserver, te, xe_, mode,
                      "stopped by observer " + detail::at_time(te));
      if (!obs.on_step(te, xe_, mode))
        return finish(r, Status::StoppedByObserver, te, xe_, mode,
                      "stopped by observer " + detail::at_time(te));
      bool immediate = false;
      for (Eigen::Index i : triggered_) immediate = immediate || monitor_.disarmed(i);
      t = te;
      x_.swap(xe_);
      const Mode from = mode;
      TransitionAction action = sys_.transition(mode, triggered_, t, x_);
      ++st.events;
      const EventRecord<Scalar, Mode> record{t, from, mode, &triggered_};
      detail::notify_event(obs, record, x_);
      if (action.stop)
        return finish(r, Status::StoppedBySystem, t, x_, mode,
                      "stopped by system " + detail::at_time(t) + ": " + action.reason);
      std::string zeno_reason;
      if (!zeno_.record(t, immediate, st.events, zeno_reason))
        return finish(r, Status::ZenoGuard, t, x_, mode, std::move(zeno_reason));
      const long rhs_before_restart = st.rhs_evaluations;
      const bool started = start_mode(mode, t, st);
      st.restart_rhs_evaluations += st.rhs_evaluations - rhs_before_restart;
      if (!started)
        return finish(r, Status::NonFiniteState, t, x_, mode,
                      "right-hand side or guards not finite after the transition " +
                          detail::at_time(t));
      if (adaptive_) {
        h = h_next;
        after_reject = false;
      } else {
        h = opt_.fixed_step;
        nan_recovery = false;
        grid_t0 = t;
        grid_k = 0;
      }
      continue;
    }

    if (!emit_samples(obs, mode, t, h, t1, x_, f_, x1_, f1_))
      return finish(r, Status::StoppedByObserver, t1, x1_, mode,
                    "stopped by observer " + detail::at_time(t1));
    t = t1;
    x_.swap(x1_);
    f_.swap(f1_);
    if (on_grid && !cut_back) {
      ++grid_k;
    } else {
      grid_t0 = t;  // off the grid after a non-finite trial step or a cut-back: a new grid from here
      grid_k = 0;
    }
    if (guarded_) {
      ga_.swap(gb_);
      monitor_.update_arming(ga_);
    }
    core_.new_point();
    if (!obs.on_step(t, x_, mode))
      return finish(r, Status::StoppedByObserver, t, x_, mode,
                    "stopped by observer " + detail::at_time(t));
    if (adaptive_) {
      h *= fac;  // (applied to a step cut back as well)
    } else if (!nan_recovery) {
      h = opt_.fixed_step;
    }
    after_reject = false;
  }
  return finish(r, Status::Success, t, x_, mode, std::string());
}

}  // namespace stickslip

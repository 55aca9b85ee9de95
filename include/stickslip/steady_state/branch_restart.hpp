#pragma once
/// \file branch_restart.hpp
/// \brief RestartingContinuation: a branch of forced periodic orbits followed over a parameter
/// range by Continuation, restarted past the places where the continuation stalls (a
/// discontinuous period map where a stick phase appears with mu_s > mu_k, a grazing): the
/// response is settled by a transient beyond the stall, its period k T is read from Poincaré
/// sections, and a new segment of period-k orbits is continued from there. The result keeps the
/// segments apart, so that a plot draws the gaps between them.

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/poincare.hpp>
#include <stickslip/steady_state/progress.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Options of the restarts of RestartingContinuation (the branch's own are ContinuationOptions).
template <class Scalar>
struct RestartOptions {
  /// The parameter distance beyond the farthest point of a stalled segment (in the direction of
  /// travel) at which the response is settled and a new segment starts; a failed attempt moves
  /// one gap further. Must be > 0 and below the width of the range. The points in a gap are not
  /// computed.
  Scalar gap = Scalar(0.01);
  int max_restarts = 4;  ///< restart attempts at most (successful or not), >= 0
  /// Forcing periods of the transient at the restart parameter, from the state of the stalled
  /// segment's last orbit, run by ShootingOptions' integrator (>= 0).
  int settle_periods = 40;
  int max_period = 4;  ///< largest multiple k of the forcing period looked for (>= 1)
  /// Poincaré sections recorded after the transient (>= 2 max_period; PoincareOptions).
  int record_periods = 12;
  /// The recurrence tolerance of the sections (PoincareOptions::tolerance, > 0).
  Scalar recurrence_tolerance = Scalar(1e-5);
  /// > 0: a segment also stalls when its last stall_points points (accepted ones, the newest
  /// corrected one included) advanced the parameter by less than stall_progress together: the
  /// corrector crawls towards a discontinuity with ever smaller steps long before the step
  /// falls below ContinuationOptions::min_step. 0 (the default): only the continuation's own
  /// failures (StepTooSmall) count as stalls.
  int stall_points = 0;
  /// The parameter advance that stall_points points must exceed (>= 0; > 0 when stall_points > 0).
  Scalar stall_progress = 0;

  /// Throws std::invalid_argument("<where>: restart.<name> ...") for an option out of range, for
  /// the range width `width` of the branch.
  void validate(const std::string& where, Scalar width) const {
    detail::require_positive(where, "restart.gap", gap);
    if (!(gap < width))
      detail::throw_invalid(where, "restart.gap must be < parameter_max - parameter_min", gap);
    if (max_restarts < 0) detail::throw_invalid(where, "restart.max_restarts must be >= 0", max_restarts);
    if (settle_periods < 0)
      detail::throw_invalid(where, "restart.settle_periods must be >= 0", settle_periods);
    if (max_period < 1) detail::throw_invalid(where, "restart.max_period must be >= 1", max_period);
    if (static_cast<long long>(record_periods) < 2LL * max_period)
      detail::throw_invalid(where, "restart.record_periods must be >= 2 restart.max_period", record_periods);
    detail::require_positive(where, "restart.recurrence_tolerance", recurrence_tolerance);
    if (stall_points < 0) detail::throw_invalid(where, "restart.stall_points must be >= 0", stall_points);
    if (stall_points == 1)
      detail::throw_invalid(where, "restart.stall_points must be 0 (off) or >= 2", stall_points);
    detail::require_non_negative(where, "restart.stall_progress", stall_progress);
    if (stall_points > 0 && !(stall_progress > 0))
      detail::throw_invalid(where, "restart.stall_progress must be > 0 when restart.stall_points > 0",
                            stall_progress);
  }
};

/// How a segment of a RestartingContinuation began.
enum class SegmentKind : std::uint8_t {
  Start,        ///< the first segment, from the caller's guess
  Restart,      ///< after a stall: period-1 orbits shot from a settled transient
  Subharmonic   ///< after a stall: the settled response repeats every k T, k > 1
};

/// Human-readable name of a segment kind.
inline const char* to_string(SegmentKind k) noexcept {
  switch (k) {
    case SegmentKind::Start: return "start";
    case SegmentKind::Restart: return "restart";
    case SegmentKind::Subharmonic: return "subharmonic";
  }
  return "unknown";
}

/// One continued segment of a RestartingContinuation.
template <class System>
struct BranchSegment {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  SegmentKind kind = SegmentKind::Start;  ///< how it began
  int period_multiple = 1;  ///< k: its orbits have period k T(p) (orbit.period says so too)
  Scalar start_parameter = 0;  ///< the parameter of its first orbit
  /// Why the segment before ended (its status and message; empty for the first segment).
  std::string after;
  /// The relative recurrence r_k of the sections that gave k (PoincareSections; 0 for Start).
  Scalar recurrence = 0;
  ContinuationResult<System> branch;  ///< its points, status and message
  /// When the branch is Completed: the parameter of the corrected point beyond the range that
  /// ended it (not kept), which tells the end it left by (a first step may leave a narrow range
  /// at once, past either end).
  Scalar exit_parameter = 0;
  double cpu_seconds = 0;  ///< CPU seconds of the segment (the settling and sections included)
};

/// A restart attempt that gave no segment: where, and why.
template <class Scalar>
struct FailedRestart {
  Scalar parameter = 0;  ///< where the response was settled
  std::string reason;    ///< no period <= max_period, a failed run, no orbit from the sections
};

/// The segments of a RestartingContinuation in order of travel.
template <class System>
struct RestartedBranch {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  std::vector<BranchSegment<System>> segments;  ///< in order; segments[0] is the Start
  std::vector<FailedRestart<Scalar>> failed;   ///< attempts without a segment
  int restarts = 0;  ///< restart attempts made (segments.size() - 1 + failed.size())
  /// How the whole ended: Completed when a segment reached the end of the range, else the status
  /// of the last segment (StepTooSmall or Stopped when the restarts ran out or the next one
  /// would lie beyond the range; StartFailed when the first segment's start failed).
  ContinuationStatus status = ContinuationStatus::Completed;
  std::string message;  ///< why it ended short of the range's end (empty when Completed)
  /// status == Completed.
  bool completed() const noexcept { return status == ContinuationStatus::Completed; }
  /// Points of all segments.
  std::size_t points() const noexcept {
    std::size_t n = 0;
    for (const auto& s : segments) n += s.branch.points.size();
    return n;
  }
};

/// Continuation over [options.parameter_min, options.parameter_max] (from the start in
/// options.direction) that restarts past stalls. A segment stalls when its continuation ends
/// StepTooSmall, crawls (RestartOptions::stall_points), or leaves the range backwards (turned at
/// a fold towards where it came from). Then, with p_far the farthest parameter reached or tried
/// in the direction of travel, the system is set to p_r = p_far + direction gap, the last orbit's
/// state (mode, t0, x0) is run for settle_periods forcing periods T(p_r) (run_period with the
/// shooting options: their integrator), Poincaré sections (poincare_sections: Dormand-Prince
/// at the shooting options' stepper tolerances, record_periods sections, the periodic
/// components) give the smallest k <= max_period with which the response repeats (Periodic or
/// Undecided: the candidate is shot and Newton decides), and a new Continuation of period-k T(p)
/// orbits starts from the last section over [p_r, parameter_max] (direction +1; [parameter_min,
/// p_r] for -1). No k, a failed run or a start that does not converge: a FailedRestart, and the
/// next attempt settles one gap further. At most max_restarts attempts; options.max_points
/// bounds the points of all segments together. A segment that ends Completed (past the end of
/// the range), MaxPoints, Interrupted or StartFailed (the first one) ends the whole.
///
/// options.progress is called per accepted point with the whole branch's progress (points of
/// all segments, the fraction of the range from the start covered by the farthest point, the
/// CPU seconds of the whole so far, ContinuationProgress). on_point() sees each point with its
/// segment's index. Throws std::invalid_argument for empty callbacks or invalid options (the
/// message names the option: `options.<name>`, `restart.<name>`).
template <class System>
class RestartingContinuation {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// The continuation of one segment.
  using Segment = Continuation<System>;
  /// The result type.
  using Result = RestartedBranch<System>;
  /// Called after each accepted point with its segment's index.
  using OnPoint = std::function<void(std::size_t, const ContinuationPoint<System>&)>;

  /// Keeps a reference to `system`. Throws std::invalid_argument for empty set_parameter or
  /// period, or invalid options.
  RestartingContinuation(System& system, typename Segment::SetParameter set_parameter,
                         typename Segment::PeriodOf period, ShootingOptions<Scalar> shooting = {},
                         ContinuationOptions<Scalar> options = {}, RestartOptions<Scalar> restart = {})
      : sys_(system), set_(std::move(set_parameter)), period_(std::move(period)),
        shooting_(std::move(shooting)), opt_(std::move(options)), restart_(restart) {
    static const std::string where = "RestartingContinuation";
    if (!set_) throw std::invalid_argument(where + ": set_parameter must not be empty");
    if (!period_) throw std::invalid_argument(where + ": period must not be empty");
    opt_.validate(where);
    restart_.validate(where, opt_.parameter_max - opt_.parameter_min);
  }

  /// The start-mode rule of every segment (Continuation::start_mode).
  void start_mode(typename Segment::StartMode rule) { start_mode_ = std::move(rule); }
  /// Call `f(segment index, point)` after each accepted point.
  void on_point(OnPoint f) { on_point_ = std::move(f); }

  /// Follow the branch from the orbit at p0 shot from (mode, t0, x0_guess), restarting past
  /// stalls. Throws std::invalid_argument for p0 outside the range (and as Continuation::run).
  Result run(const Mode& mode, Scalar t0, const State& x0_guess, Scalar p0);

 private:
  // Runs one segment of period multiple k over [lo, hi] from (mode, t0, x0, p0) into `seg`.
  void segment(BranchSegment<System>& seg, const Mode& mode, Scalar t0, const State& x0, Scalar p0,
               Scalar lo, Scalar hi, std::size_t index, Result& result);
  // A stall that a restart may carry the branch past (status and the segment's extent).
  bool stalled(const BranchSegment<System>& seg, Scalar p_start) const;

  System& sys_;
  typename Segment::SetParameter set_;
  typename Segment::PeriodOf period_;
  ShootingOptions<Scalar> shooting_;
  ContinuationOptions<Scalar> opt_;
  RestartOptions<Scalar> restart_;
  typename Segment::StartMode start_mode_;
  OnPoint on_point_;
  // The whole branch's progress: its start, farthest point, points and CPU clock.
  Scalar p_begin_ = 0, p_far_ = 0;
  double cpu0_ = 0, cpu_last_ = 0;
};

template <class System>
bool RestartingContinuation<System>::stalled(const BranchSegment<System>& seg, Scalar p_start) const {
  const auto& b = seg.branch;
  if (b.status == ContinuationStatus::StepTooSmall || b.status == ContinuationStatus::Stopped) return true;
  // Completed through the segment's own start bound: the branch turned back at a fold.
  if (b.status != ContinuationStatus::Completed || b.points.empty()) return false;
  return Scalar(opt_.direction) * (seg.exit_parameter - p_start) < 0;
}

template <class System>
void RestartingContinuation<System>::segment(BranchSegment<System>& seg, const Mode& mode, Scalar t0,
                                             const State& x0, Scalar p0, Scalar lo, Scalar hi,
                                             std::size_t index, Result& result) {
  const int k = seg.period_multiple;
  ContinuationOptions<Scalar> o = opt_;
  o.parameter_min = lo;
  o.parameter_max = hi;
  o.max_points = std::max(1, opt_.max_points - static_cast<int>(result.points()));
  const std::size_t before = result.points();
  const Scalar p_end = opt_.direction > 0 ? opt_.parameter_max : opt_.parameter_min;
  o.progress = [this, before, p_end](const ContinuationProgress& part) {
    if (!opt_.progress) return;
    ContinuationProgress pr = part;
    pr.points = static_cast<int>(before) + part.points;
    pr.max_points = opt_.max_points;
    using std::abs;
    if (abs(part.parameter - p_begin_) > abs(p_far_ - p_begin_) &&
        (part.parameter - p_begin_) * Scalar(opt_.direction) > 0)
      p_far_ = Scalar(part.parameter);
    pr.covered = p_end == p_begin_ ? 1.0
                                   : std::clamp(static_cast<double>((p_far_ - p_begin_) / (p_end - p_begin_)), 0.0, 1.0);
    const double now = detail::thread_cpu_seconds();
    pr.cpu_seconds = now - cpu0_;
    pr.seconds_per_point = now - cpu_last_;
    cpu_last_ = now;
    pr.remaining_seconds = detail::branch_remaining(pr.covered, pr.cpu_seconds, pr.points, pr.max_points);
    opt_.progress(pr);
  };
  Segment cont(sys_, set_, [this, k](Scalar p) { return Scalar(k) * period_(p); }, shooting_, o);
  if (start_mode_) cont.start_mode(start_mode_);
  std::vector<Scalar> params;  // of the accepted points (the crawl test)
  cont.on_point([&](const ContinuationPoint<System>& pt) {
    params.push_back(pt.parameter);
    if (on_point_) on_point_(index, pt);
  });
  const int n = restart_.stall_points;
  std::string crawl;
  Scalar exit = p0;  // the last corrected point: beyond the range when the branch Completed
  cont.stop_when([&](const ContinuationPoint<System>&, const ContinuationPoint<System>& next) {
    exit = next.parameter;
    if (n <= 0 || params.size() + 1 < static_cast<std::size_t>(n)) return false;
    using std::abs;
    const Scalar advance = abs(next.parameter - params[params.size() + 1 - static_cast<std::size_t>(n)]);
    if (advance >= restart_.stall_progress) return false;
    crawl = "the branch crawled: its last " + std::to_string(n) + " points advanced the parameter by " +
            detail::format_value(advance) + " < restart.stall_progress after p = " +
            detail::format_value(params.back());
    return true;
  });
  const double c0 = detail::thread_cpu_seconds();
  seg.start_parameter = p0;
  seg.branch = cont.run(mode, t0, x0, p0);
  seg.exit_parameter = exit;
  if (seg.branch.status == ContinuationStatus::Stopped) seg.branch.message = crawl;
  seg.cpu_seconds += detail::thread_cpu_seconds() - c0;
}

template <class System>
auto RestartingContinuation<System>::run(const Mode& mode, Scalar t0, const State& x0_guess, Scalar p0)
    -> Result {
  static const std::string where = "RestartingContinuation::run";
  detail::require_finite(where, "p0", p0);
  if (!(p0 >= opt_.parameter_min && p0 <= opt_.parameter_max))
    detail::throw_invalid(where, "p0 must lie in [options.parameter_min, options.parameter_max]", p0);
  Result result;
  p_begin_ = p_far_ = p0;
  cpu0_ = cpu_last_ = detail::thread_cpu_seconds();
  const Scalar dir = Scalar(opt_.direction);
  const Scalar p_end = opt_.direction > 0 ? opt_.parameter_max : opt_.parameter_min;

  result.segments.emplace_back();
  segment(result.segments.back(), mode, t0, x0_guess, p0, opt_.parameter_min, opt_.parameter_max, 0, result);
  Scalar tried = p0;  // the farthest parameter reached or tried, in the direction of travel
  auto finish = [&](const BranchSegment<System>& s) {
    result.status = s.branch.status;
    result.message = s.branch.message;
  };
  finish(result.segments.back());
  std::size_t last_ok = 0;  // the segment whose last orbit a restart settles from
  std::string after;        // why that segment ended
  while (true) {
    const BranchSegment<System>& last = result.segments[last_ok];
    if (!stalled(last, last.start_parameter) || last.branch.points.empty()) return result;
    if (result.status == ContinuationStatus::Completed) {  // turned back: not the end of the range
      result.status = ContinuationStatus::Stopped;
      result.message = "the segment from p = " + detail::format_value(last.start_parameter) +
                       " turned back at a fold and left the range behind its start";
    }
    if (after.empty()) after = std::string(to_string(last.branch.status)) + ": " + result.message;
    for (const auto& pt : last.branch.points) tried = dir * (pt.parameter - tried) > 0 ? pt.parameter : tried;
    if (static_cast<int>(result.points()) >= opt_.max_points) {
      result.status = ContinuationStatus::MaxPoints;
      result.message = "options.max_points (" + std::to_string(opt_.max_points) + ") reached over the segments";
      return result;
    }
    if (result.restarts >= restart_.max_restarts) {
      result.message += " (restart.max_restarts = " + std::to_string(restart_.max_restarts) + " attempts made)";
      return result;
    }
    const Scalar p_r = tried + dir * restart_.gap;
    if (dir * (p_r - p_end) > 0) {
      result.message += " (the next restart, at p = " + detail::format_value(p_r) + ", lies beyond the range)";
      return result;
    }
    ++result.restarts;
    tried = p_r;
    const double c0 = detail::thread_cpu_seconds();
    // Settle at p_r from the last orbit's state.
    const PeriodicOrbit<System>& orbit = last.branch.points.back().orbit;
    set_(sys_, p_r);
    const Scalar T = period_(p_r);
    detail::require_positive(where, "period(p)", T);
    Mode m = orbit.mode;
    State x = orbit.x0;
    Scalar t = orbit.t0;
    auto fail = [&](std::string reason) {
      result.failed.push_back({p_r, reason});
      result.message = "restart at p = " + detail::format_value(p_r) + ": " + reason;
    };
    auto interrupted = [&]() -> Result& {
      result.status = ContinuationStatus::Interrupted;
      return result;
    };
    if (restart_.settle_periods > 0) {
      const PeriodRun<System> settled =
          run_period(sys_, m, t, x, Scalar(restart_.settle_periods) * T, shooting_, false);
      if (!settled.ok()) {
        fail("the transient of restart.settle_periods failed: " + settled.message);
        if (settled.interrupted) return interrupted();
        continue;
      }
      t += Scalar(restart_.settle_periods) * T;
      x = settled.x_end;
      m = settled.mode_end;
    }
    PoincareOptions<Scalar> po;
    po.transient_periods = 0;
    po.record_periods = restart_.record_periods;
    po.max_period = restart_.max_period;
    po.tolerance = restart_.recurrence_tolerance;
    po.periodic = shooting_.periodic;
    po.stepper = shooting_.stepper;
    po.interrupt = shooting_.interrupt;
    const PoincareSections<System> sec = poincare_sections(sys_, m, t, x, T, po);
    if (sec.period == 0) {
      if (sec.status == PoincareStatus::IntegrationFailed) {
        fail("the Poincaré sections failed: " + sec.message);
        if (sec.message.rfind("interrupted", 0) == 0) return interrupted();
      } else {
        Scalar best = sec.recurrence.empty() ? Scalar(0) : *std::min_element(sec.recurrence.begin(), sec.recurrence.end());
        fail("no period <= restart.max_period T in the sections (smallest recurrence " + detail::format_value(best) +
             " > " + detail::format_value(sec.tolerance) + "): quasi-periodic, chaotic or still transient");
      }
      continue;
    }
    BranchSegment<System> seg;
    seg.period_multiple = sec.period;
    seg.kind = sec.period > 1 ? SegmentKind::Subharmonic : SegmentKind::Restart;
    seg.after = after;
    seg.recurrence = sec.recurrence[static_cast<std::size_t>(sec.period - 1)];
    seg.cpu_seconds = detail::thread_cpu_seconds() - c0;
    const Scalar t_last = sec.t0 + Scalar(sec.states.size() - 1) * T;
    const Scalar lo = dir > 0 ? p_r : opt_.parameter_min, hi = dir > 0 ? opt_.parameter_max : p_r;
    segment(seg, sec.modes.back(), t_last, sec.states.back(), p_r, lo, hi, result.segments.size(), result);
    if (seg.branch.status == ContinuationStatus::StartFailed) {
      fail("period " + std::to_string(sec.period) + " T from the sections: " + seg.branch.message);
      continue;
    }
    result.segments.push_back(std::move(seg));
    last_ok = result.segments.size() - 1;
    after.clear();
    finish(result.segments.back());
  }
}

}  // namespace stickslip

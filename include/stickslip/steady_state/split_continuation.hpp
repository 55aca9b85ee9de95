#pragma once
/// \file split_continuation.hpp
/// \brief SplitContinuation: one branch of forced periodic orbits followed in parts, each part on
/// its own thread and its own copy of the system, joined where a part's branch runs into the next
/// part's start orbit (a frequency-response curve on several cores).

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/period_run.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <functional>
#include <future>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace stickslip {

/// What one part of a SplitContinuation did.
template <class Scalar>
struct ContinuationPart {
  Scalar start_parameter = 0;  ///< the parameter of the part's start orbit
  ContinuationStatus status = ContinuationStatus::Completed;  ///< how the part's run ended
  std::string message;   ///< why it ended (empty when Completed)
  std::size_t points = 0;  ///< points the part computed
  std::size_t kept = 0;    ///< of them in the joined branch (0: the branch never reached the part)
  /// The part's branch ran into the next part's start orbit and stopped there (status Stopped).
  bool joined = false;
  double cpu_seconds = 0;  ///< CPU time of the part's thread
};

/// The joined branch and the parts it was made of.
template <class System>
struct SplitContinuationResult {
  /// The branch in branch order: part 0's points up to the join, then part 1's, ... Its status
  /// is that of the last part it holds; a later part's first point has `step` = its distance
  /// from the point before (in the arclength norm) and `stability_changed` against that point.
  ContinuationResult<System> branch;
  std::vector<ContinuationPart<typename System::Scalar>> parts;  ///< one per system, in order
  /// Per part: its own run when the joined branch does not hold it (parts[k].kept == 0: an
  /// earlier part ended without joining, e.g. StepTooSmall before the cut, or went past it on
  /// another sheet), else empty - the pieces of the curve beyond where the branch ended.
  std::vector<ContinuationResult<System>> dropped;
  /// branch.completed().
  bool completed() const noexcept { return branch.completed(); }
};

/// Pseudo-arclength continuation (Continuation) of one branch in n parts run at once: the
/// parameter range [parameter_min, parameter_max] is cut into n equal intervals, and part k
/// starts at the k-th cut in the direction of travel (options.direction), with its own system
/// (`systems[k]`, on its own std::thread; part 0 on the calling thread) and the whole range
/// allowed. Part k ends when its branch runs into part k + 1's start: a step (y_a, y_b) of part k
/// (y = (x_P, p) as in Continuation's arclength norm) that crosses the start parameter p_s of
/// part k + 1 in the direction of travel, passes within join_tolerance |y_b - y_a| of part k+1's
/// start point y_s, and points the way part k + 1's first step does (positive scalar product).
/// A part whose branch never meets the next start (the start orbit lies on another branch, e.g.
/// the other side of a fold, or the start failed) goes on to the end of the range alone, and the
/// later parts are dropped: the joined branch follows the curve that a single Continuation from
/// the first cut traces (its points differ where the parts' steps do), whatever the later starts
/// found. The speed-up is up to n on n cores when every part joins. options.max_points bounds
/// each part. Points compare on part k + 1's section t0: where part k's section moved
/// (ContinuationOptions::section_margin moved it away from an event), the two points of its
/// crossing step are carried there by a plain run each (of less than a period, on part k's
/// system) before the test. Where the step's chord misses part k + 1's start (a kink of the
/// branch at a grazing, where the event sequence changes), part k's orbit at that start's
/// parameter, shot from the chord's point there, decides: it joins when that orbit lies within
/// the same tolerance of the start.
///
/// The systems must be independent objects (copies at the same settings): `set_parameter`,
/// `start` and the start_mode rule are called for part k with systems[k] on part k's thread.
/// Throws std::invalid_argument for an empty system list, a null or repeated system, empty
/// callbacks, invalid options or a join tolerance outside (0, 1); an exception in a part's thread
/// is rethrown from run() after every thread ended (and std::system_error when a thread cannot be
/// started).
template <class System>
class SplitContinuation {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// The continuation of one part.
  using Part = Continuation<System>;
  /// The result type.
  using Result = SplitContinuationResult<System>;
  /// A start guess of the orbit at a part's start parameter: mode, t0 and state.
  struct Guess {
    Mode mode;     ///< the mode at t0
    Scalar t0 = 0;  ///< the start time of the orbit
    State x0;      ///< the guess of the orbit's state at t0
  };
  /// The guess at parameter p on a part's system (already set to p): e.g. the end of a transient.
  using StartGuess = std::function<Guess(System&, Scalar)>;
  /// Called after each accepted point of part k, on part k's thread.
  using OnPoint = std::function<void(std::size_t, const ContinuationPoint<System>&)>;

  /// Keeps the pointers: systems[k] is part k's system. Throws std::invalid_argument for an
  /// empty list, a null or repeated entry, empty set_parameter or period, or invalid options.
  SplitContinuation(std::vector<System*> systems, typename Part::SetParameter set_parameter,
                    typename Part::PeriodOf period, ShootingOptions<Scalar> shooting = {},
                    ContinuationOptions<Scalar> options = {})
      : systems_(std::move(systems)), set_(std::move(set_parameter)), period_(std::move(period)),
        shooting_(std::move(shooting)), opt_(options) {
    static const std::string where = "SplitContinuation";
    if (systems_.empty()) detail::throw_invalid(where, "systems must not be empty, size", 0);
    for (std::size_t k = 0; k < systems_.size(); ++k) {
      if (!systems_[k]) detail::throw_invalid(where, "systems[k] must not be null, k", k);
      for (std::size_t j = 0; j < k; ++j)  // one object on two threads: a data race
        if (systems_[j] == systems_[k])
          detail::throw_invalid(where, "systems[k] must be distinct objects (copies), k", k);
    }
    if (!set_) throw std::invalid_argument("SplitContinuation: set_parameter must not be empty");
    if (!period_) throw std::invalid_argument("SplitContinuation: period must not be empty");
    opt_.validate(where);
  }

  /// The start-mode rule of every part (Continuation::start_mode).
  void start_mode(typename Part::StartMode rule) { start_mode_ = std::move(rule); }
  /// Call `f(k, point)` after each accepted point of part k (on part k's thread: synchronise).
  void on_point(OnPoint f) { on_point_ = std::move(f); }
  /// A step joins the next part when it passes within `tolerance` times its length of the next
  /// start (default 0.1: a chord strays from a branch of curvature kappa by kappa |dy|^2 / 8).
  /// Throws std::invalid_argument outside (0, 1).
  void join_tolerance(Scalar tolerance) {
    if (!(tolerance > 0 && tolerance < 1))
      detail::throw_invalid("SplitContinuation::join_tolerance", "tolerance must be in (0, 1)", tolerance);
    join_tol_ = tolerance;
  }

  /// Follow the branch in systems.size() parts; `start(system, p)` gives each part's guess.
  /// Throws std::invalid_argument when start is empty.
  Result run(const StartGuess& start);

 private:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  // A part's start and its first step's corrected point in (x_P, p) (valid: both on one section).
  struct Head {
    bool valid = false;
    Vector y0, y1;
    Scalar t0 = 0;  // the section of both (a part whose second point moved it has no head)
  };
  // (x_P, p) of a state at parameter p, x_P the periodic components of ShootingOptions.
  Vector pack(const State& x, Scalar p) const {
    const std::vector<Eigen::Index> P = shooting_.periodic_indices(x.size());
    Vector y(static_cast<Eigen::Index>(P.size()) + 1);
    for (std::size_t k = 0; k < P.size(); ++k) y[static_cast<Eigen::Index>(k)] = x[P[k]];
    y[y.size() - 1] = p;
    return y;
  }
  Vector pack(const ContinuationPoint<System>& pt) const { return pack(pt.orbit.x0, pt.parameter); }
  // The state and mode of a point's orbit on the section t0: its own when the orbit is there,
  // else where a plain run of the shift (t0 - its t0, modulo its period) from its own section
  // ends, on `sys` at the point's parameter (the forcing repeats every period: the same orbit,
  // seen at t0). False when that run fails.
  bool on_section(System& sys, const ContinuationPoint<System>& pt, Scalar t0, State& x, Mode& m) const;
  // Does the step (a, b) of a part (on `sys`, left at b's parameter) run into the next part's
  // start?
  bool joins(System& sys, const ContinuationPoint<System>& a, const ContinuationPoint<System>& b,
             Scalar p_next, std::shared_future<Head>& next) const;

  std::vector<System*> systems_;
  typename Part::SetParameter set_;
  typename Part::PeriodOf period_;
  ShootingOptions<Scalar> shooting_;
  ContinuationOptions<Scalar> opt_;
  typename Part::StartMode start_mode_;
  OnPoint on_point_;
  Scalar join_tol_ = Scalar(0.1);
};

template <class System>
bool SplitContinuation<System>::on_section(System& sys, const ContinuationPoint<System>& pt, Scalar t0, State& x,
                                           Mode& m) const {
  x = pt.orbit.x0;
  m = pt.orbit.mode;
  if (pt.orbit.t0 == t0) return true;
  using std::fmod;
  const Scalar T = pt.orbit.period;
  Scalar shift = fmod(t0 - pt.orbit.t0, T);
  if (shift < 0) shift += T;
  if (!(shift > 0)) return true;  // t0 and the orbit's section differ by whole periods
  set_(sys, pt.parameter);
  const PeriodRun<System> r = run_period(sys, pt.orbit.mode, pt.orbit.t0, pt.orbit.x0, shift, shooting_, false);
  if (!r.ok()) return false;
  x = r.x_end;
  m = r.mode_end;
  return true;
}

template <class System>
bool SplitContinuation<System>::joins(System& sys, const ContinuationPoint<System>& a,
                                      const ContinuationPoint<System>& b, Scalar p_next,
                                      std::shared_future<Head>& next) const {
  const Scalar dir = Scalar(opt_.direction);
  if (!(dir * (a.parameter - p_next) < 0 && dir * (b.parameter - p_next) >= 0)) return false;
  const Head& head = next.get();  // waits for the next part's start and its first step
  if (!head.valid) return false;
  // (x_P, p) compare on one section: where Continuation moved this part's section away from an
  // event (ContinuationOptions::section_margin), a and b are carried to the next part's by a
  // plain run each. The system is set back to b's parameter, where the part goes on.
  State xa, xb;
  Mode ma{}, mb{};
  const bool moved = !(a.orbit.t0 == head.t0 && b.orbit.t0 == head.t0);
  auto done = [&](bool joined) {
    if (moved) set_(sys, b.parameter);
    return joined;
  };
  if (!on_section(sys, a, head.t0, xa, ma) || !on_section(sys, b, head.t0, xb, mb)) return done(false);
  const Vector ya = pack(xa, a.parameter), d = pack(xb, b.parameter) - ya;
  const Scalar len2 = d.squaredNorm();
  if (!(len2 > 0) || !(d.dot(head.y1 - head.y0) > 0)) return done(false);
  using std::sqrt;
  const Scalar tol = join_tol_ * sqrt(len2);
  const Scalar s = std::clamp((head.y0 - ya).dot(d) / len2, Scalar(0), Scalar(1));
  if ((ya + s * d - head.y0).norm() <= tol) return done(true);
  // The chord of a step over a kink of the branch (a phase born at a grazing, where the orbits'
  // event sequence changes) can miss the next start by more than the tolerance although both lie
  // on one branch: then the orbit of this part's branch at p_next decides, shot from the chord's
  // point there (it converges to the next start's orbit only when both are on one sheet).
  const Scalar sp = std::clamp((p_next - a.parameter) / (b.parameter - a.parameter), Scalar(0), Scalar(1));
  const State xg = xa + sp * (xb - xa);
  set_(sys, p_next);
  const Mode guess_mode = start_mode_ ? start_mode_(sys, head.t0, xg, sp < Scalar(0.5) ? ma : mb)
                                      : (sp < Scalar(0.5) ? ma : mb);
  Shooting<System> shooting(sys, shooting_);
  const PeriodicOrbit<System> orbit = shooting.forced(guess_mode, head.t0, xg, period_(p_next));
  set_(sys, b.parameter);
  return orbit.ok() && (pack(orbit.x0, p_next) - head.y0).norm() <= tol;
}

template <class System>
auto SplitContinuation<System>::run(const StartGuess& start) -> Result {
  if (!start) throw std::invalid_argument("SplitContinuation::run: start must not be empty");
  const std::size_t n = systems_.size();
  Result result;
  result.parts.resize(n);
  std::vector<ContinuationResult<System>> runs(n);
  std::vector<std::promise<Head>> heads(n);
  std::vector<std::shared_future<Head>> head_of(n);
  for (std::size_t k = 0; k < n; ++k) head_of[k] = heads[k].get_future().share();
  std::vector<std::exception_ptr> errors(n);
  const Scalar width = (opt_.parameter_max - opt_.parameter_min) / Scalar(n);
  auto start_parameter = [&](std::size_t k) {
    return opt_.direction > 0 ? opt_.parameter_min + Scalar(k) * width : opt_.parameter_max - Scalar(k) * width;
  };
  auto part = [&](std::size_t k) {
    ContinuationPart<Scalar>& report = result.parts[k];
    const double cpu0 = detail::thread_cpu_seconds();
    Head head;
    bool published = false;
    auto publish = [&] {
      if (!published) heads[k].set_value(head);
      published = true;
    };
    try {
      System& sys = *systems_[k];
      const Scalar p0 = start_parameter(k);
      report.start_parameter = p0;
      Part cont(sys, set_, period_, shooting_, opt_);
      if (start_mode_) cont.start_mode(start_mode_);
      std::size_t count = 0;
      cont.on_point([&](const ContinuationPoint<System>& pt) {
        if (count == 0) {
          head.y0 = pack(pt);
          head.t0 = pt.orbit.t0;
        }
        ++count;
        if (on_point_) on_point_(k, pt);
      });
      // Every part (the last one too) publishes its head at its first step, whether or not that
      // step joins or leaves the range: a part that joins the next one (cuts narrower than the
      // step) or ends at once would otherwise leave the part before it unable to join it.
      const bool last = k + 1 == n;
      const Scalar p_next = last ? Scalar(0) : start_parameter(k + 1);
      std::shared_future<Head> next = last ? std::shared_future<Head>() : head_of[k + 1];
      cont.stop_when([this, &sys, last, p_next, next, &count, &head, &publish](
                         const ContinuationPoint<System>& a, const ContinuationPoint<System>& b) mutable {
        if (count == 1) {
          head.y1 = pack(b);
          head.valid = b.orbit.t0 == head.t0;
          publish();
        }
        return !last && joins(sys, a, b, p_next, next);
      });
      set_(sys, p0);
      const Guess g = start(sys, p0);
      runs[k] = cont.run(g.mode, g.t0, g.x0, p0);
      report.status = runs[k].status;
      report.message = runs[k].message;
      report.points = runs[k].points.size();
      report.joined = runs[k].status == ContinuationStatus::Stopped;
    } catch (...) {
      errors[k] = std::current_exception();
    }
    head.valid = head.valid && !errors[k];
    publish();
    report.cpu_seconds = detail::thread_cpu_seconds() - cpu0;
  };

  std::vector<std::thread> threads;
  threads.reserve(n - 1);
  try {
    for (std::size_t k = 1; k < n; ++k) threads.emplace_back(part, k);
  } catch (...) {  // no thread for part k: the parts started end without joining it, then throw
    for (std::size_t k = threads.size() + 1; k < n; ++k) heads[k].set_value(Head{});
    for (auto& t : threads) t.join();
    throw;
  }
  part(0);
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  // Join: part 0's points, then each next part's while the one before joined.
  ContinuationResult<System>& branch = result.branch;
  result.dropped.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    auto& pts = runs[k].points;
    if (!pts.empty() && !branch.points.empty()) {
      const ContinuationPoint<System>& last = branch.points.back();
      pts.front().step = (pack(pts.front()) - pack(last)).norm();
      pts.front().stability_changed = pts.front().orbit.floquet.stable != last.orbit.floquet.stable;
    }
    result.parts[k].kept = pts.size();
    for (auto& pt : pts) branch.points.push_back(std::move(pt));
    branch.status = runs[k].status;
    branch.message = runs[k].message;
    if (!result.parts[k].joined) {
      for (std::size_t j = k + 1; j < n; ++j) result.dropped[j] = std::move(runs[j]);
      break;
    }
  }
  branch.bifurcations = locate_bifurcations(branch.points, shooting_.multiplier_tolerance);
  return result;
}

}  // namespace stickslip

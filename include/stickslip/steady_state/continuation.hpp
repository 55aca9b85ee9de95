#pragma once
/// \file continuation.hpp
/// \brief Continuation: a branch of forced periodic orbits followed in a scalar parameter by
/// pseudo-arclength continuation (through folds), with stability along the branch.

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/progress.hpp>
#include <stickslip/steady_state/shooting.hpp>
#include <stickslip/steady_state/stall_diagnosis.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Options of Continuation (the orbit tolerances are those of ShootingOptions).
template <class Scalar>
struct ContinuationOptions {
  Scalar parameter_min = 0;  ///< the branch ends when the parameter leaves [parameter_min, parameter_max]
  Scalar parameter_max = 1;  ///< upper end of the parameter range
  Scalar initial_step = Scalar(0.01);  ///< first arclength step (in the norm of (x_P, p))
  Scalar min_step = Scalar(1e-6);      ///< smallest arclength step before giving up
  Scalar max_step = Scalar(0.1);       ///< largest arclength step
  int max_points = 200;                ///< points computed at most (the start included)
  int max_corrector_iterations = 8;    ///< Newton iterations of the corrector per step
  int fast_iterations = 3;  ///< converged in at most this many: the next step grows by `growth`
  Scalar growth = Scalar(1.5);  ///< step growth after a fast corrector (a failure halves the step)
  /// Sign of the first parameter step: +1 towards parameter_max, -1 towards parameter_min.
  int direction = 1;
  /// > 0: a corrected point farther than max_corrector_distance * ds from its prediction counts
  /// as a failed step (the step halves): the corrector jumped to another orbit (a branch
  /// switch at a kink of G, where the event sequence changes, or a far-off solution outside the
  /// range). 0: no check (the default).
  Scalar max_corrector_distance = 0;
  /// > 0: when an event of an accepted orbit lies within section_margin T of the section t0
  /// (mod T), t0 moves to the middle of the orbit's longest event-free interval before the next
  /// step (the last two points are carried there by a plain run of the shift, the secant taken
  /// between them): an event crossing t0 along the branch makes G kink there (the start mode
  /// flips between iterates) and stalls the corrector. Each point's orbit reports its own t0.
  /// Default 0.02 (2 % of a period: what the blade's and the grounded slider's frequency
  /// responses need). 0: t0 fixed along the branch (a branch followed into a family of orbits,
  /// e.g. a damper stuck all period, takes a different corrector path on a moved section).
  Scalar section_margin = Scalar(0.02);
  /// true: the section t0 is kept within the first period, t0 in [0, T(p)): the start's t0 is
  /// reduced modulo T(p0) (the orbit through (t0 - k T, x0) is the one through (t0, x0): the
  /// system is T-periodic in t), and a section moved past T(p) by section_margin is moved back
  /// by whole periods. The state at t0 of an orbit forced at omega = 2 pi / T turns with the
  /// forcing phase omega t0: at a fixed t0 along a frequency branch, |dx0/d omega| ~ |x| t0, so a
  /// start at the end of a transient of n periods (t0 = n T) winds the branch into a helix of
  /// n turns per unit of omega T / (2 pi): the secant predictor misses it (the corrector fails,
  /// the steps stay tiny and the parameter crawls). Kept within a period, the turning adds at most
  /// 2 pi |x| per unit of omega / omega to the slope of the branch. false: t0 as given, moved only
  /// by section_margin (a system whose time dependence is not T(p)-periodic).
  bool wrap_section = true;
  /// > 0: the corrector first makes up to this many chord iterations: plain orbit runs (no
  /// monodromy, no dG/dp) solved with the last accepted point's [M - I, dG/dp] and the current
  /// tangent, while the residual at least halves per run; Newton's own iterations (a
  /// variational run and dG/dp each) then confirm the point (one run when the chord converged:
  /// the converged orbit's monodromy) or take over. A variational run costs several plain ones
  /// (the blade: ~14), so a point costs about one variational run instead of one per iteration.
  /// The step control reads Newton's iterations only: a point the chord converged counts as
  /// fast. Not after the section moved (the last M belongs to the old section). 0 (the
  /// default): Newton only.
  int chord_iterations = 0;
  /// Called after each accepted point, before Continuation::on_point's function (empty: never),
  /// with the points so far, the fraction of the range covered, the CPU seconds so far and an
  /// estimate of the seconds to the end of the range (ContinuationProgress). SplitContinuation
  /// calls it from each part's thread with that part's progress.
  ContinuationProgressCallback progress;

  /// Throws std::invalid_argument("<where>: options.<name> ...") for an option out of range.
  void validate(const std::string& where) const {
    detail::require_finite(where, "options.parameter_min", parameter_min);
    detail::require_finite(where, "options.parameter_max", parameter_max);
    if (!(parameter_min < parameter_max))
      detail::throw_invalid(where, "options.parameter_max must be > options.parameter_min",
                            parameter_max);
    detail::require_positive(where, "options.min_step", min_step);
    detail::require_positive(where, "options.max_step", max_step);
    if (!(initial_step >= min_step && initial_step <= max_step))
      detail::throw_invalid(where, "options.initial_step must be in [min_step, max_step]",
                            initial_step);
    if (max_points <= 0) detail::throw_invalid(where, "options.max_points must be > 0", max_points);
    if (max_corrector_iterations <= 0)
      detail::throw_invalid(where, "options.max_corrector_iterations must be > 0",
                            max_corrector_iterations);
    if (fast_iterations < 1)
      detail::throw_invalid(where, "options.fast_iterations must be >= 1", fast_iterations);
    if (!(growth >= 1 && growth <= 4))
      detail::throw_invalid(where, "options.growth must be in [1, 4]", growth);
    if (direction != 1 && direction != -1)
      detail::throw_invalid(where, "options.direction must be +1 or -1", direction);
    detail::require_non_negative(where, "options.max_corrector_distance", max_corrector_distance);
    if (chord_iterations < 0)
      detail::throw_invalid(where, "options.chord_iterations must be >= 0", chord_iterations);
    if (!(section_margin >= 0 && section_margin < Scalar(0.5)))
      detail::throw_invalid(where, "options.section_margin must be in [0, 0.5)", section_margin);
  }
};

/// How a continuation run ended.
enum class ContinuationStatus : std::uint8_t {
  Completed,     ///< the branch left the parameter range
  MaxPoints,     ///< options.max_points reached inside the range
  StepTooSmall,  ///< the corrector failed down to options.min_step (the last failure is reported)
  StartFailed,   ///< no orbit at the start parameter (the shooting failure is reported)
  Stopped,       ///< the stop_when rule ended the branch (SplitContinuation: a join)
  Interrupted    ///< ShootingOptions::interrupt stopped the run (the points so far are kept)
};

/// Human-readable name of a continuation status.
inline const char* to_string(ContinuationStatus s) noexcept {
  switch (s) {
    case ContinuationStatus::Completed: return "completed";
    case ContinuationStatus::MaxPoints: return "max_points";
    case ContinuationStatus::StepTooSmall: return "step_too_small";
    case ContinuationStatus::StartFailed: return "start_failed";
    case ContinuationStatus::Stopped: return "stopped";
    case ContinuationStatus::Interrupted: return "interrupted";
  }
  return "unknown";
}

/// One point of a branch.
template <class System>
struct ContinuationPoint {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  Scalar parameter = 0;                ///< the parameter p
  PeriodicOrbit<System> orbit;         ///< the orbit at p (initial state, multipliers, amplitudes, events)
  Scalar step = 0;                     ///< the arclength step that reached it (0 at the start)
  /// The orbit's stability differs from the previous point's (a multiplier crossed the unit
  /// circle between them; orbit.floquet.instability says where when it became unstable).
  bool stability_changed = false;
};

/// A computed branch.
template <class System>
struct ContinuationResult {
  ContinuationStatus status = ContinuationStatus::Completed;  ///< how it ended
  std::string message;  ///< why it ended early (empty when Completed)
  std::vector<ContinuationPoint<System>> points;  ///< the points in branch order
  /// Where multipliers crossed the unit circle between points, and how (locate_bifurcations).
  std::vector<BifurcationPoint<typename System::Scalar>> bifurcations;
  /// status == Completed.
  bool completed() const noexcept { return status == ContinuationStatus::Completed; }
};

/// Pseudo-arclength continuation of the forced periodic orbits of `System` in a scalar parameter
/// p that the user maps onto the system: `set_parameter(system, p)` and the forcing period
/// `period(p)` (e.g. 2 pi / p when p is the excitation frequency). Unknowns y = (x_P, p):
///
///     G(y) = x_P(t0 + T(p); x0, p) - x_P = 0,   tau^T (y - y_k - ds tau) = 0,
///
/// predictor y_k + ds tau, Newton corrector on both equations with dG/dx_P = M_PP - I (the
/// monodromy of ShootingOptions) and dG/dp by central differences of re-shot orbits
/// (h = fd_step max(1, |p|)); the corrector step is Shooting::newton_step's (minimum-norm when
/// the matrix is singular to the monodromy's accuracy: a family of orbits, e.g. a damper stuck
/// all period, is crossed the least). tau: at the start the null vector of [dG/dx_P, dG/dp]
/// with the least x_P part (towards options.direction); then the secant of the last two points,
/// so the branch turns at folds.
/// Step control: a corrector converged in <= fast_iterations grows ds by `growth` (up to
/// max_step), one that needs more than half the allowed iterations halves it, a failure halves it
/// and retries (down to min_step); with max_corrector_distance > 0 a corrected point farther from
/// its prediction than that many ds is a failure too. The arclength norm is Euclidean in (x_P, p): scale the
/// parameter (or the states) so that both are of order one. t0 is taken within the first
/// period (options.wrap_section: a section at t0 = n T turns the orbit's state with the forcing
/// phase, n turns per unit of omega T / (2 pi)), kept along the branch while
/// no event of the orbit comes within options.section_margin of a period of it, else moved
/// away from the events (see the option); the start mode is kept too, unless a start_mode()
/// rule re-decides it from each iterate (needed when a switch of the orbit crosses t0 along the
/// branch, i.e. with section_margin = 0). The system is left at the
/// parameter of the last point. Throws std::invalid_argument for caller errors only.
template <class System>
class Continuation {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// The user's map of p onto the system.
  using SetParameter = std::function<void(System&, Scalar)>;
  /// The forcing period as a function of p.
  using PeriodOf = std::function<Scalar(Scalar)>;
  /// Called after each accepted point (progress output).
  using OnPoint = std::function<void(const ContinuationPoint<System>&)>;
  /// The mode at t0 for the state x (the previous mode given): e.g. a FrictionDampedSystem's
  /// make_consistent on a copy of x.
  using StartMode = std::function<Mode(System&, Scalar, const State&, const Mode&)>;
  /// Ends the branch when it returns true for (last accepted point, newly corrected point).
  using StopRule = std::function<bool(const ContinuationPoint<System>&, const ContinuationPoint<System>&)>;
  /// The result type.
  using Result = ContinuationResult<System>;

  /// Keeps a reference to `system`. Throws std::invalid_argument when set_parameter or period is
  /// empty, or for invalid options.
  Continuation(System& system, SetParameter set_parameter, PeriodOf period,
               ShootingOptions<Scalar> shooting = {}, ContinuationOptions<Scalar> options = {})
      : sys_(system), set_(std::move(set_parameter)), period_(std::move(period)),
        shooting_(system, std::move(shooting)), opt_(options) {
    if (!set_) throw std::invalid_argument("Continuation: set_parameter must not be empty");
    if (!period_) throw std::invalid_argument("Continuation: period must not be empty");
    opt_.validate("Continuation");
  }

  /// Follow symmetric orbits shot on half the period (Shooting::half_period_symmetry): the
  /// corrector solves c + S (x(t0 + T/2) - c) = x(t0) with H - I; the points' monodromy is H^2.
  void half_period_symmetry(HalfPeriodSymmetry<System> symmetry) {
    shooting_.half_period_symmetry(std::move(symmetry));
  }

  /// Call `on_point(point)` after each accepted point.
  void on_point(OnPoint f) { on_point_ = std::move(f); }

  /// Re-decide the start mode of every orbit run from its start state: mode =
  /// rule(system, t0, x, previous mode) (default: the mode given to run() throughout). An orbit
  /// is periodic when the run ends in the mode so decided.
  void start_mode(StartMode rule) { start_mode_ = std::move(rule); }

  /// Ask `rule(last, next)` after each corrected point, the first one beyond the range too (the
  /// step that leaves it): true ends the run with status Stopped before `next` is added
  /// (SplitContinuation joins its parts so); false beyond the range ends it Completed.
  void stop_when(StopRule rule) { stop_ = std::move(rule); }

  /// Follow the branch from the orbit at p0 (found by shooting from (mode, t0, x0_guess)), with
  /// its bifurcations (locate_bifurcations at options.multiplier_tolerance).
  /// Throws std::invalid_argument for p0 outside the range, or (via Shooting) for bad x0/t0.
  Result run(const Mode& mode, Scalar t0, const State& x0_guess, Scalar p0) {
    Result r = follow(mode, t0, x0_guess, p0);
    r.bifurcations = locate_bifurcations(r.points, shooting_.options().multiplier_tolerance);
    return r;
  }

 private:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  Result follow(const Mode& mode, Scalar t0, const State& x0_guess, Scalar p0);
  // Whether ShootingOptions::interrupt asks to stop (then the result's status and message).
  bool interrupted(Result& result, Scalar p) const {
    const InterruptCheck& stop = shooting_.options().interrupt;
    if (!stop || !stop()) return false;
    result.status = ContinuationStatus::Interrupted;
    result.message = "interrupted: options.interrupt returned true after p = " + detail::format_value(p);
    return true;
  }
  // Orbit run at (x, p) with the monodromy.
  PeriodRun<System> shoot(const Mode& mode, Scalar t0, const State& x, Scalar p, bool monodromy) {
    set_(sys_, p);
    return shooting_.run_orbit(mode, t0, x, period_(p), monodromy);
  }
  // The start mode for x at the current parameter (start_mode_, else `mode`).
  Mode mode_at(const Mode& mode, Scalar t0, const State& x) {
    return start_mode_ ? start_mode_(sys_, t0, x, mode) : mode;
  }
  // dG/dp at (x, p) by central differences; false (and why) when a run fails.
  bool parameter_derivative(const Mode& mode, Scalar t0, const State& x, Scalar p, Vector& gp,
                            std::string& why);
  // Chord iterations from (x, p) = the prediction (ContinuationOptions::chord_iterations): leaves
  // (x, p, mode) at the converged or the best iterate, for the Newton loop to confirm.
  void chord(Mode& mode, Scalar t0, State& x, Scalar& p, const Vector& tau, const Vector& y_pred,
             int& iterations);
  // Corrector from y_pred along tau; true with the orbit (and its start mode), else why.
  // iterations: all orbit runs; newton: Newton's own (1 when the chord converged), which the step
  // control reads.
  bool correct(Mode& mode, Scalar t0, State& x, Scalar& p, const Vector& tau,
               const State& x_pred, Scalar p_pred, PeriodicOrbit<System>& orbit, int& iterations,
               int& newton, std::string& why);
  // The shift of t0 to the middle of the orbit's longest event-free interval when one of its
  // events lies within section_margin T of t0 (mod T); 0 when none does, or when no interval
  // is longer than twice the margin.
  Scalar section_shift(const PeriodicOrbit<System>& orbit, Scalar T) const;
  // t reduced into [0, T) by whole periods (ContinuationOptions::wrap_section).
  static Scalar within_period(Scalar t, Scalar T) {
    using std::floor;
    const Scalar r = t - floor(t / T) * T;
    return r >= 0 && r < T ? r : Scalar(0);
  }
  // Runs (mode, t0, x) at parameter p for `delta`; false when the run fails.
  bool advance(Mode& mode, Scalar t0, State& x, Scalar p, Scalar delta) {
    set_(sys_, p);
    const PeriodRun<System> r = run_period(sys_, mode, t0, x, delta, shooting_.options(), false);
    if (!r.ok()) return false;
    x = r.x_end;
    mode = r.mode_end;
    return true;
  }
  // The corrector's matrix [M_PP - I, dG/dp; tau^T] (M_PP: the periodic block of a monodromy).
  static void corrector_matrix(const Matrix& M_PP, const Vector& gp, const Vector& tau, Matrix& J) {
    const Eigen::Index np = M_PP.rows();
    J.resize(np + 1, np + 1);
    J.topLeftCorner(np, np) = M_PP - Matrix::Identity(np, np);
    J.topRightCorner(np, 1) = gp;
    J.bottomRows(1) = tau.transpose();
  }
  Vector pack(const State& x, Scalar p) const {
    Vector y(static_cast<Eigen::Index>(P_.size()) + 1);
    for (std::size_t k = 0; k < P_.size(); ++k) y[static_cast<Eigen::Index>(k)] = x[P_[k]];
    y[y.size() - 1] = p;
    return y;
  }
  void unpack(const Vector& y, State& x, Scalar& p) const {
    for (std::size_t k = 0; k < P_.size(); ++k) x[P_[k]] = y[static_cast<Eigen::Index>(k)];
    p = y[y.size() - 1];
  }

  System& sys_;
  SetParameter set_;
  PeriodOf period_;
  Shooting<System> shooting_;
  ContinuationOptions<Scalar> opt_;
  OnPoint on_point_;
  StartMode start_mode_;
  StopRule stop_;
  std::vector<Eigen::Index> P_;
  // The chord's matrix parts: the last accepted point's periodic monodromy block and the latest
  // dG/dp (valid while the section is that point's).
  bool chord_valid_ = false;
  Matrix chord_M_;
  Vector chord_gp_;
};

template <class System>
bool Continuation<System>::parameter_derivative(const Mode& mode, Scalar t0, const State& x,
                                                Scalar p, Vector& gp, std::string& why) {
  const Scalar h = shooting_.options().fd_step * std::max(Scalar(1), std::abs(p));
  // One-sided where T(p +- h) is not a period (p at the end of T's domain, e.g. T(p) = p near
  // p = 0): the difference stays inside the domain instead of a run_period that throws.
  const auto has_period = [&](Scalar q) {
    const Scalar T = period_(q);
    return detail::is_finite(q) && detail::is_finite(T) && T > 0;
  };
  const bool up = has_period(p + h), down = has_period(p - h);
  if (!up && !down) {
    why = "the period T(p) is not finite and > 0 at p +- " + detail::format_value(h) +
          " (p = " + detail::format_value(p) + ")";
    return false;
  }
  const Scalar hp = up ? h : Scalar(0), hm = down ? h : Scalar(0);
  const PeriodRun<System> plus = shoot(mode, t0, x, p + hp, false);
  const PeriodRun<System> minus = shoot(mode, t0, x, p - hm, false);
  set_(sys_, p);
  if (!plus.ok() || !minus.ok()) {
    why = "orbit run at p +- " + detail::format_value(h) + " failed: " +
          (plus.ok() ? minus.message : plus.message);
    return false;
  }
  Vector rp, rm;
  shooting_.residual(plus.x_end, x, rp);
  shooting_.residual(minus.x_end, x, rm);
  gp = (rp - rm) / (hp + hm);
  return true;
}

template <class System>
bool Continuation<System>::correct(Mode& mode, Scalar t0, State& x, Scalar& p,
                                   const Vector& tau, const State& x_pred, Scalar p_pred,
                                   PeriodicOrbit<System>& orbit, int& iterations, int& newton,
                                   std::string& why) {
  const auto np = static_cast<Eigen::Index>(P_.size());
  const Vector y_pred = pack(x_pred, p_pred);
  x = x_pred;
  p = p_pred;
  iterations = 0;
  if (opt_.chord_iterations > 0 && chord_valid_) chord(mode, t0, x, p, tau, y_pred, iterations);
  Vector r, gp, rhs(np + 1), dy(np + 1);
  Matrix J;
  StallEvidence<Scalar> evidence;  // what the corrector's runs show when it stalls
  Scalar res_prev = -1;
  for (newton = 1; newton <= opt_.max_corrector_iterations; ++newton) {
    ++iterations;
    if (!detail::is_finite(p) || !(period_(p) > 0)) {
      why = "the period T(p) is not > 0 at p = " + detail::format_value(p);
      return false;
    }
    set_(sys_, p);
    mode = mode_at(mode, t0, x);
    const PeriodRun<System> run = shoot(mode, t0, x, p, true);
    if (!run.ok()) {
      why = "orbit run failed at p = " + detail::format_value(p) + ": " + run.message;
      return false;
    }
    const Scalar res = shooting_.residual(run.x_end, x, r);
    evidence.note_run(t0, period_(p), run.events, run.grazing_events);
    if (res_prev >= 0) evidence.note_residual(res_prev, res);
    res_prev = res;
    if (res <= shooting_.tolerance_at(x)) {
      orbit = shooting_.make_orbit(run, mode, t0, x, period_(p), false, res, iterations);
      if (!orbit.ok()) why = orbit.message;
      return orbit.ok();
    }
    if (!parameter_derivative(mode, t0, x, p, gp, why)) return false;
    chord_gp_ = gp;
    corrector_matrix(shooting_.periodic_block(run.monodromy), gp, tau, J);
    rhs.head(np) = -r;
    rhs[np] = -tau.dot(pack(x, p) - y_pred);
    if (!shooting_.newton_step(J, rhs, dy)) {
      why = "singular corrector matrix at p = " + detail::format_value(p) + " (residual " +
            detail::format_value(res) + ", not in its range)";
      return false;
    }
    const Vector y = pack(x, p) + dy;
    unpack(y, x, p);
  }
  why = "the corrector did not converge in " + std::to_string(opt_.max_corrector_iterations) +
        " iterations (residual " + detail::format_value(res_prev) + "); detected: " +
        evidence.describe(true, opt_.section_margin);
  return false;
}

template <class System>
void Continuation<System>::chord(Mode& mode, Scalar t0, State& x, Scalar& p, const Vector& tau,
                                 const Vector& y_pred, int& iterations) {
  const auto np = static_cast<Eigen::Index>(P_.size());
  Matrix J;
  corrector_matrix(chord_M_, chord_gp_, tau, J);
  Vector r, rhs(np + 1), dy(np + 1);
  State best_x = x;
  Scalar best_p = p, best = std::numeric_limits<Scalar>::infinity();
  Mode best_mode = mode;
  auto keep_best = [&] {
    x = best_x;
    p = best_p;
    mode = best_mode;
  };
  for (int c = 0; c < opt_.chord_iterations; ++c) {
    if (!detail::is_finite(p) || !(period_(p) > 0)) return keep_best();
    set_(sys_, p);
    mode = mode_at(mode, t0, x);
    const PeriodRun<System> run = shoot(mode, t0, x, p, false);
    ++iterations;
    if (!run.ok()) return keep_best();
    const Scalar res = shooting_.residual(run.x_end, x, r);
    if (res <= shooting_.tolerance_at(x)) return;  // the Newton loop's first run confirms it
    if (!(res < Scalar(0.5) * best)) return keep_best();  // not contracting: Newton from the best
    best = res;
    best_x = x;
    best_p = p;
    best_mode = mode;
    rhs.head(np) = -r;
    rhs[np] = -tau.dot(pack(x, p) - y_pred);
    // (Newton's solve: minimum-norm where M - I is singular, e.g. on a family of stuck orbits)
    if (!shooting_.newton_step(J, rhs, dy) || !detail::all_finite(dy)) return keep_best();
    unpack(pack(x, p) + dy, x, p);
  }
}

template <class System>
auto Continuation<System>::section_shift(const PeriodicOrbit<System>& orbit, Scalar T) const -> Scalar {
  if (!(opt_.section_margin > 0) || orbit.events.empty() || !(T > 0)) return Scalar(0);
  using std::fmod;
  std::vector<Scalar> phase;
  phase.reserve(orbit.events.size());
  Scalar nearest = T;
  for (const auto& e : orbit.events) {
    Scalar f = fmod(e.t - orbit.t0, T);
    if (f < 0) f += T;
    phase.push_back(f);
    nearest = std::min({nearest, f, T - f});
  }
  const Scalar margin = opt_.section_margin * T;
  if (nearest >= margin) return Scalar(0);
  std::sort(phase.begin(), phase.end());
  Scalar best = phase.front() + T - phase.back(), shift = fmod(phase.back() + best / 2, T);
  for (std::size_t k = 1; k < phase.size(); ++k) {
    const Scalar gap = phase[k] - phase[k - 1];
    if (gap > best) {
      best = gap;
      shift = phase[k - 1] + gap / 2;
    }
  }
  return best > 2 * margin ? shift : Scalar(0);
}

template <class System>
auto Continuation<System>::follow(const Mode& mode0, Scalar t0, const State& x0_guess, Scalar p0)
    -> Result {
  static const std::string where = "Continuation::run";
  detail::require_finite(where, "p0", p0);
  if (!(p0 >= opt_.parameter_min && p0 <= opt_.parameter_max))
    detail::throw_invalid(where, "p0 must lie in [options.parameter_min, options.parameter_max]",
                          p0);
  Result result;
  const double cpu0 = detail::thread_cpu_seconds();  // options.progress's clock
  double cpu_last = cpu0;
  const Scalar p_end = opt_.direction > 0 ? opt_.parameter_max : opt_.parameter_min;
  auto report = [&](Scalar p_now) {
    if (!opt_.progress) return;
    ContinuationProgress pr;
    pr.points = static_cast<int>(result.points.size());
    pr.max_points = opt_.max_points;
    pr.parameter = static_cast<double>(p_now);
    pr.covered = p_end == p0 ? 1.0 : std::clamp(static_cast<double>((p_now - p0) / (p_end - p0)), 0.0, 1.0);
    const double now = detail::thread_cpu_seconds();
    pr.cpu_seconds = now - cpu0;
    pr.seconds_per_point = now - cpu_last;
    cpu_last = now;
    pr.remaining_seconds = detail::branch_remaining(pr.covered, pr.cpu_seconds, pr.points, pr.max_points);
    opt_.progress(pr);
  };
  P_ = shooting_.options().periodic_indices(x0_guess.size());
  const auto np = static_cast<Eigen::Index>(P_.size());
  set_(sys_, p0);
  const Scalar T0 = period_(p0);
  detail::require_positive(where, "period(p0)", T0);
  detail::require_finite(where, "t0", t0);
  if (opt_.wrap_section) t0 = within_period(t0, T0);
  Mode mode = mode0;
  PeriodicOrbit<System> orbit = shooting_.forced(mode, t0, x0_guess, T0);
  if (!orbit.ok()) {
    if (interrupted(result, p0)) return result;
    result.status = ContinuationStatus::StartFailed;
    result.message = "no periodic orbit at p0 = " + detail::format_value(p0) + ": " + orbit.message;
    return result;
  }
  // A start orbit with an event next to t0: the same orbit from a section away from its events.
  if (const Scalar shift = section_shift(orbit, T0); shift > 0) {
    Mode m = orbit.mode;
    State xs = orbit.x0;
    if (advance(m, t0, xs, p0, shift)) {
      PeriodicOrbit<System> moved = shooting_.forced(m, t0 + shift, xs, T0);
      if (moved.ok()) {
        t0 += shift;
        mode = moved.mode;
        orbit = std::move(moved);
      }
    }
    set_(sys_, p0);
  }
  State x = orbit.x0;
  Scalar p = p0;
  result.points.push_back({p, orbit, Scalar(0), false});
  report(p);
  if (on_point_) on_point_(result.points.back());

  // Start tangent: dG/dx_P v = -dG/dp (the least v when M - I is singular: a family),
  // tau = (v, 1) / |(v, 1)| towards options.direction.
  Vector gp, v, tau(np + 1);
  std::string why;
  if (!parameter_derivative(mode, t0, x, p, gp, why)) {
    result.status = ContinuationStatus::StartFailed;
    result.message = "start tangent: " + why;
    return result;
  }
  if (!shooting_.newton_step(orbit.shooting_map() - Matrix::Identity(np, np), -gp, v)) {
    result.status = ContinuationStatus::StartFailed;
    result.message = "start tangent: M - I is singular at p0 and dG/dp is not in its range (a "
                     "multiplier 1: start off a fold)";
    return result;
  }
  tau.head(np) = v;
  tau[np] = 1;
  tau *= Scalar(opt_.direction) / tau.norm();
  chord_M_ = orbit.shooting_map();
  chord_gp_ = gp;
  chord_valid_ = true;

  Scalar ds = opt_.initial_step;
  while (static_cast<int>(result.points.size()) < opt_.max_points) {
    if (interrupted(result, p)) {
      set_(sys_, p);
      return result;
    }
    const Vector y_pred = pack(x, p) + ds * tau;
    State x_pred = x, x_new = x;
    Scalar p_pred = 0, p_new = 0;
    unpack(y_pred, x_pred, p_pred);
    int iterations = 0;
    PeriodicOrbit<System> next;
    Mode mode_new = mode;
    int newton = 0;
    bool ok = correct(mode_new, t0, x_new, p_new, tau, x_pred, p_pred, next, iterations, newton, why);
    if (ok && opt_.max_corrector_distance > 0) {
      const Scalar jump = (pack(x_new, p_new) - y_pred).norm();
      if (jump > opt_.max_corrector_distance * ds) {
        ok = false;
        why = "the corrector landed " + detail::format_value(jump) + " from the prediction (more than " +
              detail::format_value(opt_.max_corrector_distance) + " ds = " + detail::format_value(ds) +
              "): another orbit";
      }
    }
    if (!ok) {
      if (interrupted(result, p)) {
        set_(sys_, p);
        return result;
      }
      ds /= Scalar(2);
      if (ds < opt_.min_step) {
        set_(sys_, p);
        result.status = ContinuationStatus::StepTooSmall;
        result.message = "the step fell below options.min_step after p = " +
                         detail::format_value(p) + ": " + why;
        return result;
      }
      continue;
    }
    // A point beyond the range ends the branch (Completed, the point not kept), but the stop
    // rule sees that last step too: it may cross what the rule looks for inside the range (a
    // SplitContinuation part whose last step passes both the next part's start and the end).
    const bool outside = p_new < opt_.parameter_min || p_new > opt_.parameter_max;
    const bool changed = next.floquet.stable != result.points.back().orbit.floquet.stable;
    const Scalar shift = outside ? Scalar(0) : section_shift(next, period_(p_new));
    ContinuationPoint<System> point{p_new, std::move(next), ds, changed};
    if (stop_ && stop_(result.points.back(), point)) {
      set_(sys_, p);
      result.status = ContinuationStatus::Stopped;
      result.message = "the stop rule ended the branch after p = " + detail::format_value(p);
      return result;
    }
    if (outside) {
      set_(sys_, p);
      return result;
    }
    Vector y_last = pack(x, p);
    chord_M_ = point.orbit.shooting_map();
    chord_valid_ = true;
    if (shift > 0) {  // both points to the section t0 + shift (kept at t0 if a run fails)
      Mode ma = mode, mb = mode_new;
      State xa = x, xb = x_new;
      // With wrap_section, the section t0 + shift - m T(p_new) in [0, T(p_new)): the new point
      // is there after `shift` (its period is T(p_new)), the last one after shift + m (T(p) -
      // T(p_new)) (its period is T(p)), so that the secant joins the two orbits at one section.
      const Scalar T_new = period_(p_new), t_shifted = t0 + shift;
      const Scalar t_wrapped = opt_.wrap_section ? within_period(t_shifted, T_new) : t_shifted;
      const Scalar m = std::round((t_shifted - t_wrapped) / T_new);
      Scalar shift_a = shift + m * (period_(p) - T_new);
      const bool wrap = m > 0 && shift_a > 0;
      if (!wrap) shift_a = shift;
      if (advance(ma, t0, xa, p, shift_a) && advance(mb, t0, xb, p_new, shift)) {
        t0 = wrap ? t_wrapped : t_shifted;
        x_new = xb;
        mode_new = mb;
        y_last = pack(xa, p);
        chord_valid_ = false;  // the last monodromy and dG/dp belong to the old section
      }
      set_(sys_, p_new);
    }
    const Vector secant = pack(x_new, p_new) - y_last;
    tau = secant / secant.norm();
    x = x_new;
    p = p_new;
    mode = mode_new;
    result.points.push_back(std::move(point));
    report(p);
    if (on_point_) on_point_(result.points.back());
    // (Newton's iterations: a point the chord converged counts as fast)
    if (newton <= opt_.fast_iterations)
      ds = std::min(ds * opt_.growth, opt_.max_step);
    else if (2 * newton > opt_.max_corrector_iterations)
      ds = std::max(ds / Scalar(2), opt_.min_step);
  }
  result.status = ContinuationStatus::MaxPoints;
  result.message = "options.max_points (" + std::to_string(opt_.max_points) +
                   ") reached at p = " + detail::format_value(p);
  return result;
}

}  // namespace stickslip

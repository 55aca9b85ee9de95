#pragma once
/// \file shooting.hpp
/// \brief Shooting: periodic orbits of a hybrid system by Newton's method on x(T) - x(0) = 0,
/// forced (period given) or autonomous (period unknown, with a phase condition).

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/floquet.hpp>
#include <stickslip/steady_state/half_period_symmetry.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/shooting_options.hpp>
#include <stickslip/steady_state/stall_diagnosis.hpp>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace stickslip {

/// How a periodic-orbit computation ended.
enum class ShootingStatus : std::uint8_t {
  Converged,          ///< a periodic orbit to the tolerance, its mode sequence closes
  NoConvergence,      ///< Newton did not reach the tolerance (the residual is reported)
  /// x(T) = x(0) but the mode at t0 + T is not the start mode; with a half-period symmetry
  /// also: the symmetric problem closes at t0 + T/2 but the full period does not (an event at
  /// the mirror point t0 + T/2)
  ModeNotPeriodic,
  IntegrationFailed,  ///< a run ended early (its status and message are reported)
  SingularJacobian    ///< the Newton matrix is singular (e.g. a multiplier exactly 1)
};

/// Human-readable name of a shooting status.
inline const char* to_string(ShootingStatus s) noexcept {
  switch (s) {
    case ShootingStatus::Converged: return "converged";
    case ShootingStatus::NoConvergence: return "no_convergence";
    case ShootingStatus::ModeNotPeriodic: return "mode_not_periodic";
    case ShootingStatus::IntegrationFailed: return "integration_failed";
    case ShootingStatus::SingularJacobian: return "singular_jacobian";
  }
  return "unknown";
}

/// A periodic orbit found by Shooting (or the last Newton iterate when it failed).
template <class System>
struct PeriodicOrbit {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  ShootingStatus status = ShootingStatus::NoConvergence;  ///< how the computation ended
  std::string message;  ///< empty when converged; otherwise what failed, with the residual
  Scalar t0 = 0;        ///< start time
  Scalar period = 0;    ///< T (autonomous: the one found)
  Mode mode{};          ///< mode at t0 (and, when converged, at t0 + T)
  State x0;             ///< the orbit's state at t0
  Scalar residual = 0;  ///< max |x_i(T) - x_i(0)| over the periodic components
  int iterations = 0;   ///< orbit runs made (Newton iterations and backtracking trials)
  /// dx_P(T)/dx_P(0) over the periodic components P (in the order of options.periodic); with a
  /// half-period symmetry (Shooting::half_period_symmetry) the full period's M, the periodic
  /// block of (S dx(t0 + T/2)/dx(t0))^2 over the whole state (H^2 when every component is periodic).
  Matrix monodromy;
  /// With a half-period symmetry: H = (S dx(t0 + T/2)/dx(t0))_PP, the matrix of the symmetric
  /// problem's Newton step (H - I); empty without one.
  Matrix half_period_map;
  /// Multipliers of `monodromy`, stability and instability kind.
  FloquetMultipliers<Scalar> floquet;
  /// max |x_i| over the orbit for options.amplitude_components (from the run that closed it).
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> amplitudes;
  /// The linear outputs of options.outputs over the orbit's period (OrbitSignal: extremes, mean,
  /// harmonics), from the run that closed the orbit: an unstable orbit is measured where it is,
  /// not where a later run would drift.
  std::vector<OrbitSignal<Scalar>> outputs;
  /// The events of one period, in order.
  std::vector<OrbitEvent<Scalar, Mode>> events;
  StepperStats stats;  ///< counters of the last orbit run
  /// status == ShootingStatus::Converged.
  bool ok() const noexcept { return status == ShootingStatus::Converged; }
  /// The map whose fixed point the orbit is: half_period_map with a half-period symmetry, else
  /// monodromy (Newton's and the continuation's matrix is this minus I).
  const Matrix& shooting_map() const noexcept { return half_period_map.size() ? half_period_map : monodromy; }
};

/// Periodic orbits of a hybrid system by single shooting:
///
///     forced:      x_P(t0 + T; x0) - x_P(0) = 0                    (T given, or k T: subharmonic)
///     autonomous:  x_P(T; x0) - x_P(0) = 0,  f_P(x0_k)^T (x0 - x0_k) = 0   (T unknown)
///
/// over the periodic components P (options.periodic; the others keep their start values), by
/// Newton's method with the Jacobian [M_PP - I] (autonomous: bordered by f_P(x(T)) and the phase
/// row f_P(x0_k)^T: the correction is orthogonal to the flow at the current iterate). M is the
/// monodromy (options.monodromy). When J is singular to the monodromy's accuracy (1 / |J^-1|,
/// estimated by the LU's rcond, below 1000 options.stepper.rtol) the step is the minimum-norm
/// least-squares one: a family of orbits (a damper stuck all period) is crossed the least; the
/// status is SingularJacobian when the residual is not in J's range. The start mode is kept: the orbit must return to it at
/// t0 + T. Every outcome is in the orbit's status; caller errors throw std::invalid_argument.
/// With a half-period symmetry (half_period_symmetry()) forced() solves the symmetric problem
/// c + S (x(t0 + T/2) - c) = x(t0) instead, with the Jacobian H - I (run_orbit()).
template <class System>
class Shooting {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// The result type.
  using Orbit = PeriodicOrbit<System>;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// Dynamic vector type.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// Keeps a reference to `system` (it must outlive the solver). Options are validated per call.
  explicit Shooting(System& system, ShootingOptions<Scalar> options = {})
      : sys_(system), opt_(std::move(options)) {}

  /// The options in use.
  const ShootingOptions<Scalar>& options() const { return opt_; }
  /// The system solved for.
  System& system() { return sys_; }

  /// Shoot on half the period under `symmetry` (see HalfPeriodSymmetry): every orbit run
  /// (run_orbit()) covers T/2 and ends mirrored, forced() finds the symmetric orbits, and their
  /// monodromy is the full period's M = H^2. Throws std::invalid_argument unless S is a finite
  /// square involution and the centre empty or finite of S's size; each run checks that S has
  /// the state's size.
  void half_period_symmetry(HalfPeriodSymmetry<System> symmetry) {
    // The centre's size where it has one (a fixed-size State always has): S must match it.
    const Eigen::Index n = symmetry.centre.size() != 0 ? symmetry.centre.size() : symmetry.S.rows();
    symmetry.validate("Shooting::half_period_symmetry", n);
    sym_ = std::move(symmetry);
  }
  /// Shoot on the full period again.
  void clear_half_period_symmetry() { sym_.reset(); }
  /// The half-period symmetry in use, nullptr when none.
  const HalfPeriodSymmetry<System>* half_period_symmetry() const { return sym_ ? &*sym_ : nullptr; }

  /// One orbit run from (mode, t0, x0), with its sensitivity when `sensitivity`: run_period
  /// over `period`; with a half-period symmetry over period / 2 with its end mirrored,
  ///
  ///     x_end <- c + S (x_end - c),  monodromy <- S dx(t0 + T/2)/dx(t0),  mode_end <- mode_image(mode_end),
  ///
  /// so that x_end = x0 and mode_end = mode hold on the symmetric orbits. Throws like run_period.
  PeriodRun<System> run_orbit(const Mode& mode, Scalar t0, const State& x0, Scalar period, bool sensitivity) {
    if (!sym_) return run_period(sys_, mode, t0, x0, period, opt_, sensitivity);
    require_symmetry_size("Shooting::half_period_symmetry", x0.size());
    PeriodRun<System> run = run_period(sys_, mode, t0, x0, period / 2, opt_, sensitivity);
    if (!run.ok()) return run;
    run.x_end = sym_->mirror(run.x_end);
    if (run.monodromy.size()) run.monodromy = sym_->S * run.monodromy;
    run.mode_end = sym_->mirror_mode(run.mode_end);
    return run;
  }

  /// The forced orbit of period `period` through (mode, t0) starting from the guess x0.
  /// Throws std::invalid_argument for empty/non-finite x0, non-finite t0, period <= 0 or
  /// invalid options (or symmetry).
  Orbit forced(const Mode& mode, Scalar t0, const State& x0, Scalar period) {
    return solve(mode, t0, x0, period, false);
  }

  /// The autonomous orbit through (mode, x0 guess) with period guess `period` (t0 = 0).
  /// Throws like forced(), and with a half-period symmetry set (not supported).
  Orbit autonomous(const Mode& mode, const State& x0, Scalar period) {
    if (sym_)
      throw std::invalid_argument("Shooting::autonomous: a half-period symmetry is not supported (clear it)");
    return solve(mode, Scalar(0), x0, period, true);
  }

  /// The orbit data (monodromy block, multipliers, amplitudes, events) of a run of run_orbit()
  /// that closes; status Converged, or ModeNotPeriodic when the end mode differs from `mode`.
  /// With a half-period symmetry: half_period_map = H (the run's block), monodromy = H^2, and
  /// amplitudes, outputs, events and stats from one more (plain) run of the full period, which
  /// must close as well (ModeNotPeriodic otherwise: an event at t0 + T/2).
  /// Used by Continuation.
  Orbit make_orbit(const PeriodRun<System>& run, const Mode& mode, Scalar t0, const State& x0,
                   Scalar period, bool autonomous, Scalar residual, int iterations) const;

  /// max_i |x_end_i - x0_i| over the periodic components, and the residual vector r.
  Scalar residual(const State& x_end, const State& x0, Vector& r) const {
    const auto P = opt_.periodic_indices(x0.size());
    r.resize(static_cast<Eigen::Index>(P.size()));
    for (std::size_t k = 0; k < P.size(); ++k)
      r[static_cast<Eigen::Index>(k)] = x_end[P[k]] - x0[P[k]];
    return r.size() ? r.cwiseAbs().maxCoeff() : Scalar(0);
  }
  /// The Newton tolerance at x0: options.tolerance * max(1, max_i |x0_i|), i periodic.
  Scalar tolerance_at(const State& x0) const {
    Scalar s = 1;
    for (Eigen::Index i : opt_.periodic_indices(x0.size())) s = std::max(s, std::abs(x0[i]));
    return opt_.tolerance * s;
  }
  /// M_PP: the rows and columns of the periodic components of a full monodromy M.
  Matrix periodic_block(const Matrix& M) const {
    const auto P = opt_.periodic_indices(M.rows());
    const auto p = static_cast<Eigen::Index>(P.size());
    Matrix B(p, p);
    for (Eigen::Index a = 0; a < p; ++a)
      for (Eigen::Index b = 0; b < p; ++b)
        B(a, b) = M(P[static_cast<std::size_t>(a)], P[static_cast<std::size_t>(b)]);
    return B;
  }

  /// The Newton step: dy = J^-1 rhs when J is regular to the monodromy's accuracy (1 / |J^-1|_1,
  /// estimated by the LU's rcond, above 1000 options.stepper.rtol); otherwise the minimum-norm
  /// least-squares dy = J^+ rhs (complete orthogonal decomposition, pivots below 1000 rtol
  /// dropped), the step across a family of orbits that moves the least. False when J is
  /// singular and rhs is not in its range (|J dy - rhs| > |rhs| / 2, max norms). Used by
  /// Continuation's corrector and start tangent too.
  bool newton_step(const Matrix& J, const Vector& rhs, Vector& dy) const;

 private:
  Orbit solve(const Mode& mode, Scalar t0, const State& x0, Scalar period, bool autonomous);

  System& sys_;
  ShootingOptions<Scalar> opt_;
  std::optional<HalfPeriodSymmetry<System>> sym_;  // empty: shoot on the full period
  // The symmetry (validated when set) acts on states of n entries.
  void require_symmetry_size(const std::string& where, Eigen::Index n) const {
    if (sym_->S.rows() != n)
      detail::throw_invalid(where, "S must have the state size " + std::to_string(n) + ", rows", sym_->S.rows());
  }
};

template <class System>
bool Shooting<System>::newton_step(const Matrix& J, const Vector& rhs, Vector& dy) const {
  const Scalar floor = Scalar(1000) * opt_.stepper.rtol;
  const Eigen::FullPivLU<Matrix> lu(J);
  // 1 / |J^-1|_1 (estimated by rcond) above 1000 rtol: regular. (A relative test is not enough:
  // the entries of M - I can all be round-off.)
  if (lu.isInvertible() && lu.rcond() * J.cwiseAbs().colwise().sum().maxCoeff() > floor) {
    dy = lu.solve(rhs);
    return true;
  }
  // Singular to the accuracy of M: the minimum-norm least-squares step, pivots below 1000 rtol
  // dropped. A family of orbits (e.g. a damper stuck all period: any stuck offset repeats)
  // leaves the residual in the range of J and the step moves across the family the least;
  // a residual outside the range (resonance without damping) has no Newton step.
  Eigen::CompleteOrthogonalDecomposition<Matrix> cod(J);
  const Scalar largest = J.cwiseAbs().maxCoeff();
  cod.setThreshold(largest > floor ? floor / largest : Scalar(1));
  dy = cod.solve(rhs);
  return detail::all_finite(dy) &&
         (J * dy - rhs).cwiseAbs().maxCoeff() <= Scalar(0.5) * rhs.cwiseAbs().maxCoeff();
}

template <class System>
auto Shooting<System>::make_orbit(const PeriodRun<System>& run, const Mode& mode, Scalar t0,
                                  const State& x0, Scalar period, bool autonomous,
                                  Scalar residual, int iterations) const -> Orbit {
  Orbit o;
  o.t0 = t0;
  o.period = period;
  o.mode = mode;
  o.x0 = x0;
  o.residual = residual;
  o.iterations = iterations;
  o.monodromy = periodic_block(run.monodromy);
  if (sym_) {
    // M = H^2 over the whole state, then its periodic block: the components outside it (a
    // contact coordinate that moves while a damper slides) carry a perturbation from the first
    // half period into the second, which the square of H's periodic block would drop.
    o.half_period_map = o.monodromy;
    o.monodromy = periodic_block(run.monodromy * run.monodromy);
  }
  if (!detail::all_finite(o.monodromy)) {
    o.status = ShootingStatus::IntegrationFailed;
    o.message = "the monodromy matrix of the closing run is not finite (its variational run blew up)";
    return o;
  }
  o.floquet = floquet_multipliers<Scalar>(o.monodromy, autonomous, opt_.multiplier_tolerance);
  // With a symmetry the run covered half the period: the full period's signals from a plain run.
  PeriodRun<System> full;
  if (sym_) {
    full = run_period(sys_, mode, t0, x0, period, opt_, false);
    if (!full.ok()) {
      o.status = ShootingStatus::IntegrationFailed;
      o.message = "the full-period run of the symmetric orbit failed (" + std::string(to_string(full.status)) +
                  "): " + full.message;
      return o;
    }
  }
  const PeriodRun<System>& signals = sym_ ? full : run;
  o.amplitudes = signals.amplitudes;
  o.outputs = signals.outputs;
  o.events = signals.events;
  o.stats = signals.stats;
  if (!(run.mode_end == mode)) {
    o.status = ShootingStatus::ModeNotPeriodic;
    o.message = "x(t0 + T) = x(t0) to " + detail::format_value(residual) +
                " but the mode at t0 + T differs from the start mode (" +
                std::to_string(run.events.size()) +
                " events in the period): an event at the period start (the orbit starts on a "
                "switching surface: start it from another t0, away from its events; "
                "Continuation does so with ContinuationOptions::section_margin > 0), or the "
                "response is not periodic with this period";
    return o;
  }
  if (sym_) {
    // The symmetric problem closed at t0 + T/2; the full period must close too. It does not
    // where the run to t0 + T/2 decides an event that a run through t0 + T/2 does not make: a
    // switching surface or a grazing at the mirror point, or a guard's excursion inside one long
    // step (a time-driven guard over a constant state). Bound: the half-period residual carried
    // over the second half by H (|H|_inf), plus the runs' integration error, 100 times.
    Vector rf;
    const Scalar closing = this->residual(full.x_end, x0, rf);
    const Scalar allowed =
        Scalar(100) * (Scalar(2) + o.half_period_map.cwiseAbs().rowwise().sum().maxCoeff()) * tolerance_at(x0);
    if (!(full.mode_end == mode && closing <= allowed)) {
      o.status = ShootingStatus::ModeNotPeriodic;
      o.message = "the symmetric orbit closes at t0 + T/2 to " + detail::format_value(residual) +
                  " but the full period does not (max |x(t0 + T) - x(t0)| = " + detail::format_value(closing) +
                  (full.mode_end == mode ? std::string() : std::string(", and the mode at t0 + T differs")) +
                  "): the run to t0 + T/2 and a run through it see different events - a guard crossed and "
                  "recrossed inside one step (bound options.stepper.max_step or set stepper.guard_samples), or "
                  "an event at the mirror point t0 + T/2 (start it from another t0: "
                  "ContinuationOptions::section_margin > 0)";
      return o;
    }
  }
  o.status = ShootingStatus::Converged;
  return o;
}

template <class System>
auto Shooting<System>::solve(const Mode& mode, Scalar t0, const State& x0, Scalar period,
                             bool autonomous) -> Orbit {
  static const std::string where = "Shooting";
  const Eigen::Index n = x0.size();
  if (n == 0) throw std::invalid_argument(where + ": x0 must not be empty");
  if (!detail::all_finite(x0)) throw std::invalid_argument(where + ": x0 must be finite");
  detail::require_finite(where, "t0", t0);
  detail::require_positive(where, "period", period);
  opt_.validate(where, n);
  detail::require_resolved_period(where, "period", t0, period, opt_.stepper);
  if (sym_) require_symmetry_size(where + "::half_period_symmetry", n);

  const auto P = opt_.periodic_indices(n);
  const auto p = static_cast<Eigen::Index>(P.size());
  const Eigen::Index m = autonomous ? p + 1 : p;
  State x = x0;
  Scalar T = period;
  Vector r, rhs(m), dy(m);
  Matrix J(m, m);
  State f0 = x0, fT = x0;
  Orbit failed;  // the last Newton iterate, also when the first run fails
  failed.t0 = t0;
  failed.mode = mode;
  failed.x0 = x0;
  failed.period = period;
  int runs = 0;
  auto run_failed = [&](const PeriodRun<System>& run, int it) {
    failed.iterations = runs;
    failed.stats = run.stats;
    failed.status = ShootingStatus::IntegrationFailed;
    failed.message = "orbit run of Newton iteration " + std::to_string(it) + " failed (" +
                     to_string(run.status) + "): " + run.message;
    return failed;
  };
  const double cpu0 = detail::thread_cpu_seconds();  // ShootingOptions::progress's clock
  PeriodRun<System> run = run_orbit(mode, t0, x, T, true);
  ++runs;
  if (!run.ok()) return run_failed(run, 0);
  Scalar res = residual(run.x_end, x, r);
  StallEvidence<Scalar> evidence;  // what the runs show when Newton stalls
  evidence.note_run(t0, T, run.events, run.grazing_events);
  double res_before = -1;  // the residual one iteration earlier (the contraction rate)
  for (int it = 1;; ++it) {
    if (opt_.progress) {
      ShootingProgress pr;
      pr.iteration = it - 1;
      pr.max_iterations = opt_.max_iterations;
      pr.runs = runs;
      pr.residual = static_cast<double>(res);
      pr.tolerance = static_cast<double>(tolerance_at(x));
      pr.cpu_seconds = detail::thread_cpu_seconds() - cpu0;
      pr.remaining_seconds = detail::newton_remaining(pr.residual, res_before, pr.tolerance,
                                                      opt_.max_iterations - (it - 1),
                                                      pr.cpu_seconds / it);
      opt_.progress(pr);
    }
    res_before = static_cast<double>(res);
    failed.x0 = x;
    failed.period = T;
    failed.iterations = runs;
    failed.stats = run.stats;
    failed.residual = res;
    if (res <= tolerance_at(x)) {
      if (autonomous) {
        // An equilibrium closes for any T: the phase condition f(x0)^T dx = 0 is empty there and
        // the "period" is only the guess. Not an orbit when the flow moves x0 by less than the
        // tolerance in a period.
        sys_.rhs(mode, t0, x, f0);
        Scalar speed = 0;
        for (Eigen::Index i : P) speed = std::max(speed, std::abs(f0[i]));
        if (speed * T <= tolerance_at(x)) {
          failed.status = ShootingStatus::NoConvergence;
          failed.message = "Newton converged to an equilibrium, not a periodic orbit: max |f_P(x0)| T = " +
                           detail::format_value(speed * T) + " <= tolerance " +
                           detail::format_value(tolerance_at(x)) +
                           " (the phase condition is empty there and the period is undefined)";
          return failed;
        }
      }
      return make_orbit(run, mode, t0, x, T, autonomous, res, runs);
    }
    if (it > opt_.max_iterations) {
      failed.status = ShootingStatus::NoConvergence;
      failed.message = "Newton did not converge in " + std::to_string(opt_.max_iterations) +
                       " iterations: residual " + detail::format_value(res) + " > tolerance " +
                       detail::format_value(tolerance_at(x)) + "; detected: " +
                       evidence.describe(false);
      return failed;
    }
    J.setZero();
    J.topLeftCorner(p, p) = periodic_block(run.monodromy) - Matrix::Identity(p, p);
    rhs.head(p) = -r;
    if (autonomous) {
      sys_.rhs(mode, t0, x, f0);
      sys_.rhs(run.mode_end, t0 + T, run.x_end, fT);
      for (Eigen::Index k = 0; k < p; ++k) {
        J(k, p) = fT[P[static_cast<std::size_t>(k)]];
        J(p, k) = f0[P[static_cast<std::size_t>(k)]];
      }
      rhs[p] = 0;
    }
    if (!newton_step(J, rhs, dy)) {
      failed.status = ShootingStatus::SingularJacobian;
      failed.message = "the Newton matrix is singular at iteration " + std::to_string(it) +
                       " (residual " + detail::format_value(res) +
                       ", not in its range): a Floquet multiplier is 1 (a fold, or an undamped "
                       "system whose periodic orbits are not isolated)";
      return failed;
    }
    // Backtracking: the full step unless it does not lower the residual (a switch crossed the
    // ends of the period, or the period went out of range); halve it down to 1/32, then take it.
    for (Scalar lambda = 1;; lambda /= 2) {
      State xt = x;
      for (Eigen::Index k = 0; k < p; ++k) xt[P[static_cast<std::size_t>(k)]] += lambda * dy[k];
      const Scalar Tt = autonomous ? T + lambda * dy[p] : T;
      const bool last = lambda < Scalar(1) / Scalar(32);
      if (!(Tt > 0)) {
        if (!last) continue;
        failed.status = ShootingStatus::NoConvergence;
        failed.message = "the period became " + detail::format_value(Tt) +
                         " at Newton iteration " + std::to_string(it) + " (residual " +
                         detail::format_value(res) + ")";
        return failed;
      }
      PeriodRun<System> trial = run_orbit(mode, t0, xt, Tt, true);
      ++runs;
      if (!trial.ok()) {
        if (!last && !trial.interrupted) continue;
        return run_failed(trial, it);
      }
      Vector rt;
      const Scalar res_t = residual(trial.x_end, xt, rt);
      if (res_t < res || last) {
        evidence.note_run(t0, Tt, trial.events, trial.grazing_events);
        if (!(res_t < res)) evidence.note_residual(res, res_t);
        x = xt;
        T = Tt;
        run = std::move(trial);
        res = res_t;
        r = rt;
        break;
      }
    }
  }
}

}  // namespace stickslip

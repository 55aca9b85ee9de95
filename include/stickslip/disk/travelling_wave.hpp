#pragma once
/// \file travelling_wave.hpp
/// \brief Travelling-wave steady states of a tuned bladed disk under engine-order forcing as
/// relative periodic orbits: the annulus integrated over the shift time tau only, closed by the
/// cyclic index shift S, x(t0 + tau) = S x(t0), by Newton's method; Floquet multipliers of the
/// travelling wave and of the full period, and an optional full-annulus check (docs/disks.md).

#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/disk/cyclic_shift.hpp"
#include "stickslip/modal/modal_basis.hpp"
#include "stickslip/steady_state/floquet.hpp"
#include "stickslip/steady_state/period_run.hpp"
#include "stickslip/steady_state/shooting.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// The state map of a travelling wave on a ContactSystem scene of a tuned disk: S over the whole
/// state [q, bodies, q', bodies', audit] and the matching permutation of the contacts' states.
/// Bodies and contacts are numbered sector by sector (body k b_s + j, contact k c_s + j: as
/// neighbour_wedge_dampers and neighbour_joints give them).
template <class Scalar>
struct TravellingWaveShift {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  ///< dense matrix
  EngineOrderSymmetry symmetry;       ///< sigma, L = T / tau
  Matrix state;                       ///< S: (S x)_k = x_{k + sigma}; the audit integrals unchanged
  std::vector<Eigen::Index> contact_source;  ///< the shifted mode's contact i is contact_source[i] of the mode
  /// The mode S m: contact i takes the state of contact_source[i].
  template <class Mode>
  Mode shifted(const Mode& m) const {
    Mode out = m;
    for (std::size_t i = 0; i < contact_source.size(); ++i)
      out[static_cast<Eigen::Index>(i)] = m[contact_source[i]];
    return out;
  }
  /// The mode m with shifted(m) = `image` (the inverse permutation).
  template <class Mode>
  Mode unshifted(const Mode& image) const {
    Mode m = image;
    for (std::size_t i = 0; i < contact_source.size(); ++i) m[contact_source[i]] = image[static_cast<Eigen::Index>(i)];
    return m;
  }
};

/// The shift of `system` (a ContactSystem over disk.frame() and `basis`, its bodies and contacts
/// numbered sector by sector, its loads engine order `engine_order`) for the symmetry
/// engine_order_symmetry(engine_order, N): the modal block modal_cyclic_shift(disk, basis, sigma)
/// on q and q', the permutation of bodies and contacts.
/// \throws std::invalid_argument naming the parameter: a number of bodies or contacts that is not
///         a multiple of num_sectors (system), and modal_cyclic_shift's refusals (basis, disk).
template <class Scalar, class System>
TravellingWaveShift<Scalar> travelling_wave_shift(const BladedDisk<Scalar>& disk, const ModalBasis<Scalar>& basis,
                                                  const System& system, Eigen::Index engine_order) {
  static const char* where = "travelling_wave_shift";
  using Index = Eigen::Index;
  const Index N = disk.num_sectors();
  if (system.num_bodies() % N != 0)
    detail::throw_invalid(where, "system must hold a multiple of num_sectors bodies; num_bodies", system.num_bodies());
  if (system.num_contacts() % N != 0)
    detail::throw_invalid(where, "system must hold a multiple of num_sectors contacts; num_contacts",
                          system.num_contacts());
  if (system.num_modes() != basis.size())
    detail::throw_invalid(where, "system must use basis (its modes); num_modes", system.num_modes());
  TravellingWaveShift<Scalar> s;
  s.symmetry = engine_order_symmetry(engine_order, N);
  const Index sigma = s.symmetry.sector_shift;
  const auto Sq = modal_cyclic_shift(disk, basis, sigma);
  const Index n = system.num_modes(), m = system.num_coordinates(), size = system.state_size();
  s.state = TravellingWaveShift<Scalar>::Matrix::Identity(size, size);
  const Index bs = system.num_bodies() / N;
  for (Index half : {Index(0), m}) {
    s.state.block(half + n, half + n, m - n, m - n).setZero();
    s.state.block(half, half, n, n) = Sq;
    for (Index k = 0; k < N; ++k)
      for (Index j = 0; j < bs; ++j)
        for (Index c = 0; c < 3; ++c)
          s.state(half + n + 3 * (k * bs + j) + c, half + n + 3 * (((k + sigma) % N) * bs + j) + c) = Scalar(1);
  }
  const Index cs = system.num_contacts() / N;
  s.contact_source.resize(static_cast<std::size_t>(system.num_contacts()));
  for (Index k = 0; k < N; ++k)
    for (Index j = 0; j < cs; ++j) s.contact_source[static_cast<std::size_t>(k * cs + j)] = ((k + sigma) % N) * cs + j;
  return s;
}

/// Options of TravellingWaveShooting.
template <class Scalar>
struct TravellingWaveOptions {
  /// Runs, Newton tolerance and iterations, monodromy method, amplitude components (as Shooting;
  /// `periodic` empty: the mechanical states, every component but the system's audit integrals).
  ShootingOptions<Scalar> shooting;
  /// Also integrate the converged orbit over the full period T with its monodromy (the
  /// full-annulus Floquet check: about L times the cost of one travelling-wave run).
  bool full_annulus_check = false;
  /// How often solve() repeats a solve whose state closes but whose start mode the orbit does not
  /// reproduce, from the mode the run ends in shifted back (>= 0; 0: report ModeNotPeriodic).
  int mode_retries = 3;
  /// When Newton from the guess fails (no convergence, a singular matrix, a start mode the orbit
  /// does not reproduce), the annulus is integrated this many forcing periods from the guess, a
  /// transient toward the response that attracts it (about settle_periods L runs over tau
  /// without sensitivities), and the solve repeated from where it ends, at t0 again (the
  /// engine-order forcing is T-periodic). Far from the orbit (the stuck closed form under a
  /// preload the dampers slip at) Newton's steps cross stick-slip boundaries and stall where a
  /// short transient lands close enough for it. 0: never (>= 0).
  int settle_periods = 40;
  /// With settle_periods > 0: the Newton iterations from the guess before the settling transient
  /// is tried (a Newton that needs more is crossing stick-slip boundaries, not converging); the
  /// solve after it has shooting.max_iterations (>= 1).
  int settle_after = 8;
};

/// Which Floquet analysis a travelling-wave orbit carries.
enum class FloquetCheck : std::uint8_t {
  TravellingWave,  ///< from the run over tau only (M_T = S^L A^L)
  FullAnnulus      ///< and from an independent run of the annulus over T
};

/// A travelling-wave orbit (or the last Newton iterate when it failed).
template <class System>
struct TravellingWaveOrbit {
  using Scalar = typename System::Scalar;  ///< floating-point type
  using State = typename System::State;    ///< state
  using Mode = typename System::Mode;      ///< mode
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  ///< dense matrix

  ShootingStatus status = ShootingStatus::NoConvergence;  ///< how the solve ended
  std::string message;          ///< empty when converged; otherwise what failed
  Scalar t0 = 0;                ///< start time
  Scalar period = 0;            ///< T of the forcing
  Scalar shift_time = 0;        ///< tau = T / L
  EngineOrderSymmetry symmetry; ///< sigma and L
  Mode mode{};                  ///< mode at t0 (at t0 + tau: its shift)
  State x0;                     ///< the orbit's state at t0
  Scalar residual = 0;          ///< max |x_P(t0 + tau) - (S x0)_P|
  int iterations = 0;           ///< runs over tau made (Newton iterations and backtracking trials)
  /// Forcing periods of the settling transient (options.settle_periods) the last solve started
  /// from; 0: it started from the guess.
  int settled_periods = 0;
  /// A = S_PP^T dx_P(t0 + tau)/dx_P(t0) (S orthogonal): the linearised map of one shift.
  Matrix shift_map;
  /// Eigenvalues of A. The full-period multipliers are omega_j lambda_j^L with omega_j roots of
  /// unity of S^L: same stability, moduli |lambda_j|^L.
  FloquetMultipliers<Scalar> shift_multipliers;
  /// Multipliers of the full-period monodromy M_T = S_PP^L A^L (exact by the symmetry: the
  /// flow from t + tau maps S y as S maps the flow from t). The run over tau integrates the whole
  /// annulus, so A carries every perturbation, symmetric or not.
  FloquetMultipliers<Scalar> floquet;
  /// max |x_i| over [t0, t0 + tau] of the amplitude components (over a period, blade k's
  /// maximum is the largest over blades k, k + sigma, ... of these).
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> amplitudes;
  std::vector<OrbitEvent<Scalar, Mode>> events;  ///< events in (t0, t0 + tau]
  StepperStats stats;           ///< counters of the last run over tau

  FloquetCheck check = FloquetCheck::TravellingWave;  ///< which analysis was done
  Scalar full_residual = 0;     ///< full-annulus check: max |x_P(t0 + T) - x_P(t0)|
  bool full_mode_closes = false;  ///< full-annulus check: the mode at t0 + T is the start mode
  FloquetMultipliers<Scalar> full_floquet;  ///< full-annulus check: multipliers of its M_T
  StepperStats full_stats;      ///< full-annulus check: counters of its run
  double full_seconds = 0;      ///< full-annulus check: wall time of its run [s]

  /// status == ShootingStatus::Converged.
  bool ok() const noexcept { return status == ShootingStatus::Converged; }
};

/// Travelling-wave orbits of a tuned disk's ContactSystem under engine-order forcing, as relative
/// periodic orbits: Newton's method on
///
///     G(x0) = x_P(t0 + tau; x0) - (S x0)_P = 0,   dG/dx0 = M_PP(tau) - S_PP,
///
/// with the runs and the monodromy of run_period and Shooting's Newton step (minimum-norm when
/// the matrix is singular to the monodromy's accuracy) and backtracking. The start mode is kept;
/// the mode at t0 + tau must be its shift. The runs cost tau = T / L of the annulus: for EO
/// coprime with N, T / N, about one sector over a period.
template <class System>
class TravellingWaveShooting {
 public:
  using Scalar = typename System::Scalar;  ///< floating-point type
  using State = typename System::State;    ///< state
  using Mode = typename System::Mode;      ///< mode
  using Orbit = TravellingWaveOrbit<System>;  ///< result
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;  ///< dense matrix
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;               ///< dense vector

  /// Keeps a reference to `system`. \throws std::invalid_argument naming the parameter: a shift
  /// whose size is not the system's state size (shift.state) or whose contact permutation does
  /// not match its contacts (shift.contact_source), or invalid options.
  TravellingWaveShooting(System& system, TravellingWaveShift<Scalar> shift, TravellingWaveOptions<Scalar> options = {})
      : sys_(system), shift_(std::move(shift)), opt_(std::move(options)) {
    static const char* where = "TravellingWaveShooting";
    const Eigen::Index n = system.state_size();
    if (shift_.state.rows() != n || shift_.state.cols() != n)
      detail::throw_invalid(where, "shift.state must be state_size() square; rows", shift_.state.rows());
    if (static_cast<Eigen::Index>(shift_.contact_source.size()) != system.num_contacts())
      detail::throw_invalid(where, "shift.contact_source must have one entry per contact; size",
                            shift_.contact_source.size());
    if (opt_.shooting.periodic.empty()) opt_.shooting.periodic = ShootingOptions<Scalar>::first(2 * system.num_coordinates());
    opt_.shooting.validate(where, n);
    if (opt_.mode_retries < 0) detail::throw_invalid(where, "options.mode_retries must be >= 0; mode_retries", opt_.mode_retries);
    if (opt_.settle_periods < 0)
      detail::throw_invalid(where, "options.settle_periods must be >= 0; settle_periods", opt_.settle_periods);
    if (opt_.settle_after < 1)
      detail::throw_invalid(where, "options.settle_after must be >= 1; settle_after", opt_.settle_after);
  }

  /// The options in use (periodic filled in).
  const TravellingWaveOptions<Scalar>& options() const noexcept { return opt_; }
  /// The shift in use.
  const TravellingWaveShift<Scalar>& shift() const noexcept { return shift_; }

  /// The travelling wave of forcing period `period` through (mode, t0), from the guess x0.
  /// \throws std::invalid_argument for an empty or non-finite x0, non-finite t0, period <= 0,
  ///         or a system without the shift's symmetry at (mode, t0) (its loads not the engine
  ///         order's, or the disk mistuned): rhs(S m, t0 + tau, S x) != S rhs(m, t0, x).
  /// A start mode that the converged state does not reproduce (x(t0 + tau) = S x(t0) but the
  /// mode at t0 + tau is not S mode: the guess's stick/slip pattern was not the orbit's) is
  /// replaced by the one the run ends in, shifted back (S^-1 mode(t0 + tau)), and the solve
  /// repeated from the converged state, at most options().mode_retries times. A solve that still
  /// fails (not by a failed run; after options().settle_after iterations when settling is on) is
  /// repeated once from the end of a settling transient of options().settle_periods periods from
  /// the guess (orbit.settled_periods says so).
  Orbit solve(const Mode& mode, Scalar t0, const State& x0, Scalar period);

 private:
  // Newton in `mode` (and its retries) with at most max_iterations iterations.
  Orbit solve_in_mode(const Mode& mode, Scalar t0, const State& x0, Scalar period, Scalar tau, int max_iterations);
  Orbit solve_with_retries(const Mode& mode, Scalar t0, const State& x0, Scalar period, Scalar tau,
                           int max_iterations);

  void require_symmetry(const Mode& mode, Scalar t0, const State& x0, Scalar tau);
  Scalar residual(const State& x_end, const State& x0, Vector& r) const {
    const State sx = shift_.state * x0;
    return shooter().residual(x_end, sx, r);
  }
  Shooting<System> shooter() const { return Shooting<System>(sys_, opt_.shooting); }
  Matrix periodic_shift() const { return shooter().periodic_block(shift_.state); }
  Orbit finish(const PeriodRun<System>& run, Orbit o) const;

  System& sys_;
  TravellingWaveShift<Scalar> shift_;
  TravellingWaveOptions<Scalar> opt_;
};

template <class System>
void TravellingWaveShooting<System>::require_symmetry(const Mode& mode, Scalar t0, const State& x0, Scalar tau) {
  State a(x0.size()), b(x0.size());
  const Mode sm = shift_.shifted(mode);
  for (const State& x : {x0, State(State::Zero(x0.size()))}) {
    sys_.rhs(mode, t0, x, a);
    const State expected = shift_.state * a;
    sys_.rhs(sm, t0 + tau, State(shift_.state * x), b);
    // Round-off of the dense modal shift on the largest terms (omega^2 q): 1e-8 of their size.
    const Scalar scale = std::max(expected.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
    const Scalar defect = (b - expected).cwiseAbs().maxCoeff();
    if (!(defect <= Scalar(1e-8) * scale))
      detail::throw_invalid("TravellingWaveShooting",
                            "system must have the shift's symmetry, rhs(S m, t0 + tau, S x) = S rhs(m, t0, x) "
                            "(engine-order loads of the shift's order on a tuned disk); relative defect",
                            scale > 0 ? defect / scale : defect);
  }
}

template <class System>
auto TravellingWaveShooting<System>::finish(const PeriodRun<System>& run, Orbit o) const -> Orbit {
  const Matrix S = periodic_shift();
  const Matrix M = shooter().periodic_block(run.monodromy);
  o.amplitudes = run.amplitudes;
  o.events = run.events;
  o.stats = run.stats;
  if (!detail::all_finite(M)) {
    o.status = ShootingStatus::IntegrationFailed;
    o.message = "the monodromy of the closing run is not finite (its variational run blew up)";
    return o;
  }
  o.shift_map = S.transpose() * M;
  const Scalar tol = opt_.shooting.multiplier_tolerance;
  o.shift_multipliers = floquet_multipliers<Scalar>(o.shift_map, false, tol);
  Matrix MT = Matrix::Identity(S.rows(), S.cols());
  for (Eigen::Index l = 0; l < o.symmetry.shifts_per_period; ++l) MT = o.shift_map * MT;
  for (Eigen::Index l = 0; l < o.symmetry.shifts_per_period; ++l) MT = S * MT;
  o.floquet = floquet_multipliers<Scalar>(MT, false, tol);
  if (run.mode_end != shift_.shifted(o.mode)) {
    o.status = ShootingStatus::ModeNotPeriodic;
    o.message = "x(t0 + tau) = S x(t0) to " + detail::format_value(o.residual) +
                " but the mode at t0 + tau is not the shifted start mode (" + run.mode_end.to_string() + " against " +
                shift_.shifted(o.mode).to_string() + "): the orbit starts on a switching surface, or the response "
                "is not a travelling wave";
    return o;
  }
  o.status = ShootingStatus::Converged;
  if (!opt_.full_annulus_check) return o;
  const auto start = std::chrono::steady_clock::now();
  const PeriodRun<System> full = run_period(sys_, o.mode, o.t0, o.x0, o.period, opt_.shooting, true);
  o.full_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  o.full_stats = full.stats;
  if (!full.ok()) {
    o.status = ShootingStatus::IntegrationFailed;
    o.message = "full-annulus check: the run over T failed (" + std::string(to_string(full.status)) + "): " + full.message;
    return o;
  }
  Vector r;
  o.full_residual = shooter().residual(full.x_end, o.x0, r);
  o.full_mode_closes = full.mode_end == o.mode;
  o.full_floquet = floquet_multipliers<Scalar>(shooter().periodic_block(full.monodromy), false, tol);
  o.check = FloquetCheck::FullAnnulus;
  return o;
}

template <class System>
auto TravellingWaveShooting<System>::solve(const Mode& mode, Scalar t0, const State& x0, Scalar period) -> Orbit {
  static const std::string where = "TravellingWaveShooting";
  const Eigen::Index n = x0.size();
  if (n != sys_.state_size()) detail::throw_invalid(where, "x0 must have state_size() entries; size", n);
  if (!detail::all_finite(x0)) throw std::invalid_argument(where + ": x0 must be finite");
  detail::require_finite(where, "t0", t0);
  detail::require_positive(where, "period", period);
  const Scalar tau = period / Scalar(shift_.symmetry.shifts_per_period);
  detail::require_resolved_period(where, "period", t0, tau, opt_.shooting.stepper);
  require_symmetry(mode, t0, x0, tau);
  const int all = opt_.shooting.max_iterations;
  Orbit o = solve_with_retries(mode, t0, x0, period, tau, opt_.settle_periods > 0 ? std::min(all, opt_.settle_after) : all);
  if (o.ok() || opt_.settle_periods == 0 || o.status == ShootingStatus::IntegrationFailed) return o;
  const int k = opt_.settle_periods;
  const PeriodRun<System> settle = run_period(sys_, mode, t0, x0, Scalar(k) * period, opt_.shooting, false);
  if (!settle.ok()) {
    o.message += " (a settling run of " + std::to_string(k) + " periods from the guess failed too (" +
                 to_string(settle.status) + "): " + settle.message + ")";
    return o;
  }
  const int runs = o.iterations;
  const std::string from_guess = o.message;
  o = solve_with_retries(settle.mode_end, t0, settle.x_end, period, tau, all);
  o.iterations += runs;
  o.settled_periods = k;
  if (!o.ok()) o.message += " (after settling " + std::to_string(k) + " periods; from the guess: " + from_guess + ")";
  return o;
}

template <class System>
auto TravellingWaveShooting<System>::solve_with_retries(const Mode& mode, Scalar t0, const State& x0, Scalar period,
                                                        Scalar tau, int max_iterations) -> Orbit {
  Orbit o = solve_in_mode(mode, t0, x0, period, tau, max_iterations);
  for (int retry = 0; retry < opt_.mode_retries && o.status == ShootingStatus::ModeNotPeriodic; ++retry) {
    const Mode next = shift_.unshifted(o.events.empty() ? o.mode : o.events.back().to);  // S^-1 (end mode)
    if (next == o.mode) break;
    const int runs = o.iterations;
    const std::string before = o.message;
    o = solve_in_mode(next, t0, o.x0, period, tau, max_iterations);
    o.iterations += runs;
    if (o.status == ShootingStatus::ModeNotPeriodic) o.message += " (after a retry from: " + before + ")";
  }
  return o;
}

template <class System>
auto TravellingWaveShooting<System>::solve_in_mode(const Mode& mode, Scalar t0, const State& x0, Scalar period,
                                                   Scalar tau, int max_iterations) -> Orbit {
  const Eigen::Index n = x0.size();
  const Shooting<System> sh = shooter();
  const auto P = opt_.shooting.periodic_indices(n);
  const auto p = static_cast<Eigen::Index>(P.size());
  const Matrix S = periodic_shift();
  Orbit o;
  o.t0 = t0;
  o.period = period;
  o.shift_time = tau;
  o.symmetry = shift_.symmetry;
  o.mode = mode;
  o.x0 = x0;
  auto failed_run = [&](const PeriodRun<System>& run, int it) {
    o.stats = run.stats;
    o.status = ShootingStatus::IntegrationFailed;
    o.message = "run over tau of Newton iteration " + std::to_string(it) + " failed (" + to_string(run.status) +
                "): " + run.message;
    return o;
  };
  State x = x0;
  PeriodRun<System> run = run_period(sys_, mode, t0, x, tau, opt_.shooting, true);
  o.iterations = 1;
  if (!run.ok()) return failed_run(run, 0);
  Vector r, dy(p), rhs(p);
  Scalar res = residual(run.x_end, x, r);
  for (int it = 1;; ++it) {
    o.x0 = x;
    o.residual = res;
    if (res <= sh.tolerance_at(x)) return finish(run, o);
    if (it > max_iterations) {
      o.status = ShootingStatus::NoConvergence;
      o.message = "Newton did not converge in " + std::to_string(max_iterations) +
                  " iterations: residual " + detail::format_value(res) + " > tolerance " +
                  detail::format_value(sh.tolerance_at(x));
      return o;
    }
    const Matrix J = sh.periodic_block(run.monodromy) - S;
    rhs = -r;
    if (!sh.newton_step(J, rhs, dy)) {
      o.status = ShootingStatus::SingularJacobian;
      o.message = "the Newton matrix M(tau) - S is singular at iteration " + std::to_string(it) + " (residual " +
                  detail::format_value(res) + ", not in its range)";
      return o;
    }
    // Backtracking as Shooting: the full step unless it does not lower the residual; halve it
    // down to 1/32, then take it.
    for (Scalar lambda = 1;; lambda /= 2) {
      State xt = x;
      for (Eigen::Index k = 0; k < p; ++k) xt[P[static_cast<std::size_t>(k)]] += lambda * dy[k];
      const bool last = lambda < Scalar(1) / Scalar(32);
      PeriodRun<System> trial = run_period(sys_, mode, t0, xt, tau, opt_.shooting, true);
      ++o.iterations;
      if (!trial.ok()) {
        if (!last && !trial.interrupted) continue;
        o.x0 = xt;
        return failed_run(trial, it);
      }
      Vector rt;
      const Scalar res_t = residual(trial.x_end, xt, rt);
      if (res_t < res || last) {
        x = xt;
        run = std::move(trial);
        res = res_t;
        r = rt;
        break;
      }
    }
  }
}

}  // namespace stickslip

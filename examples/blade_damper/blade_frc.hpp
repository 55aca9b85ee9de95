#pragma once
/// \file blade_frc.hpp
/// \brief The blade's frequency-response curves (`blade_damper --frc f_lo:f_hi`): forced periodic
/// orbits of the damped blade followed in the excitation frequency by pseudo-arclength
/// continuation (stickslip::Continuation) at each preload, with stability, regime and tip
/// amplitude per point, next to the two linear limits in closed form (all dampers stuck; no
/// friction, mu = 0); and the optimal preload (`--optimise-preload`). docs/howto/frequency_response.md.

#include "blade_regime.hpp"
#include "frc_peak.hpp"
#include "blade_scene.hpp"
#include "blade_sweep.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/steady_state.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace blade {

/// Mass and stiffness of the blade reduced on its retained modes with every damper stuck to the
/// platform (M = I + sum m (b b^T [+ a a^T, inertial normal load]), K = Omega^2 + sum k b b^T;
/// a, b the modal shapes of the contact point across and along the platform) or, `stuck` false,
/// with frictionless dampers (mu = 0: M = I [+ sum m a a^T], K = Omega^2; the dampers' own
/// oscillation x'' = -k x / m is not excited).
inline void linear_matrices(BladeScene& scene, bool stuck, Eigen::MatrixXd& M, Eigen::MatrixXd& K) {
  using stickslip::LoadDirection;
  const auto& sys = *scene.system;
  const Eigen::Index n = scene.basis.size();
  M = Eigen::MatrixXd::Identity(n, n);
  K = sys.omega_squared().asDiagonal();
  for (const auto& d : sys.dampers()) {
    const Eigen::VectorXd a = sys.point_shape(d.member, d.contact_coordinate, LoadDirection::Transverse);
    const Eigen::VectorXd b = sys.point_shape(d.member, d.contact_coordinate, LoadDirection::Axial);
    const double m = d.effective_mass();
    if (sys.options().normal_load == stickslip::NormalLoad::Inertial) M += m * a * a.transpose();
    if (!stuck) continue;
    M += m * b * b.transpose();
    K += d.effective_stiffness() * b * b.transpose();
  }
}

/// A linear limit of the blade as the model has it: the exact linear part x_L' = A x_L + b(t)
/// (FrictionDampedSystem::linear_part) of `system` in `mode` at rest, b(t) = bc cos(w t) +
/// bs sin(w t) from the harmonic load (its shape does not depend on w).
struct LinearLimit {
  Eigen::MatrixXd A;
  Eigen::VectorXcd forcing;  ///< bc - i bs: b(t) = Re(forcing e^{i w t})
  Eigen::Index modes = 0;
  /// |lambda| / 2 pi [Hz] of the oscillatory eigenvalues of A (Im lambda > 1e-6 |lambda|: not the
  /// zero eigenvalues of the stuck family or of the frozen contact coordinates, which round-off
  /// splits into tiny complex pairs: |lambda| > 1e-6 max |lambda| too), ascending: the
  /// undamped natural frequencies of the limit's modes.
  std::vector<double> natural_frequencies_hz() const {
    const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
    const double scale = ev.cwiseAbs().maxCoeff();
    std::vector<double> f;
    for (Eigen::Index k = 0; k < ev.size(); ++k)
      if (ev[k].imag() > 1e-6 * std::abs(ev[k]) && std::abs(ev[k]) > 1e-6 * scale)
        f.push_back(std::abs(ev[k]) / (2 * M_PI));
    std::sort(f.begin(), f.end());
    return f;
  }
  /// Complex state amplitudes X = (i w I - A)^-1 (bc - i bs): the steady state x_L = Re(X e^{i w t}).
  Eigen::VectorXcd response(double omega) const {
    using cd = std::complex<double>;
    Eigen::MatrixXcd D = -A.cast<cd>();
    D.diagonal().array() += cd(0, omega);
    return D.partialPivLu().solve(forcing);
  }
};

/// The linear limit of `system` in `mode` (see LinearLimit).
inline LinearLimit linear_limit(BladeScene::System& system, const BladeScene::System::Mode& mode) {
  stickslip::LinearPart<double> lp;
  if (!system.linear_part(mode, 0.0, system.initial_state(), lp) || lp.omega.size() != 1)
    throw std::runtime_error("frc: the linear part at rest is not available");
  LinearLimit l;
  l.A = lp.A;
  l.forcing = lp.bc.col(0).cast<std::complex<double>>() - std::complex<double>(0, 1) * lp.bs.col(0).cast<std::complex<double>>();
  l.modes = system.num_modes();
  return l;
}

/// The two linear limits of the scene: every damper stuck (the model's Stick mode, exact) and no
/// friction (mu_s = mu_k = 0, the dampers slipping: friction force 0).
inline std::array<LinearLimit, 2> blade_linear_limits(BladeScene& scene) {
  using stickslip::ContactState;
  BladeScene::System::Mode stuck(scene.system->num_dampers()), slip(scene.system->num_dampers());
  for (Eigen::Index i = 0; i < stuck.size(); ++i) {
    stuck[i] = ContactState::Stick;
    slip[i] = ContactState::SlipPositive;
  }
  BladeParameters p = scene.parameters;
  p.mu_s = p.mu_k = 0;
  BladeScene::System frictionless = make_blade_system(scene, p);
  return {linear_limit(*scene.system, stuck), linear_limit(frictionless, slip)};
}

/// Natural frequencies [rad/s] of a linear limit, ascending.
inline std::vector<double> linear_frequencies(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  std::vector<double> w;
  for (Eigen::Index j = 0; j < es.eigenvalues().size(); ++j) w.push_back(std::sqrt(std::max(0.0, es.eigenvalues()[j])));
  return w;
}

/// One point of a frequency-response curve (a converged orbit).
struct FrcPoint {
  double preload = 0;        ///< N0 [N]
  double omega = 0;          ///< excitation [rad/s]
  /// Half the tip's peak-to-peak over the orbit [m]: the amplitude comparable with the linear
  /// curves (a damper stuck all period holds the member at an offset: the orbit's mean tip
  /// deflection is not zero, max |tip| would add it).
  double tip_amplitude = 0;
  double tip_max_abs = 0;    ///< max |tip displacement| over the orbit [m]
  bool stable = true;
  std::string instability;   ///< "none", "fold", "period_doubling", "neimark_sacker"
  double max_multiplier = 0; ///< largest |mu|
  double stick_fraction[2] = {0, 0};       ///< per damper, over the period
  double switches_per_period[2] = {0, 0};  ///< per damper: its contact-state changes in a period
  std::string regime;        ///< the dampers' common regime (blade_regime.hpp), or "a / b"
  int iterations = 0;        ///< corrector iterations (orbit runs) of the point
  double residual = 0;       ///< |x_P(T) - x_P(0)| max norm
  double cpu_seconds = 0;    ///< CPU time since the previous point (or the branch start)
  /// The branch's (or its part's) CPU seconds so far and the estimate of what remains to the
  /// end of its range (stickslip::ContinuationProgress); -1: not from a continuation.
  double branch_cpu_seconds = -1, remaining_seconds = -1;
  /// 0: a point of the branch; k > 0: a separate segment of the curve, not connected to the
  /// branch - with --frc-parts, part k's own branch, which the joined branch never reached
  /// (stickslip::SplitContinuationResult::dropped: an earlier part ended first, e.g. at a
  /// nonsmooth point); then the restarts past a stall (FrcSettings::restarts), numbered on.
  int segment = 0;
  /// The orbit's period in forcing periods: 1, or k > 1 for a subharmonic orbit (period k T)
  /// found after a restart where the response repeats every k periods (FrcSettings::restarts),
  /// or born at a flip of a period-k T branch (period 2 k T).
  int period = 1;
  /// Which branch the point is on: "period_1" (the branch from f_lo and its parts),
  /// "subharmonic" (a restart's period-k T segment, k > 1), "restart" (a restart's period-1
  /// segment) or "period_doubled" (the period-2k T branch born at a flip of a period-k T one,
  /// stickslip::PeriodDoubling; FrcSettings::switch_points).
  std::string kind = "period_1";
};

/// Where a restart found no periodic response (stickslip::poincare_sections: no k <= 8): the
/// tip's half peak-to-peak in each recorded forcing period of the transient - a column of a
/// brute-force bifurcation diagram.
struct FrcPoincare {
  double frequency_hz = 0;
  std::vector<double> tip_amplitudes;  ///< per recorded period [m]
  double recurrence = 0;               ///< the smallest recurrence over k = 1..8 (relative)
};

/// A branch at one preload and how it ended.
struct FrcBranch {
  double preload = 0;
  std::string status;   ///< stickslip::ContinuationStatus name, or "start_failed" with the message
  std::string message;
  std::string monodromy;  ///< the monodromy method the branch used
  /// The linear limits at this preload (the damper mass m = 2 N0 / (r Omega^2) changes with it):
  /// rows (f [Hz], all-stuck tip, frictionless tip), and their natural frequencies [Hz].
  std::vector<std::array<double, 3>> linear;
  std::vector<double> stuck_hz, free_hz;
  double cpu_seconds = 0;   ///< CPU time of every thread that worked on the branch
  double wall_seconds = 0;  ///< elapsed time of the branch
  /// With FrcSettings::parts > 1: per part, its start (start_parameter: the frequency in Hz),
  /// the points kept and whether it joined the next (stickslip::SplitContinuation).
  std::vector<stickslip::ContinuationPart<double>> parts;
  int restarts = 0;  ///< restart attempts past a stall, failed starts included (FrcSettings::restarts)
  std::vector<FrcPoint> points;
  /// The restarts' frequencies where the response was not periodic (FrcSettings::restarts).
  std::vector<FrcPoincare> not_periodic;
  /// Where a Floquet multiplier crossed the unit circle along the branch and its segments
  /// (stickslip::locate_bifurcations): kind ("fold", "pitchfork": through +1 without a turn of
  /// the branch, i.e. symmetry breaking; "period_doubling"; "neimark_sacker"), the frequency
  /// [Hz] interpolated to |mu| = 1, and whether the orbit lost stability there.
  struct Bifurcation {
    std::string kind;
    double frequency_hz = 0;
    bool destabilising = true;
    /// At a period doubling: the period-2T branch started there ("period-2T branch, segment n:
    /// m points, <status>") or why it was not (FrcSettings::switch_points).
    std::string switched;
  };
  std::vector<Bifurcation> bifurcations;
  /// The period-doubled branches' points (kind "period_doubled"), kept apart until the restarts
  /// are done (they do not count as computed spans there), then appended to `points`.
  std::vector<FrcPoint> switched;
  /// Points in separate segments (FrcPoint::segment > 0).
  std::size_t separate_points() const {
    return static_cast<std::size_t>(
        std::count_if(points.begin(), points.end(), [](const FrcPoint& f) { return f.segment > 0; }));
  }
};

/// Stick fraction and switches of damper i over one period of an orbit
/// (stickslip::orbit_contact_statistics).
inline void damper_period_statistics(const stickslip::PeriodicOrbit<BladeScene::System>& orbit,
                                     Eigen::Index i, double& stick_fraction, double& switches) {
  const auto s = stickslip::orbit_contact_statistics(orbit, i);
  stick_fraction = s.stick_fraction;
  switches = s.switches;
}

/// Observer of the tip displacement's extremes (steps, samples, events).
struct TipObserver : stickslip::NullObserver {
  const BladeScene* scene = nullptr;
  double lo = 0, hi = 0;
  bool seen = false;
  template <class X, class M>
  bool on_step(double, const X& x, const M&) {
    const double tip = scene->tip_displacement(x);
    lo = seen ? std::min(lo, tip) : tip;
    hi = seen ? std::max(hi, tip) : tip;
    seen = true;
    return true;
  }
  template <class X, class M>
  bool on_sample(double t, const X& x, const M& m) { return on_step(t, x, m); }
};

/// The tip displacement as output 0 of every orbit (stickslip::ShootingOptions::outputs): its
/// extremes, mean and harmonics over the orbit's own period, from the run that closed the orbit
/// (an unstable orbit is measured where it is, not where a later run would drift), sampled 512
/// times a period (a sampled sine is short of its peak by at most 1 - cos(pi / 512) = 2e-5 of
/// the amplitude).
inline void add_tip_output(const BladeScene& scene, stickslip::ShootingOptions<double>& opt) {
  const Eigen::Index n = scene.system->initial_state().size();
  opt.outputs = Eigen::MatrixXd::Zero(1, n);
  opt.outputs.row(0).head(scene.tip_shape.size()) = scene.tip_shape.transpose();
  opt.samples_per_period = 512;
}

/// The tip's extremes over the period [t0, t0 + T] of a run from (mode, t0, x0) (samples every
/// T / 512): for a transient's next period, where there is no converged orbit. An orbit's own
/// extremes are its output 0 (add_tip_output). Returns {min, max}.
inline std::array<double, 2> transient_tip_range(const BladeScene& scene, BladeScene::System& sys,
                                                 const BladeScene::System::Mode& mode, double t0,
                                                 const BladeScene::System::State& x0, double T,
                                                 const stickslip::StepperOptions<double>& stepper_options) {
  stickslip::StepperOptions<double> so = stepper_options;
  so.output_interval = T / 512;
  stickslip::HybridStepper<BladeScene::System, stickslip::DormandPrince54> stepper(sys, so);
  TipObserver obs;
  obs.scene = &scene;
  obs.on_step(t0, x0, mode);
  stepper.integrate(mode, t0, x0, t0 + T, obs);
  return {obs.lo, obs.hi};
}

/// The start-mode rule of the continuation (stickslip::Continuation::start_mode): keep each
/// damper's previous state unless a slipping damper's sliding velocity has changed sign (then it
/// is a stick candidate); FrictionDampedSystem::make_consistent then resolves the candidates
/// (a stuck damper beyond its capacity mu_s N slips).
inline BladeScene::System::Mode blade_start_mode(BladeScene::System& sys, double t,
                                                 const BladeScene::System::State& x,
                                                 const BladeScene::System::Mode& previous) {
  using stickslip::ContactState;
  BladeScene::System::Mode m = previous;
  BladeScene::System::State xc = x;
  const auto V = sys.evaluate(m, t, xc).V;
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    if ((m[i] == ContactState::SlipPositive && !(V[i] > 0)) || (m[i] == ContactState::SlipNegative && !(V[i] < 0)))
      m[i] = ContactState::Stick;
  }
  if (!sys.make_consistent(m, t, xc)) return previous;
  return m;
}

/// Settings of the frequency-response curves.
struct FrcSettings {
  double f_lo = 25, f_hi = 45;  ///< excitation range [Hz]
  int max_points = 300;         ///< per branch
  int linear_points = 400;      ///< points of each linear curve
  int transient_periods = 60;   ///< before shooting the start orbit at f_lo
  /// The monodromy by finite differences (2 n plain periods) instead of the variational run
  /// (with the model's jacobian and Phi out of the error control: as cheap at 1 N, 3x cheaper
  /// stuck, and accurate where the differences' h = 1e-6 is 1 % of the state; docs/measurements/steady_state_cost.md
  /// "Cost").
  bool finite_difference_monodromy = false;
  /// Newton iterations of the start orbit's shooting (ShootingOptions::max_iterations). From a
  /// transient's end Newton converges in 1-4 runs or stalls (near a grazing): 30 (the library's
  /// default) cost 40-50 s per failing orbit here; 8, as the optimal-preload search.
  int max_newton_iterations = 8;
  /// Parts of each branch run at once on their own threads (stickslip::SplitContinuation; 1:
  /// one Continuation). Each part starts from its own transient and shooting. Default 4, also on
  /// fewer cores: the cost per point is uneven (twice the average over the resonance), and
  /// parts of equal frequency range balance better when there are more of them than cores
  /// (docs/measurements/steady_state_cost.md, "Where the 1 N branch ends": 2 cores, 2 parts 7.2 s, 4 parts 6.0 s).
  int parts = 4;
  /// Restarts past a stall: when a branch ends with step_too_small short of f_hi (a nonsmooth
  /// point the corrector cannot pass, docs/howto/frequency_response.md), a new segment starts from its own
  /// transient and shooting at restart_gap (a fraction of the range) beyond the farthest point
  /// computed, up to this many times per preload. 0: none.
  int restarts = 8;
  double restart_gap = 0.01;  ///< the gap before a restart, as a fraction of f_hi - f_lo
  /// The orbits' period in forcing periods (k T): 1, or k > 1 for a branch of subharmonic orbits
  /// (set by a restart whose Poincaré sections repeat every k periods).
  int period_multiple = 1;
  /// Branch switching at period doublings: at each flip of a branch (a multiplier through -1)
  /// the flip is located (stickslip::PeriodDoubling::locate_flip, |mu + 1| <= 1e-6) and the
  /// branch of period-2k T orbits born there is continued for at most this many points
  /// (0: no switching).
  int switch_points = 40;
  /// The first 2k T orbit's arclength from the flip, as a fraction of the state scale of the
  /// arclength norm (frc_state_scale): large enough that it differs from the period-k T orbit
  /// by far more than Newton's tolerance, small enough for Newton from a straight step.
  double switch_offset = 0.02;
  /// Transient sweeps from rest, up and down in frequency (blade_settle.hpp frequency_sweep), at
  /// this many uniform frequencies of [f_lo, f_hi] each (0: none): what the structure reaches,
  /// each frequency's response with its period, overlaid on the branches (frc_sweep.csv).
  int sweep_points = 0;
  int sweep_settle_periods = 150;  ///< forcing periods each sweep frequency settles for
};

/// Parses `--frc lo:hi` (Hz, 0 < lo < hi) into default settings with that range.
inline FrcSettings parse_frc_range(const std::string& text) {
  FrcSettings s;
  if (std::sscanf(text.c_str(), "%lf:%lf", &s.f_lo, &s.f_hi) != 2 || !(s.f_hi > s.f_lo) || !(s.f_lo > 0))
    throw std::invalid_argument("--frc expects lo:hi [Hz] with 0 < lo < hi, got " + text);
  return s;
}

/// The shooting options of the blade's orbits: q, q', x_d, x_d' periodic (the contact
/// coordinates are a neutral direction and keep their values; docs/steady_state.md).
inline stickslip::ShootingOptions<double> blade_shooting_options(const BladeScene::System& sys, bool fd) {
  stickslip::ShootingOptions<double> opt;
  opt.periodic = stickslip::ShootingOptions<double>::first(sys.contact_offset() >= 0 ? sys.contact_offset()
                                                                                     : sys.linear_size());
  if (fd) opt.monodromy = stickslip::MonodromyMethod::FiniteDifference;
  // The variational monodromy on the steps of the plain run (Phi out of the error control):
  // 4.5-5.6x fewer steps, multipliers unchanged to 8 digits at 1 N (docs/measurements/steady_state_cost.md "Cost").
  opt.control_sensitivities = false;
  // The runs' global error over a period of ~8500 steps at rtol 1e-10 is ~1e-9 of the state:
  // a residual of 1e-9 (the default) is at that floor and stalls the corrector; 1e-7 is far
  // below what a design plot can show.
  opt.tolerance = 1e-7;
  // With the variational monodromy the runs need only be ~100x below that tolerance: rtol 1e-9
  // (atol 1e-11) gives the same orbits as rtol 1e-13 to the Newton tolerance's own ~2e-9 of the
  // state and the multipliers to 9 digits, in ~2/3 of the time of rtol 1e-10 (docs/measurements/steady_state_cost.md,
  // "Integration tolerance of the blade's orbits"). Finite differences of plain runs (h = 1e-6 of
  // the state) keep rtol 1e-10: their columns divide the runs' error by h.
  if (!fd) {
    opt.stepper.rtol = 1e-9;
    opt.stepper.atol = 1e-11;
  }
  return opt;
}

/// The system's consistent state and mode at rest (the start of every transient here).
inline void blade_rest_start(BladeScene::System& sys, BladeScene::System::Mode& mode, BladeScene::System::State& x) {
  x = sys.initial_state();
  mode = sys.requested_mode();
  if (!sys.make_consistent(mode, 0.0, x)) throw std::runtime_error("frc: no consistent start state at rest");
}

/// A start orbit of the system at the excitation frequency `force_omega` [rad/s] (the system's
/// own): the end of a transient from rest of `periods` (whole) excitation periods as the guess,
/// then shooting from t0 = 0 with period period_multiple T. Returns the orbit (check ok()).
inline stickslip::PeriodicOrbit<BladeScene::System> blade_start_orbit(BladeScene::System& sys, double force_omega,
                                                                      int periods,
                                                                      const stickslip::ShootingOptions<double>& opt,
                                                                      int period_multiple = 1) {
  const double T = 2 * M_PI / force_omega;
  BladeScene::System::State x0;
  BladeScene::System::Mode mode;
  blade_rest_start(sys, mode, x0);
  stickslip::HybridStepper<BladeScene::System, stickslip::DormandPrince54> stepper(sys, opt.stepper);
  const auto transient = stepper.integrate(mode, 0.0, x0, static_cast<double>(periods) * T);
  stickslip::Shooting<BladeScene::System> shooting(sys, opt);
  if (!transient.ok()) {
    stickslip::PeriodicOrbit<BladeScene::System> failed;
    failed.status = stickslip::ShootingStatus::IntegrationFailed;
    failed.message = "the transient before shooting failed: " + transient.message;
    return failed;
  }
  // The load F sin(omega t) repeats every T: the state after whole periods is the orbit's at
  // t0 = 0, and t0 = 0 keeps the forcing phase at t0 fixed along a frequency branch (a later t0
  // would turn it by t0 d omega).
  return shooting.forced(transient.mode, 0.0, transient.x, period_multiple * T);
}

/// One frequency-response branch of `scene` at its preload over [f_lo, f_hi] (Hz), from the
/// orbit at f_lo. The continuation parameter is omega / u with u = (omega_hi - omega_lo) / 4 S,
/// S the largest |(q, q')| of the linear limits over the range, so that the parameter and the
/// states weigh alike in the arclength norm. `progress` is called per point. With `settled`
/// (a restart's Poincaré sections at f_lo, whole periods after t = 0) the start orbit is shot
/// from its last section instead of a transient of its own.
inline FrcBranch frc_branch(BladeScene& scene, const FrcSettings& s, double state_scale,
                            const std::function<void(const FrcPoint&)>& progress,
                            const stickslip::PoincareSections<BladeScene::System>* settled = nullptr) {
  using System = BladeScene::System;
  FrcBranch b;
  b.preload = scene.parameters.preload;
  const double cpu0 = stickslip::detail::thread_cpu_seconds();
  double cpu_last = cpu0;
  const double w_lo = 2 * M_PI * s.f_lo, w_hi = 2 * M_PI * s.f_hi;
  // The parameter range weighs 4 state scales: away from resonance the orbit's states change
  // little with the frequency, and a tangent dominated by x_P would crawl in frequency.
  const double unit = (w_hi - w_lo) / (4 * state_scale);
  BladeParameters p = scene.parameters;
  p.force_omega = w_lo;
  *scene.system = make_blade_system(scene, p);
  scene.parameters = p;
  // The variational monodromy; with finite_difference_monodromy, differences where the dampers
  // slide but still the variational one for a branch that starts stuck all period (a family:
  // its multipliers 1 are exact there, the differences' noise ~rtol / fd_step hides them;
  // docs/howto/frequency_response.md "The blade scene").
  auto opt = blade_shooting_options(*scene.system, s.finite_difference_monodromy);
  opt.max_iterations = s.max_newton_iterations;
  add_tip_output(scene, opt);
  auto start_orbit = [&] {
    if (!settled) return blade_start_orbit(*scene.system, w_lo, s.transient_periods, opt, s.period_multiple);
    stickslip::Shooting<System> shooting(*scene.system, opt);
    return shooting.forced(settled->modes.back(), 0.0, settled->states.back(), s.period_multiple * 2 * M_PI / w_lo);
  };
  auto start = start_orbit();
  if (opt.monodromy == stickslip::MonodromyMethod::FiniteDifference && (!start.ok() || start.events.empty())) {
    opt.monodromy = stickslip::MonodromyMethod::Variational;
    start = start_orbit();
  }
  b.monodromy = stickslip::to_string(opt.monodromy);
  if (!start.ok()) {
    b.status = "start_failed";
    b.message = "no orbit at f_lo: " + start.message;
    b.cpu_seconds = stickslip::detail::thread_cpu_seconds() - cpu0;
    return b;
  }
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = w_lo / unit;
  co.parameter_max = w_hi / unit;
  co.max_step = state_scale / 25;
  co.initial_step = state_scale / 200;
  co.min_step = state_scale * 1e-6;
  co.max_points = s.max_points;
  // The finite-difference monodromy (accuracy ~rtol / fd_step) makes the corrector converge
  // linearly: 4 iterations are a normal step here, not a hint to shrink it.
  co.fast_iterations = 4;
  co.max_corrector_iterations = 10;
  // Where the stick fraction changes (an event appears) the corrector can land on another
  // orbit, several steps away (seen at 1 N near 16 Hz): reject such a point and halve the step.
  co.max_corrector_distance = 2;
  // (section_margin: the default 0.02 moves the section t0 away from an event that comes within
  // 2 % of a period of it: an event crossing t0 stalled the 1 N branch at 30.74 Hz,
  // docs/measurements/steady_state_cost.md, "Moving the section".)
  // The progress of the branch (of its part: each part's thread) just before its on_point.
  static thread_local stickslip::ContinuationProgress last_progress;
  co.progress = [](const stickslip::ContinuationProgress& pr) { last_progress = pr; };
  // Chord iterations first: plain periods (~14x cheaper than a variational one here) with the
  // last point's Jacobian; one variational period then confirms the point.
  co.chord_iterations = 4;
  auto set_parameter = [&scene, unit](System& sys, double par) {
    BladeParameters q = scene.parameters;
    q.force_omega = par * unit;
    sys = make_blade_system(scene, q);
  };
  const int k_T = s.period_multiple;
  auto period_of = [unit, k_T](double par) { return k_T * 2 * M_PI / (par * unit); };
  // One point of the curve from an orbit of the branch (its tip from the orbit's own period).
  auto make_point = [&b, unit, k_T](const stickslip::ContinuationPoint<System>& pt, double& cpu_mark) {
    FrcPoint f;
    f.preload = b.preload;
    f.period = k_T;
    f.omega = pt.parameter * unit;
    const stickslip::OrbitSignal<double>& tip = pt.orbit.outputs.at(0);
    f.tip_amplitude = tip.amplitude();
    f.tip_max_abs = std::max(std::abs(tip.min), std::abs(tip.max));
    f.stable = pt.orbit.floquet.stable;
    f.instability = stickslip::to_string(pt.orbit.floquet.instability);
    f.max_multiplier = pt.orbit.floquet.max_modulus;
    std::optional<Regime> r[2];
    for (Eigen::Index i = 0; i < 2; ++i) {
      damper_period_statistics(pt.orbit, i, f.stick_fraction[i], f.switches_per_period[i]);
      r[i] = damper_regime(f.stick_fraction[i]);
    }
    const auto common = common_regime(r[0], r[1]);
    f.regime = common ? to_string(*common) : std::string(to_string(*r[0])) + " / " + to_string(*r[1]);
    f.iterations = pt.orbit.iterations;
    f.residual = pt.orbit.residual;
    f.branch_cpu_seconds = last_progress.cpu_seconds;
    f.remaining_seconds = last_progress.remaining_seconds;
    const double now = stickslip::detail::thread_cpu_seconds();
    f.cpu_seconds = now - cpu_mark;
    cpu_mark = now;
    return f;
  };
  const auto wall0 = std::chrono::steady_clock::now();
  auto elapsed = [&wall0] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  };
  // Branch switching at each period doubling of the branch (FrcSettings::switch_points): the flip
  // located, the period-2k T branch started along the multiplier's eigenvector and continued
  // away from it; its points go to b.switched, numbered by flip (segment 1, 2, ...).
  auto switch_at_flips = [&](const stickslip::ContinuationResult<System>& branch) {
    if (s.switch_points <= 0) return;
    int flips = 0;
    for (const auto& bif : branch.bifurcations) {
      if (bif.kind != stickslip::BifurcationKind::PeriodDoubling || bif.before + 1 >= branch.points.size()) continue;
      auto it = std::find_if(b.bifurcations.begin(), b.bifurcations.end(), [&](const FrcBranch::Bifurcation& x) {
        return x.kind == "period_doubling" && x.frequency_hz == bif.parameter * unit / (2 * M_PI);
      });
      std::string note;
      stickslip::ContinuationOptions<double> c2 = co;
      c2.max_points = s.switch_points;
      stickslip::PeriodDoubling<System> pd(*scene.system, set_parameter, period_of, opt, c2);
      pd.start_mode(blade_start_mode);
      const auto flip = pd.locate_flip(branch.points[bif.before], branch.points[bif.before + 1], 1e-6);
      if (!flip.ok) {
        note = "not switched: " + flip.message;
      } else {
        const auto two = pd.period_doubled_branch(flip, s.switch_offset * state_scale);
        ++flips;
        std::size_t kept = 0;
        for (const auto& pt : two.points) {
          FrcPoint f = make_point(pt, cpu_last);
          f.period = 2 * k_T;
          f.kind = "period_doubled";
          f.segment = flips;
          b.switched.push_back(f);
          ++kept;
          if (progress) progress(f);
        }
        char t[200];
        std::snprintf(t, sizeof t, "period-%dT branch from the flip at %.4f Hz: %zu points, %s%s%s", 2 * k_T,
                      flip.parameter * unit / (2 * M_PI), kept, stickslip::to_string(two.status),
                      two.message.empty() ? "" : ": ", two.message.c_str());
        note = t;
      }
      std::printf("frc N0 %g N: %s\n", b.preload, note.c_str());
      std::fflush(stdout);
      if (it != b.bifurcations.end()) it->switched = note;
    }
  };
  if (s.parts <= 1) {
    stickslip::Continuation<System> cont(*scene.system, set_parameter, period_of, opt, co);
    cont.start_mode(blade_start_mode);
    cont.on_point([&](const stickslip::ContinuationPoint<System>& pt) {
      b.points.push_back(make_point(pt, cpu_last));
      if (progress) progress(b.points.back());
    });
    const auto result = cont.run(start.mode, start.t0, start.x0, w_lo / unit);
    for (const auto& bif : result.bifurcations)
      b.bifurcations.push_back({stickslip::to_string(bif.kind), bif.parameter * unit / (2 * M_PI), bif.destabilising, {}});
    b.status = stickslip::to_string(result.status);
    b.message = result.message;
    switch_at_flips(result);
    b.cpu_seconds = stickslip::detail::thread_cpu_seconds() - cpu0;
    b.wall_seconds = elapsed();
    return b;
  }
  // In parts: a copy of the system per part; part 0 starts from the orbit above, part k from its
  // own transient at its start frequency (on its own thread).
  const auto n = static_cast<std::size_t>(s.parts);
  std::vector<System> systems(n, *scene.system);
  std::vector<System*> ptrs;
  for (System& sys : systems) ptrs.push_back(&sys);
  stickslip::SplitContinuation<System> split(ptrs, set_parameter, period_of, opt, co);
  split.start_mode(blade_start_mode);
  std::vector<std::vector<FrcPoint>> part_points(n);
  // Per part, the thread CPU at its last point (part k > 0: from the start of its transient, so
  // that its first point carries its start as part 0's does).
  std::vector<double> part_cpu(n, cpu_last);
  std::mutex progress_mutex;
  split.on_point([&](std::size_t k, const stickslip::ContinuationPoint<System>& pt) {
    part_points[k].push_back(make_point(pt, part_cpu[k]));
    std::lock_guard<std::mutex> lock(progress_mutex);
    if (progress) progress(part_points[k].back());
  });
  const double cpu_before = stickslip::detail::thread_cpu_seconds() - cpu0;
  const auto result = split.run([&](System& sys, double par) {
    if (par == w_lo / unit) return stickslip::SplitContinuation<System>::Guess{start.mode, start.t0, start.x0};
    part_cpu[static_cast<std::size_t>(&sys - systems.data())] = stickslip::detail::thread_cpu_seconds();
    const auto orbit = blade_start_orbit(sys, par * unit, s.transient_periods, opt, s.period_multiple);
    return stickslip::SplitContinuation<System>::Guess{orbit.mode, orbit.t0, orbit.x0};
  });
  b.status = stickslip::to_string(result.branch.status);
  b.message = result.branch.message;
  for (const auto& bif : result.branch.bifurcations)
    b.bifurcations.push_back({stickslip::to_string(bif.kind), bif.parameter * unit / (2 * M_PI), bif.destabilising, {}});
  b.parts = result.parts;
  for (auto& part : b.parts) part.start_parameter *= unit / (2 * M_PI);  // in Hz
  b.cpu_seconds = cpu_before;
  std::size_t last = 0;  // the last part in the branch: its system is at the last point's frequency
  for (std::size_t k = 0; k < n; ++k) {
    b.cpu_seconds += result.parts[k].cpu_seconds;
    for (std::size_t i = 0; i < result.parts[k].kept; ++i) b.points.push_back(part_points[k][i]);
    if (result.parts[k].kept > 0) last = k;
  }
  // The parts the branch never reached: their own points, as separate segments after it.
  for (std::size_t k = 1; k < n; ++k)
    if (result.parts[k].kept == 0)
      for (FrcPoint f : part_points[k]) {
        f.segment = static_cast<int>(k);
        b.points.push_back(f);
      }
  *scene.system = systems[last];  // as the single Continuation leaves it
  const double cpu_switch = stickslip::detail::thread_cpu_seconds();
  switch_at_flips(result.branch);
  b.cpu_seconds += stickslip::detail::thread_cpu_seconds() - cpu_switch;
  b.wall_seconds = elapsed();
  return b;
}

/// The largest |x_P| amplitude (2-norm of the complex amplitudes of q, q', x_d, x_d') of the
/// linear limits over the frequency range: the state scale of the arclength norm.
inline double frc_state_scale(BladeScene& scene, const FrcSettings& s) {
  double scale = 0;
  const Eigen::Index np = 2 * scene.system->num_modes() + 2 * scene.system->num_dampers();
  for (const LinearLimit& l : blade_linear_limits(scene))
    for (int k = 0; k <= 200; ++k)
      scale = std::max(scale, l.response(2 * M_PI * (s.f_lo + (s.f_hi - s.f_lo) * k / 200.0)).head(np).norm());
  return scale;
}

/// The two linear curves (all stuck, mu = 0) on a uniform grid: rows (f [Hz], stuck tip, free
/// tip), tip = |psi_tip^T X_q| of LinearLimit::response.
inline std::vector<std::array<double, 3>> frc_linear_curves(BladeScene& scene, const FrcSettings& s) {
  const auto limits = blade_linear_limits(scene);
  const Eigen::VectorXcd tip = scene.tip_shape.cast<std::complex<double>>();
  std::vector<std::array<double, 3>> rows;
  for (int k = 0; k < s.linear_points; ++k) {
    const double f = s.f_lo + (s.f_hi - s.f_lo) * k / (s.linear_points - 1.0);
    std::array<double, 3> r{f, 0, 0};
    for (std::size_t j = 0; j < 2; ++j)
      r[j + 1] = std::abs(tip.dot(limits[j].response(2 * M_PI * f).head(limits[j].modes)));
    rows.push_back(r);
  }
  return rows;
}

/// `text` as the body of a JSON string (quotes, backslashes and control characters escaped).
inline std::string json_escape(const std::string& text) {
  std::string o;
  for (char ch : text) {
    if (ch == '"' || ch == '\\') o += '\\';
    o += (static_cast<unsigned char>(ch) < 0x20) ? ' ' : ch;
  }
  return o;
}

/// One line on part k of a branch in parts: its start [Hz], status, points kept and whether it
/// joined the next.
inline std::string frc_part_line(std::size_t k, const stickslip::ContinuationPart<double>& part) {
  char t[160];
  std::snprintf(t, sizeof t, "part %zu from %.3f Hz: %s, %zu of %zu points kept%s", k, part.start_parameter,
                stickslip::to_string(part.status), part.kept, part.points,
                part.joined                        ? ", joined the next"
                : part.kept == 0 && part.points > 0 ? " in the branch (written as a separate segment)"
                                                    : "");
  return t;
}

/// Writes frc.csv (one row per point), frc_linear.csv and frc.json into `out`.
inline void write_frc(const std::filesystem::path& out, const BladeParameters& p, const FrcSettings& s,
                      const std::vector<FrcBranch>& branches) {
  {
    std::ofstream o(out / "frc.csv");
    o << "preload_N,frequency_hz,tip_amplitude_m,tip_max_abs_m,stable,instability,max_multiplier,regime,stick_fraction_1,"
         "stick_fraction_2,switches_per_period_1,switches_per_period_2,newton_runs,residual,cpu_s,segment,period_T,kind\n";
    for (const auto& b : branches)
      for (const auto& f : b.points)
        o << fmt(f.preload) << ',' << fmt(f.omega / (2 * M_PI)) << ',' << fmt(f.tip_amplitude) << ',' << fmt(f.tip_max_abs) << ','
          << (f.stable ? 1 : 0) << ',' << f.instability << ',' << fmt(f.max_multiplier) << ',' << f.regime << ','
          << fmt(f.stick_fraction[0]) << ',' << fmt(f.stick_fraction[1]) << ',' << fmt(f.switches_per_period[0])
          << ',' << fmt(f.switches_per_period[1]) << ',' << f.iterations << ',' << fmt(f.residual) << ','
          << fmt(f.cpu_seconds) << ',' << f.segment << ',' << f.period << ',' << f.kind << '\n';
  }
  {  // the restarts' frequencies without a periodic response: the tip amplitude per period
    std::ofstream o(out / "frc_poincare.csv");
    o << "preload_N,frequency_hz,period_index,tip_amplitude_m,smallest_recurrence\n";
    for (const auto& b : branches)
      for (const auto& np : b.not_periodic)
        for (std::size_t n = 0; n < np.tip_amplitudes.size(); ++n)
          o << fmt(b.preload) << ',' << fmt(np.frequency_hz) << ',' << n << ',' << fmt(np.tip_amplitudes[n]) << ','
            << fmt(np.recurrence) << '\n';
  }
  {
    std::ofstream o(out / "frc_linear.csv");
    o << "preload_N,frequency_hz,tip_all_stuck_m,tip_frictionless_m\n";
    for (const auto& b : branches)
      for (const auto& r : b.linear)
        o << fmt(b.preload) << ',' << fmt(r[0]) << ',' << fmt(r[1]) << ',' << fmt(r[2]) << '\n';
  }
  std::ofstream j(out / "frc.json");
  auto list = [&](const std::vector<double>& v) {
    std::string t = "[";
    for (std::size_t k = 0; k < v.size(); ++k) t += (k ? ", " : "") + jnum(v[k]);
    return t + "]";
  };
  j << "{\n  \"f_lo_hz\": " << jnum(s.f_lo) << ", \"f_hi_hz\": " << jnum(s.f_hi)
    << ", \"damping_ratio\": " << jnum(p.damping_ratio) << ", \"force_N\": " << jnum(p.force)
    << ",\n  \"regime_rule\": \"" << regime_rule_text()
    << " (here over one period of the orbit)\",\n  \"branches\": [";
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const auto& b = branches[k];
    const std::size_t peak = stable_peak(b.points);
    j << (k ? "," : "") << "\n    {\"preload_N\": " << jnum(b.preload) << ", \"status\": \"" << b.status
      << "\", \"message\": \"" << json_escape(b.message) << "\", \"monodromy\": \"" << b.monodromy << "\", \"points\": " << b.points.size()
      << ", \"restarts\": " << b.restarts << ", \"separate_segment_points\": " << b.separate_points()
      << ", \"not_periodic_hz\": " << list([&] {
           std::vector<double> v;
           for (const auto& np : b.not_periodic) v.push_back(np.frequency_hz);
           return v;
         }())
      << ", \"cpu_s\": " << jnum(b.cpu_seconds) << ", \"wall_s\": " << jnum(b.wall_seconds) << ", \"parts\": [";
    for (std::size_t q = 0; q < b.parts.size(); ++q)
      j << (q ? ", " : "") << "{\"start_hz\": " << jnum(b.parts[q].start_parameter) << ", \"status\": \""
        << stickslip::to_string(b.parts[q].status) << "\", \"points\": " << b.parts[q].points
        << ", \"kept\": " << b.parts[q].kept << ", \"joined\": " << (b.parts[q].joined ? "true" : "false") << "}";
    j << "], \"bifurcations\": [";
    for (std::size_t q = 0; q < b.bifurcations.size(); ++q)
      j << (q ? ", " : "") << "{\"kind\": \"" << b.bifurcations[q].kind << "\", \"frequency_hz\": "
        << jnum(b.bifurcations[q].frequency_hz) << ", \"destabilising\": " << (b.bifurcations[q].destabilising ? "true" : "false")
        << (b.bifurcations[q].switched.empty() ? "" : ", \"switched\": \"" + json_escape(b.bifurcations[q].switched) + "\"")
        << "}";
    j << "]"
      << ", \"all_stuck_frequencies_hz\": " << list(b.stuck_hz) << ", \"frictionless_frequencies_hz\": " << list(b.free_hz);
    if (peak < b.points.size())  // stable orbits of every segment only (frc_peak.hpp)
      j << ", \"peak_tip_m\": " << jnum(b.points[peak].tip_amplitude)
        << ", \"peak_frequency_hz\": " << jnum(b.points[peak].omega / (2 * M_PI)) << ", \"peak_period_T\": "
        << b.points[peak].period << ", \"peak_kind\": \"" << b.points[peak].kind << "\"";
    // Per segment: its kind and period, frequency span, points and its largest stable amplitude.
    j << ", \"segments\": [";
    std::vector<int> seen;
    for (const FrcPoint& f : b.points) {
      if (std::find(seen.begin(), seen.end(), f.segment) != seen.end()) continue;
      seen.push_back(f.segment);
      double lo = HUGE_VAL, hi = -HUGE_VAL, top = -1;
      std::size_t n = 0, stable = 0;
      for (const FrcPoint& g : b.points) {
        if (g.segment != f.segment) continue;
        const double hz = g.omega / (2 * M_PI);
        lo = std::min(lo, hz);
        hi = std::max(hi, hz);
        ++n;
        if (g.stable) ++stable, top = std::max(top, g.tip_amplitude);
      }
      j << (seen.size() > 1 ? ", " : "") << "{\"segment\": " << f.segment << ", \"kind\": \"" << f.kind
        << "\", \"period_T\": " << f.period << ", \"from_hz\": " << jnum(lo) << ", \"to_hz\": " << jnum(hi)
        << ", \"points\": " << n << ", \"stable_points\": " << stable;
      if (top >= 0) j << ", \"peak_stable_tip_m\": " << jnum(top);
      j << "}";
    }
    j << "]}";
  }
  j << "\n  ]\n}\n";
}

/// Observer of the tip's extremes per forcing period after t0 (period n: t in (t0 + nT, t0 + (n+1)T]).
struct PeriodTipObserver : stickslip::NullObserver {
  const BladeScene* scene = nullptr;
  double t0 = 0, T = 1;
  std::vector<double> lo, hi;
  template <class X, class M>
  bool on_step(double t, const X& x, const M&) {
    const double tip = scene->tip_displacement(x);
    const auto n = static_cast<std::size_t>(std::max(0.0, std::ceil((t - t0) / T - 1e-9) - 1));
    if (n >= lo.size()) {
      lo.resize(n + 1, tip);
      hi.resize(n + 1, tip);
    }
    lo[n] = std::min(lo[n], tip);
    hi[n] = std::max(hi[n], tip);
    return true;
  }
  template <class X, class M>
  bool on_sample(double t, const X& x, const M& m) { return on_step(t, x, m); }
};

/// FrcSettings::restarts: after a branch that ended short of f_hi (step_too_small, or parts it
/// never reached), restarts at restart_gap (x range) beyond the farthest frequency of the branch
/// or tried so far, past the spans of the segments already computed (a part's, a restart's),
/// each new segment ending where the next known one starts. Each first
/// looks at the response: Poincaré sections (stickslip::poincare_sections) after a transient
/// from rest of 3 x transient_periods periods, 32 sections, k <= 8, the library's tolerance
/// (periodic below 1e-6, undecided up to 1e-4: the candidate k is shot). Period k:
/// a new segment (FrcPoint::segment = the next number), the branch of period-k T orbits shot
/// from the last section (k > 1: subharmonic orbits, FrcPoint::period = k). No k: the
/// tip's amplitude per recorded period goes to FrcBranch::not_periodic (quasi-periodic or
/// chaotic response there) and the next restart tries one gap further. Until a segment
/// completes or ends otherwise (max_points) or the restarts run out. The points in the gaps are
/// not computed; a segment after a fold may lie on another branch (the orbit a slow sweep would
/// jump to). b's status and message become those of the last attempt.
inline void frc_restarts(BladeScene& scene, const FrcSettings& s, FrcBranch& b,
                         const std::function<void(const FrcPoint&)>& progress) {
  int segment = 0;
  // The frequency span of each segment found so far (the branch, a part it never reached, a
  // restart's), and the farthest frequency of the branch itself (segment 0): the restarts go on
  // from there, jump over the spans already computed and end each of their segments at the next
  // span's start, so that the first gap is filled before the later ones.
  std::vector<std::array<double, 2>> spans;
  double f_far = s.f_lo;  // the farthest frequency reached or tried
  {
    std::vector<std::array<double, 2>> by_segment;
    for (const FrcPoint& f : b.points) {
      const double hz = f.omega / (2 * M_PI);
      segment = std::max(segment, f.segment);
      const auto k = static_cast<std::size_t>(f.segment);
      if (by_segment.size() <= k) by_segment.resize(k + 1, {HUGE_VAL, -HUGE_VAL});
      by_segment[k] = {std::min(by_segment[k][0], hz), std::max(by_segment[k][1], hz)};
      if (f.segment == 0) f_far = std::max(f_far, hz);
    }
    for (const auto& sp : by_segment)
      if (sp[0] <= sp[1]) spans.push_back(sp);
  }
  auto beyond = [&spans](double f) {  // f moved past every span that holds it
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& sp : spans)
        if (f >= sp[0] && f < sp[1]) {
          f = sp[1];
          moved = true;
        }
    }
    return f;
  };
  auto next_start = [&spans, &s](double f) {  // the first span that starts beyond f, or f_hi
    double n = s.f_hi;
    for (const auto& sp : spans)
      if (sp[0] > f) n = std::min(n, sp[0]);
    return n;
  };
  const double gap = s.restart_gap * (s.f_hi - s.f_lo);
  f_far = beyond(f_far);
  bool again = b.status != "max_points" && f_far + gap < s.f_hi;
  for (int r = 0; r < s.restarts && again; ++r) {
    FrcSettings sr = s;
    sr.f_lo = beyond(f_far + gap);
    sr.f_hi = next_start(sr.f_lo);
    sr.parts = 1;
    sr.restarts = 0;
    // Next to a stall the response is near a resonance or a change of regime: a longer transient
    // and more Newton iterations for the start than at f_lo.
    sr.transient_periods = 3 * s.transient_periods;
    sr.max_newton_iterations = std::max(s.max_newton_iterations, 20);
    if (!(sr.f_lo < sr.f_hi)) break;
    const double f_prev = f_far;
    f_far = sr.f_lo;  // a restart that finds no orbit here makes the next one try a gap further
    ++b.restarts;
    // The response at f_lo: period k, or none.
    const double cpu0 = stickslip::detail::thread_cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    BladeParameters q = scene.parameters;
    q.force_omega = 2 * M_PI * sr.f_lo;
    *scene.system = make_blade_system(scene, q);
    scene.parameters = q;
    const auto opt = blade_shooting_options(*scene.system, false);
    stickslip::PoincareOptions<double> po;
    po.transient_periods = sr.transient_periods;
    po.record_periods = 32;
    po.max_period = 8;
    po.periodic = opt.periodic;
    po.stepper = opt.stepper;
    BladeScene::System::State x0;
    BladeScene::System::Mode mode;
    blade_rest_start(*scene.system, mode, x0);
    PeriodTipObserver tips;
    tips.scene = &scene;
    tips.T = 2 * M_PI / q.force_omega;
    tips.t0 = po.transient_periods * tips.T;
    const auto sections = stickslip::poincare_sections(*scene.system, mode, 0.0, x0, tips.T, po, tips);
    b.cpu_seconds += stickslip::detail::thread_cpu_seconds() - cpu0;
    b.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    // Undecided (a recurrence within a factor 10 of the tolerance): the candidate period is shot
    // like a periodic one, and Newton decides.
    if (sections.period == 0) {
      FrcPoincare np;
      np.frequency_hz = sr.f_lo;
      for (std::size_t n = 0; n < tips.lo.size(); ++n) np.tip_amplitudes.push_back((tips.hi[n] - tips.lo[n]) / 2);
      np.recurrence = sections.recurrence.empty() ? 0.0 : *std::min_element(sections.recurrence.begin(), sections.recurrence.end());
      const auto [lo, hi] = std::minmax_element(np.tip_amplitudes.begin(), np.tip_amplitudes.end());
      std::printf("frc N0 %g N: restart at %.3f Hz after %s up to %.3f Hz: %s (no period <= 8 T in 32 sections, "
                  "smallest recurrence %.1e: quasi-periodic or chaotic), tip %.4e..%.4e m per period\n",
                  b.preload, sr.f_lo, b.status.c_str(), f_prev, stickslip::to_string(sections.status), np.recurrence, np.tip_amplitudes.empty() ? 0.0 : *lo,
                  np.tip_amplitudes.empty() ? 0.0 : *hi);
      std::fflush(stdout);
      b.not_periodic.push_back(std::move(np));
      if (sections.status == stickslip::PoincareStatus::IntegrationFailed) {
        b.status = "start_failed";
        b.message = "restart at " + std::to_string(sr.f_lo) + " Hz: " + sections.message;
      }
      continue;
    }
    sr.period_multiple = sections.period;
    // A subharmonic branch costs k times a period-1 one per run and lives in narrow windows (1 N:
    // period 8 T at 33.42 Hz, Neimark-Sacker after 0.01 Hz, then crawling at ~3 s per point):
    // a short stretch shows where it is.
    if (sections.period > 1) sr.max_points = std::min(sr.max_points, 12);
    std::printf("frc N0 %g N: restart at %.3f Hz after %s up to %.3f Hz (segment %d, from its transient's "
                "sections: the response repeats every %d T%s)\n",
                b.preload, sr.f_lo, b.status.c_str(), f_prev, segment + 1, sections.period,
                sections.periodic() ? "" : ", undecided: recurrence within 10x of the tolerance");
    std::fflush(stdout);
    const FrcBranch next = frc_branch(scene, sr, frc_state_scale(scene, sr), [&](const FrcPoint& f) {
      FrcPoint g = f;
      g.segment = segment + 1;
      if (progress) progress(g);
    }, &sections);
    if (!next.points.empty()) ++segment;
    double seg_lo = HUGE_VAL, seg_hi = -HUGE_VAL;
    for (FrcPoint f : next.points) {
      f.segment = segment;
      f.kind = sr.period_multiple > 1 ? "subharmonic" : "restart";
      b.points.push_back(f);
      const double hz = f.omega / (2 * M_PI);
      f_far = std::max(f_far, hz);
      seg_lo = std::min(seg_lo, hz);
      seg_hi = std::max(seg_hi, hz);
    }
    if (seg_lo <= seg_hi) spans.push_back({seg_lo, seg_hi});
    // A segment that reached the next span's start goes on beyond that span.
    if (next.status == "completed" && sr.f_hi < s.f_hi) f_far = std::max(f_far, sr.f_hi);
    f_far = beyond(f_far);
    b.status = next.status;
    b.message = next.message;
    b.bifurcations.insert(b.bifurcations.end(), next.bifurcations.begin(), next.bifurcations.end());
    int flips = 0;  // the restart's period-doubled branches numbered after those found so far
    for (const FrcPoint& f : b.switched) flips = std::max(flips, f.segment);
    for (FrcPoint f : next.switched) {
      f.segment += flips;
      b.switched.push_back(f);
    }
    b.cpu_seconds += next.cpu_seconds;
    b.wall_seconds += next.wall_seconds;
    again = (next.status == "step_too_small" || next.status == "start_failed" ||
             (sr.period_multiple > 1 && next.status == "max_points") ||  // (its short stretch ended)
             (next.status == "completed" && sr.f_hi < s.f_hi)) &&
            f_far + gap < s.f_hi;
  }
}

/// `blade_damper --frc f_lo:f_hi`: a branch per preload (scene `p` at each of `preloads`), the
/// linear curves, the files of write_frc and a summary line. Returns the exit code.
inline int run_frc(BladeParameters p, const std::vector<double>& preloads, const FrcSettings& s,
                   const std::filesystem::path& out) {
  if (!(p.damping_ratio > 0)) {
    p.damping_ratio = 0.05;
    std::printf("frc: steady states need damping (docs/steady_state.md): modal damping ratio 0.05 "
                "(--damping to change)\n");
  }
  p.model.energy_audit = false;  // quadratures: not periodic, not needed here
  std::printf("frc: %.1f..%.1f Hz, damping %.3g, preloads", s.f_lo, s.f_hi, p.damping_ratio);
  for (double n0 : preloads) std::printf(" %g", n0);
  std::printf(" N\n");
  std::fflush(stdout);
  std::vector<FrcBranch> branches;
  for (double n0 : preloads) {
    BladeParameters q = p;
    q.preload = n0;
    BladeScene sc = make_blade_scene(q);
    const auto limits = blade_linear_limits(sc);
    std::vector<double> stuck_hz = limits[0].natural_frequencies_hz(), free_hz = limits[1].natural_frequencies_hz();
    std::vector<std::array<double, 3>> linear = frc_linear_curves(sc, s);
    std::printf("frc N0 %g N: lowest mode %.2f Hz all stuck, %.2f Hz frictionless (the model's linear part)\n", n0,
                stuck_hz.empty() ? 0.0 : stuck_hz[0], free_hz.empty() ? 0.0 : free_hz[0]);
    int count = 0;
    const auto progress = [&](const FrcPoint& f) {
      const std::string cost = f.remaining_seconds >= 0 ? "  (" + std::to_string(static_cast<int>(f.branch_cpu_seconds)) +
                                                              " s so far, ~" + std::to_string(static_cast<int>(f.remaining_seconds + 0.5)) +
                                                              " s to go)"
                                                        : std::string();
      std::printf("frc N0 %g N: %3d  f %7.3f Hz  tip %.4e m  %-8s %-22s stick %.2f/%.2f  runs %d  %.2f s%s%s\n", n0,
                  ++count, f.omega / (2 * M_PI), f.tip_amplitude,
                  f.stable ? "stable" : f.instability.c_str(), f.regime.c_str(), f.stick_fraction[0],
                  f.stick_fraction[1], f.iterations, f.cpu_seconds, cost.c_str(),
                  f.period > 1 ? ("  period " + std::to_string(f.period) + " T").c_str() : "");
      std::fflush(stdout);
    };
    auto b = frc_branch(sc, s, frc_state_scale(sc, s), progress);
    frc_restarts(sc, s, b, progress);
    {  // the period-doubled branches as separate segments after the branch's and the restarts'
      int last = 0;
      for (const FrcPoint& f : b.points) last = std::max(last, f.segment);
      for (FrcPoint f : b.switched) {
        f.segment += last;
        b.points.push_back(f);
      }
      b.switched.clear();
    }
    std::printf("frc N0 %g N: %s, %zu points (%zu of them in separate segments), %.1f s CPU, %.1f s elapsed%s%s\n", n0,
                b.status.c_str(), b.points.size(), b.separate_points(), b.cpu_seconds, b.wall_seconds,
                b.message.empty() ? "" : ": ", b.message.c_str());
    for (std::size_t k = 0; k < b.parts.size(); ++k)
      std::printf("frc N0 %g N:   %s\n", n0, frc_part_line(k, b.parts[k]).c_str());
    b.linear = std::move(linear);
    b.stuck_hz = std::move(stuck_hz);
    b.free_hz = std::move(free_hz);
    branches.push_back(std::move(b));
  }
  write_frc(out, p, s, branches);
  std::size_t points = 0;
  double cpu = 0;
  std::string peaks;
  for (const auto& b : branches) {
    points += b.points.size();
    cpu += b.cpu_seconds;
    const std::size_t peak = stable_peak(b.points);
    if (peak == b.points.size()) continue;
    char t[128];
    std::snprintf(t, sizeof t, "; N0 %g N: stable peak %.3e m at %.2f Hz", b.preload, b.points[peak].tip_amplitude,
                  b.points[peak].omega / (2 * M_PI));
    peaks += t;
  }
  std::printf("frc: %zu branches, %zu points, %.1f s CPU%s; files frc.csv, frc_linear.csv, frc.json in %s\n",
              branches.size(), points, cpu, peaks.c_str(), out.string().c_str());
  return 0;
}

}  // namespace blade

// The paper's turbine blade with two under-platform friction dampers (He, Ouyang, Ren & He),
// built from stickslip's components: runs preloads, writes CSV/JSON records and spectra, a
// preload sweep with a regime map, re-runs one representative preload per regime found
// (blade_regime.hpp) with full records, and prints a summary. `blade_damper --help` for options.
#include "blade_compare.hpp"
#include "blade_frc.hpp"
#include "blade_optimal.hpp"
#include "blade_regime.hpp"
#include "blade_run.hpp"
#include "blade_settle.hpp"
#include "blade_scene.hpp"
#include "blade_sweep.hpp"

#include <stickslip/stickslip.hpp>
#include <unsupported/Eigen/FFT>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace stickslip;
using Index = Eigen::Index;
namespace fs = std::filesystem;

struct Cli {
  blade::BladeParameters params;
  blade::RunSettings settings;
  std::vector<double> preloads;
  bool sweep = false;
  double sweep_lo = 0.5, sweep_hi = 40.0;
  int sweep_count = 32;
  bool sweep_log = true;
  double sweep_duration = -1;  // < 0: same as duration
  int threads = 0;
  std::string out = "out";
  std::string compare;            // --compare: variants of the trade study (empty: none)
  int compare_repeats = 3;
  double compare_reference_rtol = 1e-10;
  std::optional<blade::FrcSettings> frc;  // --frc: frequency-response curves (blade_frc.hpp)
  std::optional<blade::OptimalSettings> optimal;  // --optimise-preload (blade_optimal.hpp)
};

const char* kHelp = R"(blade_damper - the paper's blade with two under-platform friction dampers

Usage: blade_damper [options]
  --demo                 the main job: preloads 1, 12, 26 N and a 32-point sweep 0.5..40 N,
                         with --restitution 0.5 --ends wall --wall-restitution 0.5 unless
                         a contact option is given
  --preload N0           one run at preload N0 [N] (repeatable)
  --preloads a,b,...     runs at these preloads [N]
  --sweep lo:hi:count    preload sweep (E(N0) of the paper's Fig. 20), in parallel,
                         log-spaced preloads (linear with --sweep-linear); then one
                         representative preload per regime found is re-run with full
                         records into OUT/regime_<name>/
  --sweep-linear         linearly spaced sweep preloads
  --sweep-duration T     duration of each sweep run [s] (default: --duration)
  --duration T           simulated time [s] (default 20)
  --modes n              retained modes (default 6)
  --blade-elements n     elements on the blade (default 20)
  --platform-elements n  elements on the platform, even (default 8)
  --y0 Y                 excitation point above the root [m] (default 0.05)
  --damping z            modal damping ratio of every mode (default 0)
  --mu-s m --mu-k m      static and kinetic friction coefficients (default 0.35, 0.3;
                         mu_s >= mu_k)
  --integrator name      auto | rk4 | dopri5 | rosenbrock23 | exponential (default auto: chosen
                         per run from the scene, the choice and its reason printed)
  --rtol r --atol a      tolerances of the adaptive integrators (default 1e-7, 1e-10)
  --dt h                 RK4 step [s] (default 1e-4, the paper's)
  --events name          root | bisection (event location; default root)
  --constant-normal-load N = N0 (no damper vertical inertia)
  --fixed-contact        contact points do not move along the platform
  --regularised v_eps    tanh friction with mu_k and this velocity scale [m/s]
  --beyond-ends          continue the platform's end elements beyond its ends (extrapolated
                         shapes) instead of stopping when a contact reaches an end
  --compare v1,v2,...    speed/accuracy trade of variants of this scene (at the first
                         preload, for --duration) against a tight DOPRI reference: rows
                         in OUT/compare.csv, plot with plot.py. Variants: modes=N, rtol=R,
                         regularised=V, constant-normal-load, fixed-contact, damping=Z,
                         events=root|bisection, elements=B:P, integrator=NAME[:X] (X: rk4's
                         step or the others' rtol), e.g. integrator=rk4:1e-4
  --compare-repeats n    runs per variant, CPU time = median (default 3)
  --compare-reference-rtol r  the reference's rtol (default 1e-10; atol = 1e-3 r), validated
                         by a rerun at r / 100
  --frc lo:hi            frequency-response curves over lo..hi Hz at the preloads (default
                         1,5,26 N): continuation of the periodic orbits, with the all-stuck
                         and frictionless linear curves (OUT/frc.csv, frc_linear.csv,
                         frc.json; docs/steady_state.md); modal damping 0.05 unless --damping
  --frc-points n         (after --frc) points per branch at most (default 300)
  --frc-newton n         (after --frc) Newton iterations of each branch's start orbit
                         (default 8)
  --frc-parts n          (after --frc) each branch in n parts at once, one thread each
                         (stickslip::SplitContinuation; default 4, also on fewer
                         cores: it balances the uneven cost per point; 1: one
                         Continuation); a part the branch never reached is written
                         as a separate segment
  --frc-restarts n       (after --frc) after a branch stalls short of f_hi (a
                         nonsmooth point, or where the period-1 orbit turns
                         unstable), look 1 % of the range beyond it: Poincare
                         sections of a transient; period k T: a new segment of
                         period-k T orbits (k > 1: subharmonic) from there; none:
                         the tip amplitude per period (OUT/frc_poincare.csv) and
                         the next try a gap further; at most n tries (default 8;
                         0: none)
  --frc-switch-points n  (after --frc) at each period doubling of a branch, the period-2T
                         branch born there, continued for at most n points (default 40;
                         0: no branch switching)
  --frc-sweep n          (after --frc) also sweeps of transients up and down in frequency
                         over n frequencies each (the first from rest, each next from the
                         state the last left): the response reached and its period k
                         (OUT/frc_sweep.csv, drawn over the branches; default 0: none)
  --frc-sweep-settle P   (after --frc-sweep) forcing periods per sweep frequency (default 150)
  --frc-variational      (after --frc) the variational monodromy (the default)
  --frc-finite-difference  (after --frc) the finite-difference monodromy where the branch
                         starts with events (variational for one stuck all period)
  --optimise-preload lo:hi  the preload in lo..hi N minimising the resonant tip amplitude:
                         the largest stable response over frequency (the period-1 orbit and
                         what a transient from rest settles on, subharmonics included): log
                         grid + golden sections in N0 (OUT/optimal.csv, optimal_peaks.csv,
                         optimal.json; docs/howto/frequency_response.md); modal damping 0.05
                         unless --damping; in parallel on --threads
  --optimise-step h      (after --optimise-preload) frequency grid step [Hz] (default 0.5)
  --optimise-refine h    (after --optimise-preload) refine the best grid frequency to h [Hz]
                         (default 0.05; 0: no refinement)
  --optimise-settle P    (after --optimise-preload) forcing periods of each transient from
                         rest (default 150)
  --optimise-frequencies lo:hi  (after --optimise-preload) this frequency range [Hz] at every
                         preload instead of the lowest resonance's bracket
  --threads n            worker threads of the sweep (default: all cores)
  --out DIR              output folder (default out)
  --help                 this text
)";

using blade::parse_list;

Cli parse(int argc, char** argv) {
  Cli c;
  c.settings = blade::default_settings();
  auto need = [&](int& i) { return blade::next_argument(argc, argv, i); };
  bool demo = false, contact_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    // The option's value as a number / an integer in [lo, hi]; a bad value's error names the option.
    const auto number = [&] { return blade::parse_number(need(i), a); };
    const auto integer = [&](long long lo, long long hi = std::numeric_limits<int>::max(), const std::string& why = "") {
      return static_cast<int>(blade::parse_integer(need(i), a, lo, hi, why));
    };
    if (a == "--help" || a == "-h") {
      std::cout << kHelp << blade::contact_options_help();
      std::exit(0);
    } else if (a == "--demo") {
      c.preloads = {1.0, 12.0, 26.0};
      c.sweep = true;
      demo = true;
    } else if (a == "--preload") {
      c.preloads.push_back(number());
    } else if (a == "--preloads") {
      for (double p : parse_list(need(i), a)) c.preloads.push_back(p);
    } else if (a == "--sweep") {
      blade::parse_sweep_range(need(i), c.sweep_lo, c.sweep_hi, c.sweep_count);
      c.sweep = true;
    } else if (a == "--sweep-linear") {
      c.sweep_log = false;
    } else if (a == "--sweep-duration") {
      c.sweep_duration = number();
    } else if (a == "--duration") {
      c.settings.duration = number();
    } else if (a == "--modes") {
      c.params.modes = integer(1);
    } else if (a == "--blade-elements") {
      c.params.blade_elements = integer(1);
    } else if (a == "--platform-elements") {
      c.params.platform_elements = integer(2);
    } else if (a == "--y0") {
      c.params.y0 = number();
    } else if (a == "--damping") {
      c.params.damping_ratio = number();
    } else if (a == "--mu-s") {
      c.params.mu_s = number();
    } else if (a == "--mu-k") {
      c.params.mu_k = number();
    } else if (a == "--integrator") {
      c.settings.run.integrator = parse_integrator(need(i));
    } else if (a == "--rtol") {
      c.settings.run.stepper.rtol = number();
    } else if (a == "--atol") {
      c.settings.run.stepper.atol = number();
    } else if (a == "--dt") {
      c.settings.run.stepper.fixed_step = number();
    } else if (a == "--events") {
      const std::string e = need(i);
      if (e == "root") c.settings.run.stepper.event_location = EventLocation::DenseRootFinding;
      else if (e == "bisection") c.settings.run.stepper.event_location = EventLocation::Bisection;
      else throw std::invalid_argument("--events expects root or bisection, got " + e);
    } else if (a == "--constant-normal-load") {
      c.params.model.normal_load = NormalLoad::Constant;
    } else if (a == "--fixed-contact") {
      c.params.model.moving_contact = false;
    } else if (blade::parse_contact_option(a, need, i, c.params.contact, c.params.model)) {
      contact_given = true;
    } else if (a == "--beyond-ends") {
      c.params.model.end_policy = EndPolicy::Extrapolate;
      contact_given = true;
    } else if (a == "--regularised") {
      c.params.regularised_v_eps = number();
    } else if (a == "--compare") {
      c.compare = need(i);
    } else if (a == "--compare-repeats") {
      c.compare_repeats = integer(1);
    } else if (a == "--compare-reference-rtol") {
      c.compare_reference_rtol = number();
    } else if (a == "--frc") {
      c.frc = blade::parse_frc_range(need(i));
    } else if (a == "--frc-points") {
      if (!c.frc) throw std::invalid_argument("--frc-points must follow --frc");
      c.frc->max_points = integer(1);
    } else if (a == "--frc-newton") {
      if (!c.frc) throw std::invalid_argument("--frc-newton must follow --frc");
      c.frc->max_newton_iterations = integer(1);
    } else if (a == "--frc-parts") {
      if (!c.frc) throw std::invalid_argument("--frc-parts must follow --frc");
      c.frc->parts = integer(1);
    } else if (a == "--frc-restarts") {
      if (!c.frc) throw std::invalid_argument("--frc-restarts must follow --frc");
      c.frc->restarts = integer(0);
    } else if (a == "--frc-switch-points") {
      if (!c.frc) throw std::invalid_argument("--frc-switch-points must follow --frc");
      c.frc->switch_points = integer(0);
    } else if (a == "--frc-sweep") {
      if (!c.frc) throw std::invalid_argument("--frc-sweep must follow --frc");
      c.frc->sweep_points = integer(0, std::numeric_limits<int>::max(), "0: none; else >= 2");
      if (c.frc->sweep_points == 1) throw std::invalid_argument("--frc-sweep needs 0 or at least 2 frequencies");
    } else if (a == "--frc-sweep-settle") {
      if (!c.frc) throw std::invalid_argument("--frc-sweep-settle must follow --frc");
      c.frc->sweep_settle_periods = integer(1);
    } else if (a == "--optimise-step" || a == "--optimise-refine") {
      if (!c.optimal) throw std::invalid_argument(a + " must follow --optimise-preload");
      const double h = number();
      if (!(h > 0) && !(a == "--optimise-refine" && h == 0))
        throw std::invalid_argument(a + " must be > 0" + (a == "--optimise-refine" ? " or 0" : std::string()));
      (a == "--optimise-step" ? c.optimal->step_hz : c.optimal->refine_hz) = h;
    } else if (a == "--optimise-settle") {
      if (!c.optimal) throw std::invalid_argument("--optimise-settle must follow --optimise-preload");
      c.optimal->settle.settle_periods = integer(1);
    } else if (a == "--optimise-frequencies") {
      if (!c.optimal) throw std::invalid_argument("--optimise-frequencies must follow --optimise-preload");
      const std::string text = need(i);
      double lo = 0, hi = 0;
      if (std::sscanf(text.c_str(), "%lf:%lf", &lo, &hi) != 2 || !(lo > 0) || !(hi > lo))
        throw std::invalid_argument("--optimise-frequencies expects lo:hi [Hz] with 0 < lo < hi, got " + text);
      c.optimal->f_lo = lo;
      c.optimal->f_hi = hi;
    } else if (a == "--frc-variational") {
      if (!c.frc) throw std::invalid_argument("--frc-variational must follow --frc");
      c.frc->finite_difference_monodromy = false;
    } else if (a == "--frc-finite-difference") {
      if (!c.frc) throw std::invalid_argument("--frc-finite-difference must follow --frc");
      c.frc->finite_difference_monodromy = true;
    } else if (a == "--optimise-preload") {
      c.optimal = blade::parse_optimal_range(need(i));
    } else if (a == "--threads") {
      c.threads = integer(0, 1024, "0: all cores");
    } else if (a == "--out") {
      c.out = need(i);
    } else {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    }
  }
  if (demo && !contact_given) c.params.contact = blade::demo_contact_options();  // (end policy: Throw, the default)
  if (!(c.settings.duration > 0)) throw std::invalid_argument("--duration must be > 0");
  if (c.params.platform_elements % 2 != 0)
    throw std::invalid_argument("--platform-elements must be even (the blade tip is the platform's middle node)");
  if (c.preloads.empty() && !c.sweep) c.preloads = c.frc ? std::vector<double>{1.0, 5.0, 26.0} : std::vector<double>{12.0};
  c.settings.record_window = std::min(1.0, c.settings.duration);
  c.settings.fit_energy_window();
  return c;
}

using blade::fmt;
using blade::jnum;
std::string tag(double preload) {
  char b[64];
  std::snprintf(b, sizeof b, "N0_%g", preload);
  return b;
}

/// Natural frequencies [Hz] of the frame alone, and of the all-stuck system reduced on the same
/// retained modes (I + sum m (a a^T + b b^T), omega^2 + sum k b b^T), as the simulation sees it.
struct Frequencies {
  std::vector<double> frame, stuck;
};
Frequencies frequencies(blade::BladeScene& scene) {
  Frequencies fr;
  const auto& omega = scene.basis.omega();
  for (Index j = 0; j < omega.size(); ++j) fr.frame.push_back(omega[j] / (2 * M_PI));
  Eigen::MatrixXd M, K;
  blade::linear_matrices(scene, true, M, K);
  for (double w : blade::linear_frequencies(M, K)) fr.stuck.push_back(w / (2 * M_PI));
  return fr;
}

/// Amplitude spectrum (single-sided, amplitude units) of a uniformly sampled signal, Eigen's FFT.
std::vector<double> amplitude_spectrum(const std::vector<double>& signal) {
  Eigen::FFT<double> fft;
  std::vector<double> in(signal);
  const double mean = in.empty() ? 0.0 : std::accumulate(in.begin(), in.end(), 0.0) / double(in.size());
  for (double& v : in) v -= mean;
  std::vector<std::complex<double>> out;
  fft.fwd(out, in);
  std::vector<double> amp(in.size() / 2 + 1);
  for (std::size_t k = 0; k < amp.size(); ++k)
    amp[k] = (k == 0 ? 1.0 : 2.0) * std::abs(out[k]) / double(in.size());
  return amp;
}

void write_run(const fs::path& dir, const blade::RunRecord& r, const Frequencies& fr, double dt,
               const blade::BladeParameters& p, const blade::RunSettings& s) {
  const std::string t = tag(r.preload);
  {
    std::ofstream o(dir / ("history_" + t + ".csv"));
    o << "t,tip,N1,N2,f1,f2,V1,V2,x1,x2,y1,y2,X1,X2,state1,state2\n";
    for (const auto& w : r.window) {
      o << fmt(w.t) << ',' << fmt(w.tip);
      for (const double* arr : {w.N, w.f, w.V, w.x, w.y, w.X}) o << ',' << fmt(arr[0]) << ',' << fmt(arr[1]);
      o << ',' << w.state[0] << ',' << w.state[1] << '\n';
    }
  }
  {
    std::ofstream o(dir / ("tip_" + t + ".csv"));
    o << "t,tip\n";
    for (std::size_t k = 0; k < r.tip_t.size(); ++k) o << fmt(r.tip_t[k]) << ',' << fmt(r.tip_x[k]) << '\n';
  }
  {
    std::ofstream o(dir / ("events_" + t + ".csv"));
    o << "t,damper,from,to\n";
    for (const auto& e : r.events)
      o << fmt(e.t) << ',' << e.damper << ',' << to_string(e.from) << ',' << to_string(e.to) << '\n';
  }
  if (r.window.size() > 8) {
    std::vector<std::vector<double>> sig(11);
    for (const auto& w : r.window) {
      sig[0].push_back(w.tip);
      for (int i = 0; i < 2; ++i) {
        sig[static_cast<std::size_t>(1 + i)].push_back(w.N[i]);
        sig[static_cast<std::size_t>(3 + i)].push_back(w.f[i]);
        sig[static_cast<std::size_t>(5 + i)].push_back(w.x[i]);
        sig[static_cast<std::size_t>(7 + i)].push_back(w.y[i]);
      }
    }
    std::vector<std::vector<double>> spec;
    for (std::size_t k = 0; k < 9; ++k) spec.push_back(amplitude_spectrum(sig[k]));
    std::ofstream o(dir / ("spectra_" + t + ".csv"));
    o << "frequency_hz,tip,N1,N2,f1,f2,x1,x2,y1,y2\n";
    const double df = 1.0 / (double(r.window.size()) * dt);
    for (std::size_t k = 0; k < spec[0].size(); ++k) {
      o << fmt(double(k) * df);
      for (std::size_t j = 0; j < 9; ++j) o << ',' << fmt(spec[j][k]);
      o << '\n';
    }
  }
  std::ofstream o(dir / ("summary_" + t + ".json"));
  o << "{\n  \"preload_N\": " << jnum(r.preload) << ",\n  \"damper_mass_kg\": " << jnum(p.damper_mass())
    << ",\n  \"status\": \"" << to_string(r.status) << "\",\n  \"message\": \"" << r.message
    << "\",\n  \"t_end\": " << jnum(r.t_end) << ",\n  \"regime\": \"" << r.overall_regime << "\",\n  \"dampers\": [";
  for (int i = 0; i < 2; ++i)
    o << (i ? ", " : "") << "{\"regime\": \"" << r.regime[i].name() << "\", \"stick_fraction\": "
      << jnum(r.regime[i].stick_fraction) << ", \"transitions_per_period\": "
      << jnum(r.regime[i].transitions_per_period) << "}";
  o << "],\n  \"tip_amplitude_max_m\": " << jnum(r.tip_max) << ",\n  \"tip_rms_m\": " << jnum(r.tip_rms)
    << ",\n  \"energy_density_m2\": " << jnum(r.energy_density) << ",\n  \"energy_window_s\": ["
    << jnum(s.energy_t1) << ", " << jnum(s.energy_t2) << "],\n  \"energy_audit_residual_J\": "
    << jnum(r.energy_residual) << ",\n  \"energy_audit_scale_J\": " << jnum(r.energy_scale)
    << ",\n  \"natural_frequencies_frame_hz\": [";
  for (std::size_t k = 0; k < fr.frame.size(); ++k) o << (k ? ", " : "") << jnum(fr.frame[k]);
  o << "],\n  \"natural_frequencies_all_stuck_hz\": [";
  for (std::size_t k = 0; k < fr.stuck.size(); ++k) o << (k ? ", " : "") << jnum(fr.stuck[k]);
  o << "],\n  \"integrator\": \"" << to_string(s.run.integrator) << "\",\n  \"rtol\": " << jnum(s.run.stepper.rtol)
    << ",\n  \"atol\": " << jnum(s.run.stepper.atol) << ",\n  \"cpu_seconds\": " << jnum(r.cpu_seconds)
    << ",\n  \"stats\": {\"accepted_steps\": " << r.stats.accepted_steps
    << ", \"rejected_steps\": " << r.stats.rejected_steps << ", \"rhs_evaluations\": " << r.stats.rhs_evaluations
    << ", \"jacobian_evaluations\": " << r.stats.jacobian_evaluations << ", \"events\": " << r.stats.events
    << "}\n}\n";
}

void print_run(const blade::RunRecord& r, const Frequencies& fr) {
  // A run that stopped before the recording window (or before t2 of the energy window) has no
  // window statistics (or E): printed as n/a (null in the JSON summaries, nan in sweep.csv).
  const auto num = [](double v, const char* format) {
    char buf[32];
    if (!std::isfinite(v)) return std::string("n/a");
    std::snprintf(buf, sizeof buf, format, v);
    return std::string(buf);
  };
  std::printf("N0 = %5.1f N: %-24s tip max %s m, rms %s m, E = %s m^2, stick fractions %s / %s, "
              "%s / %s switches per period, %ld events, %.2f s CPU, f1 frame %.2f Hz, all-stuck %.2f Hz%s%s\n",
              r.preload, r.overall_regime.c_str(), num(r.tip_max, "%.3e").c_str(), num(r.tip_rms, "%.3e").c_str(),
              num(r.energy_density, "%.4e").c_str(), num(r.regime[0].stick_fraction, "%.3f").c_str(),
              num(r.regime[1].stick_fraction, "%.3f").c_str(), num(r.regime[0].transitions_per_period, "%.2f").c_str(),
              num(r.regime[1].transitions_per_period, "%.2f").c_str(), r.total_events, r.cpu_seconds,
              fr.frame.empty() ? 0.0 : fr.frame[0], fr.stuck.empty() ? 0.0 : fr.stuck[0],
              r.status == Status::Success ? "" : " - ", r.status == Status::Success ? "" : r.message.c_str());
  std::printf("           integrator %s: %s\n", r.method.c_str(), r.method_reason.c_str());
}

/// The scene's parameters at this preload.
blade::BladeParameters params_at(const Cli& c, double preload) {
  blade::BladeParameters p = c.params;
  p.preload = preload;
  return p;
}

/// The run settings for this duration: the last second recorded, E over the paper's window.
blade::RunSettings settings_for(const Cli& c, double duration) {
  return blade::settings_for_duration(c.settings, duration);
}

blade::RunRecord run_preload(const Cli& c, double preload, double duration, Frequencies* fr_out) {
  blade::BladeScene scene = blade::make_blade_scene(params_at(c, preload));
  if (fr_out) *fr_out = frequencies(scene);
  return blade::run_scene(scene, settings_for(c, duration));
}

/// Runs the preloads in parallel on --threads workers (all cores by default), printing progress
/// under `what`; the full records of the last window are kept only when `keep_windows`.
/// With `natural`, also fills it with the natural frequencies of each run's scene.
std::vector<blade::RunRecord> run_parallel(const Cli& c, const std::vector<double>& preloads, double duration,
                                           bool keep_windows, const char* what,
                                           std::vector<Frequencies>* natural = nullptr) {
  std::vector<blade::RunRecord> results(preloads.size());
  if (natural) natural->assign(preloads.size(), Frequencies{});
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex print_mutex;
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned nthreads = std::min(c.threads > 0 ? static_cast<unsigned>(c.threads) : hw,
                                     static_cast<unsigned>(std::max<std::size_t>(1, preloads.size())));
  auto worker = [&]() {
    for (std::size_t k = next++; k < preloads.size(); k = next++) {
      results[k] = run_preload(c, preloads[k], duration, natural ? &(*natural)[k] : nullptr);
      if (!keep_windows) results[k].window.clear();
      const std::size_t d = ++done;
      std::lock_guard<std::mutex> lock(print_mutex);
      std::printf("\r%s: %zu/%zu preloads done (last N0 = %.2f N: %s)        ", what, d, preloads.size(),
                  preloads[k], results[k].overall_regime.c_str());
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < nthreads; ++t) pool.emplace_back(worker);
  for (auto& th : pool) th.join();
  std::printf("\n");
  return results;
}

/// One representative preload per regime found in the sweep (blade::choose_representatives),
/// re-run with full records into out/regime_<name>/; prints the choice and why, and writes the
/// representatives' entries of sweep.json to `j`.
void run_representatives(const Cli& c, const fs::path& out, const std::vector<double>& preloads,
                         const std::vector<blade::SweepPoint>& points, double duration, std::ostream& j) {
  std::vector<std::optional<blade::Regime>> regimes;
  for (const auto& p : points) regimes.push_back(p.common);
  const std::vector<blade::Representative> chosen = blade::choose_representatives(preloads, regimes);
  std::printf("regime rule: %s\nrepresentatives: %s\n", blade::regime_rule_text(),
              blade::representative_rule_text());
  std::vector<double> chosen_preloads;
  for (const auto& rep : chosen) chosen_preloads.push_back(rep.preload);
  for (blade::Regime regime : blade::kRegimes) {
    const auto it = std::find_if(chosen.begin(), chosen.end(), [&](const auto& rep) { return rep.regime == regime; });
    if (it == chosen.end())
      std::printf("  %-10s: not found in the sweep (no point where both dampers are in it), no figures\n",
                  blade::to_string(regime));
    else
      std::printf("  %-10s: N0 = %.3g N, the middle point of its widest band %.3g .. %.3g N (%zu of the %zu "
                  "sweep point(s) in this regime, %zu band(s))\n",
                  blade::to_string(regime), it->preload, preloads[it->band_first], preloads[it->band_last],
                  it->band_last - it->band_first + 1, it->points, it->bands);
  }
  std::vector<Frequencies> chosen_fr;
  const std::vector<blade::RunRecord> regime_runs =
      chosen.empty() ? std::vector<blade::RunRecord>{}
                     : run_parallel(c, chosen_preloads, duration, true, "regime runs", &chosen_fr);
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const auto& rep = chosen[k];
    const std::string folder = blade::regime_folder(rep.regime);
    fs::create_directories(out / folder);
    write_run(out / folder, regime_runs[k], chosen_fr[k], c.settings.sample_interval, params_at(c, rep.preload),
              settings_for(c, duration));
    std::printf("%s/ ", folder.c_str());
    print_run(regime_runs[k], chosen_fr[k]);
    j << (k ? ", " : "") << "{\"regime\": \"" << blade::to_string(rep.regime) << "\", \"folder\": \"" << folder
      << "\", \"preload_N\": " << jnum(rep.preload) << ", \"band_from_N\": " << jnum(preloads[rep.band_first])
      << ", \"band_to_N\": " << jnum(preloads[rep.band_last])
      << ", \"band_points\": " << rep.band_last - rep.band_first + 1 << ", \"points\": " << rep.points
      << ", \"bands\": " << rep.bands << ", \"rerun_regime\": \"" << regime_runs[k].overall_regime << "\"}";
  }
}

/// --compare: the library's trade_study() on this scene (blade_compare.hpp); rows in
/// OUT/compare.csv and on the console.
int run_compare(const Cli& c, const fs::path& out) {
  blade::BladeParameters base = c.params;
  base.preload = c.preloads.empty() ? 12.0 : c.preloads.front();
  const auto variants_in = blade::parse_compare_list(c.compare, base, c.settings.run);
  RunOptions<double> ref_run = c.settings.run;
  ref_run.integrator = Integrator::DormandPrince54;
  ref_run.stepper.rtol = c.compare_reference_rtol;
  ref_run.stepper.atol = 1e-3 * c.compare_reference_rtol;
  const auto reference = blade::trade_variant("reference dopri5 rtol=" + fmt(c.compare_reference_rtol), base, ref_run);
  std::vector<TradeVariant<blade::BladeScene::System>> variants;
  for (const auto& v : variants_in) variants.push_back(blade::trade_variant(v.name, v.params, v.run));
  const auto options = blade::compare_options(base, c.settings.duration, c.settings.sample_interval, c.compare_repeats);
  std::printf("compare: N0 = %g N, %g s, samples every %g s, %d repeats, output = blade tip displacement\n",
              base.preload, c.settings.duration, c.settings.sample_interval, c.compare_repeats);
  const auto study = trade_study(reference, variants, options);
  std::printf("reference: %s (%s, %.3g s CPU); validation: %s -> reference tip error <= %.2e of its max\n",
              study.reference.name.c_str(), study.reference.ok() ? "ok" : study.reference.message.c_str(),
              study.reference.cpu_seconds, study.validation_method.c_str(), study.validation.output_error_max);
  std::ofstream o(out / "compare.csv");
  std::vector<TradeRow<double>> rows{study.reference, study.validation};
  rows.insert(rows.end(), study.rows.begin(), study.rows.end());
  write_trade_csv(o, rows);
  std::printf("%-34s %10s %10s %7s %11s %11s %10s %6s %6s %10s\n", "variant", "CPU [s]", "RHS", "events",
              "tip err max", "tip err rms", "switch dt", "missed", "extra", "energy res");
  for (const auto& r : study.rows) {
    if (!r.ok()) {
      std::printf("%-34s failed: %s\n", r.name.c_str(), r.message.c_str());
      continue;
    }
    std::printf("%-34s %10.3g %10ld %7ld %11.2e %11.2e %10.2e %6ld %6ld %10.2e\n", r.name.c_str(), r.cpu_seconds,
                r.rhs_evaluations, r.events, r.output_error_max, r.output_error_rms, r.switch_time_error,
                r.missed_switches, r.extra_switches, r.energy_residual);
  }
  std::printf("rows in %s (plot: /usr/bin/python3 examples/blade_damper/plot.py %s)\n",
              (out / "compare.csv").c_str(), out.c_str());
  return study.reference.ok() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Cli c;
  try {
    c = parse(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_damper: %s\n", e.what());
    return 2;
  }
  try {
    fs::create_directories(c.out);
    const fs::path out(c.out);
    if (!c.compare.empty()) return run_compare(c, out);
    if (c.frc) {
      const int rc = blade::run_frc(c.params, c.preloads, *c.frc, out);
      blade::run_frc_sweeps(c.params, c.preloads, *c.frc, out);
      return rc;
    }
    if (c.optimal) {
      c.optimal->threads = c.threads;
      return blade::run_optimal_preload(c.params, *c.optimal, out);
    }
    std::printf("blade_damper: paper section 3 parameters, %d modes, %d + %d elements, integrator %s "
                "(rtol %.0e), duration %.1f s, output in %s/\n",
                c.params.modes, c.params.blade_elements, c.params.platform_elements,
                to_string(c.settings.run.integrator), c.settings.run.stepper.rtol, c.settings.duration,
                c.out.c_str());
    std::vector<blade::RunRecord> runs;
    for (double preload : c.preloads) {
      Frequencies fr;
      blade::RunRecord r = run_preload(c, preload, c.settings.duration, &fr);
      write_run(out, r, fr, c.settings.sample_interval, params_at(c, preload), settings_for(c, c.settings.duration));
      print_run(r, fr);
      runs.push_back(std::move(r));
    }

    if (c.sweep) {
      const double duration = c.sweep_duration > 0 ? c.sweep_duration : c.settings.duration;
      // The library's sweep runner on --threads threads (blade_sweep.hpp; blade_sweep_mpi runs
      // the same items over MPI ranks and writes the same sweep.csv).
      const std::vector<double> preloads = blade::sweep_preloads(c.sweep_lo, c.sweep_hi, c.sweep_count, c.sweep_log);
      const blade::RunSettings settings = settings_for(c, duration);
      const auto outcomes = run_sweep_threads(
          preloads.size(), [&](std::size_t k) { return blade::sweep_item(c.params, settings, preloads[k]); },
          static_cast<unsigned>(std::max(0, c.threads)),
          [&](std::size_t done, std::size_t n, std::size_t k, const SweepOutcome& o) {
            blade::print_sweep_progress("sweep", done, n, preloads[k], o);
          });
      std::ofstream j(out / "sweep.json");
      blade::write_sweep_files(c.out, duration, preloads, outcomes, j);
      run_representatives(c, out, preloads, blade::sweep_points(preloads, outcomes), duration, j);
      j << "]\n}\n";
    }

    if (!c.preloads.empty()) {
      // Does each of the paper's preloads fall in the paper's regime?
      const struct { double n0; blade::Regime regime; } paper[] = {
          {1.0, blade::Regime::GrossSlip}, {12.0, blade::Regime::StickSlip}, {26.0, blade::Regime::Stick}};
      for (const auto& r : runs)
        for (const auto& pr : paper)
          if (std::abs(r.preload - pr.n0) < 1e-9)
            std::printf("paper: N0 = %g N is in the %s regime; here: %s -> %s\n", pr.n0, blade::to_string(pr.regime),
                        r.overall_regime.c_str(), r.common == pr.regime ? "agrees" : "DIFFERS");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_damper: %s\n", e.what());
    return 1;
  }
  return 0;
}

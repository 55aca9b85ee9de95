#pragma once
/// \file blade_optimal.hpp
/// \brief `blade_damper --optimise-preload lo:hi`: the preload N0* that minimises the blade's
/// resonant tip amplitude A(N0) = the largest tip amplitude (half peak-to-peak) of a stable steady
/// response over the excitation frequency: the period-1 orbit and whatever the structure settles
/// on from rest (subharmonic orbits of period k T, responses that are not periodic), on a
/// frequency grid fine enough to see narrow subharmonic windows. The preload by a coarse log grid
/// and golden sections in ln N0 (resonance_search.hpp). docs/howto/frequency_response.md.

#include "blade_frc.hpp"
#include "blade_settle.hpp"
#include "resonance_search.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/steady_state.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace blade {

/// Settings of the optimal-preload search.
struct OptimalSettings {
  double n_lo = 0.5, n_hi = 40;  ///< preload range [N]
  int grid = 6;                  ///< coarse log-spaced preloads before the golden section
  double log_tol = 0.02;         ///< golden section in ln N0 to this fraction of ln(n_hi / n_lo)
  /// Spacing of the frequency grid at every preload [Hz]. A subharmonic response lives in a
  /// window of frequencies (at 5.28 N a period-3 window 57.0-59.2 Hz, 2.2 Hz wide, whose
  /// amplitude is 37 % above the period-1 peak); a grid of step h samples every window wider
  /// than h at least once and a 2.2 Hz one at least 4 times at h = 0.5 Hz. A narrower window
  /// can be missed.
  double step_hz = 0.5;
  /// The grid's best frequency refined by a golden section over its two neighbouring cells to
  /// this width [Hz] (0: no refinement).
  double refine_hz = 0.05;
  double bracket_margin = 0.05;  ///< frequencies [f_free (1 - m), f_stuck (1 + m)] ...
  double f_lo = 0, f_hi = 0;     ///< ... unless f_hi > f_lo > 0 [Hz] (`--optimise-frequencies`)
  SettleSettings settle;         ///< the transients from rest and their orbits (blade_settle.hpp)
  int threads = 0;               ///< frequencies evaluated at once (0: all cores)
};

/// Parses `--optimise-preload lo:hi` (N, 0 < lo < hi).
inline OptimalSettings parse_optimal_range(const std::string& text) {
  OptimalSettings s;
  if (std::sscanf(text.c_str(), "%lf:%lf", &s.n_lo, &s.n_hi) != 2 || !(s.n_lo > 0) || !(s.n_hi > s.n_lo))
    throw std::invalid_argument("--optimise-preload expects lo:hi [N] with 0 < lo < hi, got " + text);
  return s;
}

/// One steady response evaluated by the search.
struct OptimalOrbit {
  double preload = 0, frequency_hz = 0, tip_amplitude = 0;
  /// "from_rest": what a transient from rest settled on (its period-k T orbit when shooting
  /// converged, else its recorded periods); "period_1": the period-1 orbit shot from that
  /// transient's end where the transient did not settle on period 1 (a coexisting orbit).
  std::string kind = "from_rest";
  int period = 1;            ///< k (period k T); 0: not periodic (no k <= max_period)
  bool orbit = false;        ///< the amplitude is a converged orbit's (else the transient's)
  bool stable = true;        ///< counts in A(N0) (SettledResponse::stable)
  bool asymmetric = false;   ///< the two dampers' stick fractions differ (SettledResponse)
  double stick_fraction[2] = {0, 0};
  double max_multiplier = 0;
  double cpu_seconds = 0;
  std::string message;       ///< a failed run's reason
};

/// The largest stable response at one preload over a frequency range, and which response it is.
struct PreloadPeak {
  bool found = false;
  double amplitude = 0;   ///< A(N0) [m]
  OptimalOrbit peak;      ///< the response that set it
  /// Per period k (0: not periodic), the largest stable amplitude and its response.
  std::map<int, OptimalOrbit> by_period;
  std::vector<OptimalOrbit> responses;  ///< every response evaluated
  int frequencies = 0;                  ///< frequencies evaluated (grid and refinement)
};

/// The steady responses of `scene` at preload n0 and omega [rad/s]: what a transient from rest
/// settles on (blade_settle.hpp), and where that is not period 1 the period-1 orbit shot from its
/// end (a stable one coexists with the response from rest and counts too).
inline std::vector<OptimalOrbit> responses_at(BladeScene& scene, double n0, double omega, const SettleSettings& s) {
  BladeParameters q = scene.parameters;
  q.preload = n0;
  scene.parameters = q;
  const SettledResponse r = settle_from_rest(scene, omega, s);
  std::vector<OptimalOrbit> out;
  OptimalOrbit o;
  o.preload = n0;
  o.frequency_hz = omega / (2 * M_PI);
  o.period = r.period;
  o.orbit = r.orbit;
  o.stable = r.stable;
  o.asymmetric = r.asymmetric;
  o.tip_amplitude = r.tip_amplitude;
  o.stick_fraction[0] = r.stick_fraction[0];
  o.stick_fraction[1] = r.stick_fraction[1];
  o.max_multiplier = r.max_multiplier;
  o.cpu_seconds = r.cpu_seconds;
  o.message = r.message;
  out.push_back(o);
  if (!r.ok() || r.period == 1) return out;
  const double cpu0 = stickslip::detail::thread_cpu_seconds();
  auto opt = blade_shooting_options(*scene.system, false);
  opt.max_iterations = s.max_newton_iterations;
  add_tip_output(scene, opt);
  stickslip::Shooting<BladeScene::System> shooting(*scene.system, opt);
  const auto orbit = shooting.forced(r.end_mode, 0.0, r.end_state, 2 * M_PI / omega);
  if (!orbit.ok()) return out;
  SettledResponse one;
  settled_statistics(orbit, one);
  OptimalOrbit p1 = o;
  p1.kind = "period_1";
  p1.period = 1;
  p1.orbit = true;
  p1.stable = orbit.floquet.stable;
  p1.max_multiplier = orbit.floquet.max_modulus;
  p1.tip_amplitude = orbit.outputs.at(0).amplitude();
  p1.asymmetric = one.asymmetric;
  p1.stick_fraction[0] = one.stick_fraction[0];
  p1.stick_fraction[1] = one.stick_fraction[1];
  p1.cpu_seconds = stickslip::detail::thread_cpu_seconds() - cpu0;
  out.push_back(p1);
  return out;
}

/// The largest stable amplitude among `responses` (index), or responses.size() when none counts.
inline std::size_t largest_stable(const std::vector<OptimalOrbit>& responses) {
  std::size_t best = responses.size();
  for (std::size_t i = 0; i < responses.size(); ++i) {
    const OptimalOrbit& o = responses[i];
    if (!o.message.empty() || !o.stable || !std::isfinite(o.tip_amplitude)) continue;
    if (best == responses.size() || o.tip_amplitude > responses[best].tip_amplitude) best = i;
  }
  return best;
}

/// A(N0) over [f_lo, f_hi] [Hz] at preload n0: responses_at() on a uniform grid of spacing at
/// most s.step_hz (in parallel on `scenes`, one scene per thread, each a scene of the same
/// structure), then a golden section of the largest stable amplitude over the two grid cells
/// around the grid's best frequency, to s.refine_hz. `on_response` sees every response (under a
/// lock). Not found when no stable response was found.
inline PreloadPeak preload_peak(std::vector<BladeScene>& scenes, double n0, double f_lo, double f_hi,
                                const OptimalSettings& s,
                                const std::function<void(const OptimalOrbit&)>& on_response = {}) {
  if (scenes.empty()) throw std::invalid_argument("preload_peak: scenes must not be empty");
  if (!(f_hi > f_lo) || !(f_lo > 0)) throw std::invalid_argument("preload_peak: need 0 < f_lo < f_hi");
  if (!(s.step_hz > 0)) throw std::invalid_argument("preload_peak: step_hz must be > 0");
  PreloadPeak out;
  std::mutex lock;
  auto value_of = [](const std::vector<OptimalOrbit>& rs) {
    const std::size_t b = largest_stable(rs);
    return b < rs.size() ? rs[b].tip_amplitude : -HUGE_VAL;
  };
  auto record = [&](const std::vector<OptimalOrbit>& rs) {
    std::lock_guard<std::mutex> g(lock);
    ++out.frequencies;
    for (const OptimalOrbit& o : rs) {
      out.responses.push_back(o);
      if (on_response) on_response(o);
    }
  };
  const int n = std::max(2, static_cast<int>(std::ceil((f_hi - f_lo) / s.step_hz - 1e-9)) + 1);
  std::vector<double> grid(static_cast<std::size_t>(n)), value(static_cast<std::size_t>(n), -HUGE_VAL);
  for (int k = 0; k < n; ++k) grid[static_cast<std::size_t>(k)] = f_lo + (f_hi - f_lo) * k / (n - 1);
  std::atomic<std::size_t> next{0};
  auto worker = [&](BladeScene& scene) {
    for (std::size_t k = next++; k < grid.size(); k = next++) {
      const auto rs = responses_at(scene, n0, 2 * M_PI * grid[k], s.settle);
      value[k] = value_of(rs);
      record(rs);
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t threads = std::min<std::size_t>(
      {scenes.size(), grid.size(), s.threads > 0 ? static_cast<std::size_t>(s.threads) : hw});
  if (threads <= 1) {
    worker(scenes[0]);
  } else {
    std::vector<std::thread> pool;
    for (std::size_t t = 0; t < threads; ++t) pool.emplace_back(worker, std::ref(scenes[t]));
    for (auto& th : pool) th.join();
  }
  const auto best = static_cast<std::size_t>(std::max_element(value.begin(), value.end()) - value.begin());
  if (s.refine_hz > 0 && value[best] > -HUGE_VAL) {
    const double a = grid[best == 0 ? 0 : best - 1], b = grid[std::min(best + 1, grid.size() - 1)];
    golden_minimum(
        [&](double f) {
          const auto rs = responses_at(scenes[0], n0, 2 * M_PI * f, s.settle);
          record(rs);
          const double v = value_of(rs);
          return std::isfinite(v) ? -v : HUGE_VAL;
        },
        a, b, s.refine_hz);
  }
  const std::size_t top = largest_stable(out.responses);
  if (top == out.responses.size()) return out;
  out.found = true;
  out.peak = out.responses[top];
  out.amplitude = out.peak.tip_amplitude;
  for (const OptimalOrbit& o : out.responses) {
    if (!o.message.empty() || !o.stable || !std::isfinite(o.tip_amplitude)) continue;
    auto it = out.by_period.find(o.period);
    if (it == out.by_period.end() || o.tip_amplitude > it->second.tip_amplitude) out.by_period[o.period] = o;
  }
  return out;
}

/// "period 3 T, from rest" and the like: which response an OptimalOrbit is.
inline std::string response_name(const OptimalOrbit& o) {
  std::string t = o.period == 0 ? std::string("not periodic") : "period " + std::to_string(o.period) + " T";
  t += o.kind == "period_1" ? ", period-1 orbit coexisting with the response from rest" : ", reached from rest";
  if (!o.orbit) t += " (amplitude over the transient's recorded periods)";
  if (o.asymmetric) t += ", asymmetric";
  return t;
}

/// `blade_damper --optimise-preload lo:hi`: N0* and A(N0*), files optimal.csv (every response),
/// optimal_peaks.csv (A(N0) per preload evaluated, with the largest per period) and optimal.json.
/// Returns the exit code.
inline int run_optimal_preload(BladeParameters p, const OptimalSettings& s, const std::filesystem::path& out) {
  if (!(p.damping_ratio > 0)) {
    p.damping_ratio = 0.05;
    std::printf("optimal: steady states need damping (docs/steady_state.md): modal damping ratio 0.05 "
                "(--damping to change)\n");
  }
  p.model.energy_audit = false;
  const double cpu0 = stickslip::detail::thread_cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const unsigned nthreads = s.threads > 0 ? static_cast<unsigned>(s.threads) : hw;
  std::vector<BladeScene> scenes;
  for (unsigned t = 0; t < nthreads; ++t) scenes.push_back(make_blade_scene(p));
  std::vector<OptimalOrbit> orbits;
  std::vector<PreloadPeak> peaks;
  double cpu_responses = 0, main_responses = 0;
  const auto main_id = std::this_thread::get_id();
  // The frequencies at n0: the given range, or the bracket of the lowest resonance between the
  // frictionless and all-stuck linear limits (the damper mass 2 N0 / (r Omega^2) moves both).
  auto range = [&](double n0) {
    if (s.f_hi > s.f_lo && s.f_lo > 0) return std::make_pair(s.f_lo, s.f_hi);
    BladeParameters q = scenes[0].parameters;
    q.preload = n0;
    *scenes[0].system = make_blade_system(scenes[0], q);
    scenes[0].parameters = q;
    const auto limits = blade_linear_limits(scenes[0]);
    const double f_stuck = limits[0].natural_frequencies_hz().front(), f_free = limits[1].natural_frequencies_hz().front();
    return std::make_pair(f_free * (1 - s.bracket_margin), f_stuck * (1 + s.bracket_margin));
  };
  auto resonant = [&](double log_n0) {
    const double n0 = std::exp(log_n0);
    const auto [lo, hi] = range(n0);
    std::printf("optimal: N0 %.4g N: %.2f..%.2f Hz every <= %.2f Hz, transients of %d periods from rest\n", n0, lo, hi,
                s.step_hz, s.settle.settle_periods);
    std::fflush(stdout);
    PreloadPeak pk = preload_peak(scenes, n0, lo, hi, s, [&](const OptimalOrbit& o) {
      orbits.push_back(o);
      cpu_responses += o.cpu_seconds;
      if (std::this_thread::get_id() == main_id) main_responses += o.cpu_seconds;
      std::printf("optimal: N0 %8.4f N  f %7.3f Hz  tip %.4e m  %-9s %-8s %s%s  %.2f s\n", n0, o.frequency_hz,
                  o.tip_amplitude, o.period == 0 ? "aperiodic" : ("period " + std::to_string(o.period)).c_str(),
                  o.stable ? "stable" : "unstable", o.kind.c_str(), o.asymmetric ? "  asymmetric" : "", o.cpu_seconds);
      std::fflush(stdout);
    });
    peaks.push_back(pk);
    if (!pk.found) {
      std::printf("optimal: N0 %g N: no stable response found\n", n0);
      return std::numeric_limits<double>::quiet_NaN();
    }
    std::printf("optimal: N0 %g N: largest stable tip amplitude %.4e m at %.3f Hz (%s)\n", n0, pk.amplitude,
                pk.peak.frequency_hz, response_name(pk.peak).c_str());
    for (const auto& [k, o] : pk.by_period)
      std::printf("optimal: N0 %g N:   %-14s largest %.4e m at %.3f Hz\n", n0,
                  k == 0 ? "not periodic" : ("period " + std::to_string(k) + " T").c_str(), o.tip_amplitude,
                  o.frequency_hz);
    std::fflush(stdout);
    return pk.amplitude;
  };
  std::printf("optimal: preload %g..%g N (grid %d, then golden sections in ln N0 to %g); at each preload the "
              "largest stable response over a %.2f Hz frequency grid (refined to %.2f Hz), damping %.3g, %u threads\n",
              s.n_lo, s.n_hi, s.grid, s.log_tol, s.step_hz, s.refine_hz, p.damping_ratio, nthreads);
  const Extremum best = grid_golden_minimum(resonant, std::log(s.n_lo), std::log(s.n_hi),
                                            s.log_tol * (std::log(s.n_hi) - std::log(s.n_lo)), s.grid);
  // Every response's CPU on its own thread, and the rest of the search on this one.
  const double cpu = cpu_responses + std::max(0.0, stickslip::detail::thread_cpu_seconds() - cpu0 - main_responses);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  {
    std::ofstream o(out / "optimal.csv");
    o << "preload_N,frequency_hz,tip_amplitude_m,period_T,kind,orbit,stable,asymmetric,max_multiplier,"
         "stick_fraction_1,stick_fraction_2,cpu_s\n";
    for (const auto& r : orbits)
      o << fmt(r.preload) << ',' << fmt(r.frequency_hz) << ',' << fmt(r.tip_amplitude) << ',' << r.period << ','
        << r.kind << ',' << (r.orbit ? 1 : 0) << ',' << (r.stable ? 1 : 0) << ',' << (r.asymmetric ? 1 : 0) << ','
        << fmt(r.max_multiplier) << ',' << fmt(r.stick_fraction[0]) << ',' << fmt(r.stick_fraction[1]) << ','
        << fmt(r.cpu_seconds) << '\n';
  }
  {
    std::ofstream o(out / "optimal_peaks.csv");
    o << "preload_N,peak_frequency_hz,resonant_tip_amplitude_m,peak_period_T,peak_kind,peak_1T_m,peak_subharmonic_m,"
         "peak_not_periodic_m\n";
    for (const auto& pk : peaks) {
      if (!pk.found) continue;
      double one = 0, sub = 0, none = 0;  // the largest stable: period 1, period k > 1, not periodic
      for (const auto& [k, r] : pk.by_period) {
        double& slot = k == 1 ? one : k == 0 ? none : sub;
        slot = std::max(slot, r.tip_amplitude);
      }
      o << fmt(pk.peak.preload) << ',' << fmt(pk.peak.frequency_hz) << ',' << fmt(pk.amplitude) << ',' << pk.peak.period
        << ',' << pk.peak.kind << ',' << fmt(one) << ',' << fmt(sub) << ',' << fmt(none) << '\n';
    }
  }
  const double n_star = std::exp(best.x);
  const PreloadPeak* at = nullptr;
  for (const auto& pk : peaks)
    if (pk.found && std::abs(pk.peak.preload - n_star) <= 1e-12 * n_star) at = &pk;
  std::ofstream j(out / "optimal.json");
  j << "{\n  \"ok\": " << (best.ok && at ? "true" : "false") << ", \"message\": \"" << json_escape(best.message)
    << "\",\n  \"optimal_preload_N\": " << jnum(n_star) << ", \"resonant_tip_amplitude_m\": " << jnum(best.value);
  if (at) {
    j << ",\n  \"peak_frequency_hz\": " << jnum(at->peak.frequency_hz) << ", \"peak_period_T\": " << at->peak.period
      << ", \"peak_kind\": \"" << at->peak.kind << "\", \"peak_orbit\": " << (at->peak.orbit ? "true" : "false")
      << ", \"peak_asymmetric\": " << (at->peak.asymmetric ? "true" : "false") << ", \"peak_response\": \""
      << response_name(at->peak) << "\",\n  \"largest_by_period\": [";
    std::size_t q = 0;
    for (const auto& [k, r] : at->by_period)
      j << (q++ ? ", " : "") << "{\"period_T\": " << k << ", \"tip_amplitude_m\": " << jnum(r.tip_amplitude)
        << ", \"frequency_hz\": " << jnum(r.frequency_hz) << ", \"kind\": \"" << r.kind << "\"}";
    j << "]";
  }
  j << ",\n  \"preload_range_N\": [" << jnum(s.n_lo) << ", " << jnum(s.n_hi) << "], \"grid\": " << s.grid
    << ", \"log_tol\": " << jnum(s.log_tol) << ", \"step_hz\": " << jnum(s.step_hz) << ", \"refine_hz\": "
    << jnum(s.refine_hz) << ", \"settle_periods\": " << s.settle.settle_periods << ", \"damping_ratio\": "
    << jnum(p.damping_ratio) << ", \"force_N\": " << jnum(p.force) << ",\n  \"peaks\": " << peaks.size()
    << ", \"responses\": " << orbits.size() << ", \"cpu_s\": " << jnum(cpu) << ", \"wall_s\": " << jnum(wall) << "\n}\n";
  if (!best.ok || !at) {
    std::printf("optimal: failed: %s\n", best.ok ? "no stable response at the optimum" : best.message.c_str());
    return 1;
  }
  std::printf("optimal: N0* = %.4g N, resonant tip amplitude %.4e m at %.3f Hz, set by: %s (%zu preloads, %zu "
              "responses, %.1f s CPU, %.1f s elapsed); files optimal.csv, optimal_peaks.csv, optimal.json in %s\n",
              n_star, best.value, at->peak.frequency_hz, response_name(at->peak).c_str(), peaks.size(), orbits.size(),
              cpu, wall, out.string().c_str());
  return 0;
}

}  // namespace blade

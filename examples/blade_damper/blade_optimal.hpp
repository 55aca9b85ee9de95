#pragma once
/// \file blade_optimal.hpp
/// \brief `blade_damper --optimise-preload lo:hi`: the preload N0* that minimises the blade's
/// resonant tip amplitude A(N0) = max over the excitation frequency of the periodic orbit's tip
/// amplitude (half peak-to-peak), by resonance_search.hpp's min-max search: a coarse log grid of
/// N0, then golden sections in log N0 and, at each N0, a coarse frequency grid and a golden
/// section between the frictionless and the all-stuck lowest resonances. Each amplitude is one orbit found by shooting from the
/// end of a transient (or, when shooting fails, a longer transient's last period).
/// docs/howto/frequency_response.md.

#include "blade_frc.hpp"
#include "resonance_search.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/steady_state.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace blade {

/// Settings of the optimal-preload search.
struct OptimalSettings {
  double n_lo = 0.5, n_hi = 40;  ///< preload range [N]
  int grid = 6;                  ///< coarse log-spaced preloads before the golden section
  double log_tol = 0.02;         ///< golden section in ln N0 to this fraction of ln(n_hi / n_lo)
  double omega_tol = 0.01;       ///< golden section in frequency to this fraction of the bracket
  /// Uniform frequencies over each bracket before the golden section in frequency (a response
  /// with two peaks, or a flat top, fools a golden section over the whole bracket).
  int omega_grid = 7;
  double bracket_margin = 0.05;  ///< bracket [f_free (1 - m), f_stuck (1 + m)]
  int transient_periods = 60;    ///< periods of the transient from rest before shooting
};

/// Parses `--optimise-preload lo:hi` (N, 0 < lo < hi).
inline OptimalSettings parse_optimal_range(const std::string& text) {
  OptimalSettings s;
  if (std::sscanf(text.c_str(), "%lf:%lf", &s.n_lo, &s.n_hi) != 2 || !(s.n_lo > 0) || !(s.n_hi > s.n_lo))
    throw std::invalid_argument("--optimise-preload expects lo:hi [N] with 0 < lo < hi, got " + text);
  return s;
}

/// One orbit evaluated by the search.
struct OptimalOrbit {
  double preload = 0, frequency_hz = 0, tip_amplitude = 0;
  double stick_fraction[2] = {0, 0};
  /// "orbit" (shooting), or "transient" (shooting failed: the last period of a 2 x
  /// transient_periods transient, stick fractions not computed).
  std::string steady = "orbit";
  int runs = 0;       ///< orbit runs of the shooting
  double cpu_seconds = 0;
};

/// `blade_damper --optimise-preload lo:hi`: N0* and A(N0*), files optimal.csv (every orbit),
/// optimal_peaks.csv (A(N0) per preload evaluated) and optimal.json. Returns the exit code.
inline int run_optimal_preload(BladeParameters p, const OptimalSettings& s, const std::filesystem::path& out) {
  if (!(p.damping_ratio > 0)) {
    p.damping_ratio = 0.05;
    std::printf("optimal: steady states need damping (docs/steady_state.md): modal damping ratio 0.05 "
                "(--damping to change)\n");
  }
  p.model.energy_audit = false;
  const double cpu0 = stickslip::detail::thread_cpu_seconds();
  BladeScene scene = make_blade_scene(p);
  std::vector<OptimalOrbit> orbits;
  std::vector<std::array<double, 3>> peaks;  // N0, f [Hz], A
  auto set = [&](double n0, double omega) {
    BladeParameters q = scene.parameters;
    q.preload = n0;
    q.force_omega = omega;
    *scene.system = make_blade_system(scene, q);
    scene.parameters = q;
  };
  auto amplitude = [&](double log_n0, double omega) {
    const double n0 = std::exp(log_n0), c0 = stickslip::detail::thread_cpu_seconds();
    set(n0, omega);
    auto opt = blade_shooting_options(*scene.system, true);
    add_tip_output(scene, opt);
    // From the transient's end Newton converges in 1-2 runs or not at all (stalls near a
    // grazing cost 40-50 s with the default 30 iterations): give up after 8.
    opt.max_iterations = 8;
    OptimalOrbit r;
    r.preload = n0;
    r.frequency_hz = omega / (2 * M_PI);
    // Shot from a transient from rest, not from the previous orbit: with 5 % damping the
    // transient's end is the orbit to ~1e-8 and shooting confirms it in 1-2 runs, while Newton
    // from the orbit at another frequency (the golden section jumps by up to 24 % of the
    // bracket) took 20-64 runs (measured at N0 = 0.5 N).
    stickslip::PeriodicOrbit<BladeScene::System> orbit = blade_start_orbit(*scene.system, scene.parameters.force_omega, s.transient_periods, opt);
    if (!orbit.ok()) {
      // No orbit by shooting (Newton stalls, e.g. near a grazing): the steady state by a longer
      // transient (with 5 % damping 60 periods already decay a transient by e^-19), its last
      // period measured as the orbit's.
      std::printf("optimal: no orbit by shooting at N0 %g N, %.3f Hz (%s): the state after %d periods instead\n", n0,
                  r.frequency_hz, orbit.message.c_str(), 2 * s.transient_periods);
      auto& sys = *scene.system;
      BladeScene::System::State x = sys.initial_state();
      BladeScene::System::Mode mode = sys.requested_mode();
      stickslip::HybridStepper<BladeScene::System, stickslip::DormandPrince54> stepper(sys, opt.stepper);
      if (!sys.make_consistent(mode, 0.0, x)) return std::numeric_limits<double>::quiet_NaN();
      const auto tr = stepper.integrate(mode, 0.0, x, 2 * s.transient_periods * 2 * M_PI / omega);
      if (!tr.ok()) return std::numeric_limits<double>::quiet_NaN();
      const auto range = transient_tip_range(scene, sys, tr.mode, tr.t, tr.x, 2 * M_PI / omega, opt.stepper);
      r.tip_amplitude = (range[1] - range[0]) / 2;
      r.steady = "transient";
    } else {
      r.tip_amplitude = orbit.outputs.at(0).amplitude();  // over the orbit's own period
    }
    for (Eigen::Index i = 0; i < 2; ++i)
      r.stick_fraction[i] = orbit.ok() ? stickslip::orbit_contact_statistics(orbit, i).stick_fraction
                                       : std::numeric_limits<double>::quiet_NaN();
    r.runs = orbit.iterations;
    r.cpu_seconds = stickslip::detail::thread_cpu_seconds() - c0;
    std::printf("optimal: N0 %8.4f N  f %7.3f Hz  tip %.4e m  stick %.2f/%.2f  runs %d%s  %.2f s\n", n0, r.frequency_hz,
                r.tip_amplitude, r.stick_fraction[0], r.stick_fraction[1], r.runs, r.steady == "orbit" ? "" : " (transient only)",
                r.cpu_seconds);
    std::fflush(stdout);
    orbits.push_back(r);
    return r.tip_amplitude;
  };
  // The resonance lies between the lowest frictionless and all-stuck natural frequencies of
  // the model's linear part at that preload (the damper mass 2 N0 / (r Omega^2) moves both).
  auto bracket = [&](double log_n0) {
    set(std::exp(log_n0), scene.parameters.force_omega);
    const auto limits = blade_linear_limits(scene);
    const double f_stuck = limits[0].natural_frequencies_hz().front(), f_free = limits[1].natural_frequencies_hz().front();
    return std::make_pair(2 * M_PI * f_free * (1 - s.bracket_margin), 2 * M_PI * f_stuck * (1 + s.bracket_margin));
  };
  std::printf("optimal: preload %g..%g N (grid %d, then golden sections; per preload %d frequencies, then a "
              "golden section), damping %.3g\n",
              s.n_lo, s.n_hi, s.grid, s.omega_grid, p.damping_ratio);
  const MinMax best = min_max_amplitude(amplitude, bracket, std::log(s.n_lo), std::log(s.n_hi), s.log_tol, s.omega_tol,
                                        s.grid, [&](double log_n0, double omega, double a) {
                                          peaks.push_back({std::exp(log_n0), omega / (2 * M_PI), a});
                                          std::printf("optimal: N0 %g N: resonant tip amplitude %.4e m at %.3f Hz\n",
                                                      std::exp(log_n0), a, omega / (2 * M_PI));
                                          std::fflush(stdout);
                                        },
                                        s.omega_grid);
  const double cpu = stickslip::detail::thread_cpu_seconds() - cpu0;
  {
    std::ofstream o(out / "optimal.csv");
    o << "preload_N,frequency_hz,tip_amplitude_m,stick_fraction_1,stick_fraction_2,steady_state,newton_runs,cpu_s\n";
    for (const auto& r : orbits)
      o << fmt(r.preload) << ',' << fmt(r.frequency_hz) << ',' << fmt(r.tip_amplitude) << ',' << fmt(r.stick_fraction[0])
        << ',' << fmt(r.stick_fraction[1]) << ',' << r.steady << ',' << r.runs << ',' << fmt(r.cpu_seconds) << '\n';
  }
  {
    std::ofstream o(out / "optimal_peaks.csv");
    o << "preload_N,peak_frequency_hz,resonant_tip_amplitude_m\n";
    for (const auto& r : peaks) o << fmt(r[0]) << ',' << fmt(r[1]) << ',' << fmt(r[2]) << '\n';
  }
  const double n_star = std::exp(best.parameter.x);
  std::ofstream j(out / "optimal.json");
  j << "{\n  \"ok\": " << (best.parameter.ok ? "true" : "false") << ", \"message\": \"" << json_escape(best.parameter.message)
    << "\",\n  \"optimal_preload_N\": " << jnum(n_star) << ", \"resonant_tip_amplitude_m\": " << jnum(best.parameter.value)
    << ", \"peak_frequency_hz\": " << jnum(best.omega / (2 * M_PI)) << ",\n  \"preload_range_N\": [" << jnum(s.n_lo) << ", "
    << jnum(s.n_hi) << "], \"grid\": " << s.grid << ", \"omega_grid\": " << s.omega_grid << ", \"log_tol\": " << jnum(s.log_tol) << ", \"omega_tol\": "
    << jnum(s.omega_tol) << ", \"damping_ratio\": " << jnum(p.damping_ratio) << ", \"force_N\": " << jnum(p.force)
    << ",\n  \"peaks\": " << peaks.size() << ", \"orbits\": " << orbits.size() << ", \"cpu_s\": " << jnum(cpu) << "\n}\n";
  if (!best.parameter.ok) {
    std::printf("optimal: failed: %s\n", best.parameter.message.c_str());
    return 1;
  }
  std::printf("optimal: N0* = %.4g N, resonant tip amplitude %.4e m at %.3f Hz (%zu peaks, %zu orbits, %.1f s CPU); "
              "files optimal.csv, optimal_peaks.csv, optimal.json in %s\n",
              n_star, best.parameter.value, best.omega / (2 * M_PI), peaks.size(), orbits.size(), cpu, out.string().c_str());
  return 0;
}

}  // namespace blade

#pragma once
/// \file blade_settle.hpp
/// \brief What the blade settles on at one excitation frequency: a transient (from rest, or from
/// the state a previous frequency left), Poincaré sections x(nT) that name its period k (the
/// smallest k <= 8 with x(nT) = x((n - k) T), stickslip::poincare_sections), the period-k T orbit
/// shot from the last section with its Floquet multipliers, and the tip's amplitude over the
/// orbit's own k T. The `--frc` overlay (sweeps up and down in frequency) and the objective of
/// `--optimise-preload` (the largest stable response, subharmonics included) are built on it.
/// docs/howto/frequency_response.md.

#include "blade_frc.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/steady_state.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <limits>
#include <string>
#include <vector>

namespace blade {

/// Settings of settle().
struct SettleSettings {
  /// Forcing periods integrated before the first section. With 5 % modal damping a free
  /// transient of the lowest mode (~f) decays by exp(-2 pi 0.05 n) over n periods: 150 periods
  /// leave e^-47 of it; a subharmonic response attracts more slowly (its multipliers are those of
  /// the k T map), which is why this is longer than the 60 periods before a period-1 shooting.
  int settle_periods = 150;
  int record_periods = 24;  ///< sections recorded after the settle (>= 2 max_period)
  int max_period = 8;       ///< the largest k looked for
  /// Newton iterations of the period-k T orbit shot from the last section (from a settled state
  /// Newton converges in 1-3 runs or not at all).
  int max_newton_iterations = 8;
  bool shoot = true;  ///< shoot the period-k T orbit (its stability and its own amplitude)
};

/// A response the blade settles on at one frequency.
struct SettledResponse {
  double frequency_hz = 0;
  /// k: the sections repeat every k forcing periods (1: period 1; k > 1: subharmonic of order
  /// k); 0: no k <= max_period (quasi-periodic, chaotic or not yet settled).
  int period = 0;
  std::string verdict;  ///< stickslip::PoincareStatus name of the sections
  bool orbit = false;   ///< the period-k T orbit converged from the last section
  /// The orbit's Floquet verdict (max |mu| <= 1 + tolerance). Without an orbit: true, since the
  /// transient reached this response and stayed on it over the recorded periods.
  bool stable = true;
  double max_multiplier = std::numeric_limits<double>::quiet_NaN();  ///< the orbit's largest |mu|
  /// Half the tip's peak-to-peak [m]: over the orbit's own k T, or, without an orbit, over
  /// the recorded periods.
  double tip_amplitude = std::numeric_limits<double>::quiet_NaN();
  /// Per damper, the stick fraction over the orbit (NaN without an orbit).
  double stick_fraction[2] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  /// The two dampers behave differently: their stick fractions differ by more than 0.02 (the
  /// two are mirror images, so an orbit that maps onto itself under the mirror, shifted by half
  /// a period, has equal ones).
  bool asymmetric = false;
  double cpu_seconds = 0;
  BladeScene::System::Mode end_mode;    ///< the mode at the last section
  BladeScene::System::State end_state;  ///< the state at the last section (a whole period: phase 0)
  std::string message;                  ///< why a run failed (empty otherwise)
  bool ok() const { return message.empty(); }
};

/// Sets `scene`'s system to the excitation frequency omega [rad/s].
inline void set_blade_frequency(BladeScene& scene, double omega) {
  BladeParameters q = scene.parameters;
  q.force_omega = omega;
  *scene.system = make_blade_system(scene, q);
  scene.parameters = q;
}

/// Stick fractions and the asymmetry flag of a response from its orbit.
inline void settled_statistics(const stickslip::PeriodicOrbit<BladeScene::System>& orbit, SettledResponse& r) {
  for (Eigen::Index i = 0; i < 2; ++i)
    r.stick_fraction[i] = stickslip::orbit_contact_statistics(orbit, i).stick_fraction;
  r.asymmetric = std::abs(r.stick_fraction[0] - r.stick_fraction[1]) > 0.02;
}

/// The response of `scene` at omega [rad/s] after s.settle_periods forcing periods from (mode, x)
/// at t = 0 (the forcing's phase is 0 at every whole period, so the state a run at another
/// frequency left after whole periods is a start here): its period k from s.record_periods
/// sections, and with s.shoot the period-k T orbit shot from the last section (variational
/// monodromy, the tip's extremes from the orbit's own run). An undecided verdict (a recurrence
/// within 10x of the tolerance) is shot like a periodic one: Newton decides.
inline SettledResponse settle(BladeScene& scene, double omega, const BladeScene::System::Mode& mode,
                              const BladeScene::System::State& x, const SettleSettings& s) {
  const double cpu0 = stickslip::detail::thread_cpu_seconds();
  set_blade_frequency(scene, omega);
  auto& sys = *scene.system;
  auto opt = blade_shooting_options(sys, false);
  opt.max_iterations = s.max_newton_iterations;
  add_tip_output(scene, opt);
  stickslip::PoincareOptions<double> po;
  po.transient_periods = s.settle_periods;
  po.record_periods = s.record_periods;
  po.max_period = s.max_period;
  po.periodic = opt.periodic;
  po.stepper = opt.stepper;
  const double T = 2 * M_PI / omega;
  TipObserver tips;  // (blade_frc.hpp)
  tips.scene = &scene;
  const auto sections = stickslip::poincare_sections(sys, mode, 0.0, x, T, po, tips);
  SettledResponse r;
  r.frequency_hz = omega / (2 * M_PI);
  r.verdict = stickslip::to_string(sections.status);
  if (sections.status == stickslip::PoincareStatus::IntegrationFailed) {
    r.message = sections.message;
    r.cpu_seconds = stickslip::detail::thread_cpu_seconds() - cpu0;
    return r;
  }
  r.period = sections.period;
  r.end_mode = sections.modes.back();
  r.end_state = sections.states.back();
  r.tip_amplitude = tips.seen ? (tips.hi - tips.lo) / 2 : 0.0;
  if (s.shoot && r.period > 0) {
    stickslip::Shooting<BladeScene::System> shooting(sys, opt);
    const auto orbit = shooting.forced(r.end_mode, 0.0, r.end_state, r.period * T);
    if (orbit.ok()) {
      r.orbit = true;
      r.stable = orbit.floquet.stable;
      r.max_multiplier = orbit.floquet.max_modulus;
      r.tip_amplitude = orbit.outputs.at(0).amplitude();
      settled_statistics(orbit, r);
    }
  }
  r.cpu_seconds = stickslip::detail::thread_cpu_seconds() - cpu0;
  return r;
}

/// settle() from rest.
inline SettledResponse settle_from_rest(BladeScene& scene, double omega, const SettleSettings& s) {
  set_blade_frequency(scene, omega);
  BladeScene::System::Mode mode;
  BladeScene::System::State x;
  blade_rest_start(*scene.system, mode, x);
  return settle(scene, omega, mode, x, s);
}

/// A stepped frequency sweep over `hz` in the order given (ascending: a sweep up; descending: a
/// sweep down): the first frequency from rest, each next one from the state the previous left
/// (its last section), so that the sweep stays on the response it is on until that response
/// ends, as a slow sweep of a test rig does. A failed run restarts the next frequency from rest.
/// `progress` is called after each frequency.
template <class Progress>
std::vector<SettledResponse> frequency_sweep(BladeScene& scene, const std::vector<double>& hz, const SettleSettings& s,
                                             Progress&& progress) {
  std::vector<SettledResponse> out;
  for (double f : hz) {
    const double omega = 2 * M_PI * f;
    if (out.empty() || !out.back().ok()) {
      out.push_back(settle_from_rest(scene, omega, s));
    } else {
      const SettledResponse& last = out.back();
      const auto mode = last.end_mode;
      const auto x = last.end_state;
      out.push_back(settle(scene, omega, mode, x, s));
    }
    progress(out.back());
  }
  return out;
}

/// `--frc ... --frc-sweep n`: at each preload a sweep up and a sweep down over n uniform
/// frequencies of [f_lo, f_hi] (frequency_sweep, the two at once on two threads), each frequency
/// settling for s.sweep_settle_periods periods; rows in OUT/frc_sweep.csv (preload, direction,
/// frequency, the response's period k (0: none <= 8), Poincaré verdict, whether its k T orbit
/// converged and is stable, asymmetric, tip amplitude, stick fractions, largest |mu|, CPU).
inline void run_frc_sweeps(BladeParameters p, const std::vector<double>& preloads, const FrcSettings& s,
                           const std::filesystem::path& out) {
  if (s.sweep_points < 2) return;
  if (!(p.damping_ratio > 0)) p.damping_ratio = 0.05;  // as run_frc
  p.model.energy_audit = false;
  SettleSettings ss;
  ss.settle_periods = s.sweep_settle_periods;
  std::vector<double> up;
  for (int k = 0; k < s.sweep_points; ++k) up.push_back(s.f_lo + (s.f_hi - s.f_lo) * k / (s.sweep_points - 1.0));
  const std::vector<double> down(up.rbegin(), up.rend());
  std::ofstream o(out / "frc_sweep.csv");
  o << "preload_N,direction,frequency_hz,period_T,verdict,orbit,stable,asymmetric,tip_amplitude_m,stick_fraction_1,"
       "stick_fraction_2,max_multiplier,cpu_s\n";
  std::mutex print;
  for (double n0 : preloads) {
    BladeParameters q = p;
    q.preload = n0;
    std::vector<SettledResponse> result[2];
    const char* name[2] = {"up", "down"};
    std::printf("frc sweep N0 %g N: %d frequencies up and down, %d periods each from the previous state\n", n0,
                s.sweep_points, ss.settle_periods);
    std::fflush(stdout);
    auto run = [&](int d) {
      BladeScene scene = make_blade_scene(q);
      int count = 0;
      result[d] = frequency_sweep(scene, d == 0 ? up : down, ss, [&](const SettledResponse& r) {
        std::lock_guard<std::mutex> g(print);
        std::printf("frc sweep N0 %g N %-4s %3d/%d  f %7.3f Hz  tip %.4e m  %s%s%s  %.2f s%s%s\n", n0, name[d], ++count,
                    s.sweep_points, r.frequency_hz, r.tip_amplitude,
                    r.period == 0 ? "not periodic" : ("period " + std::to_string(r.period) + " T").c_str(),
                    r.orbit ? (r.stable ? " orbit stable" : " orbit unstable") : "", r.asymmetric ? ", asymmetric" : "",
                    r.cpu_seconds, r.ok() ? "" : "  failed: ", r.message.c_str());
        std::fflush(stdout);
      });
    };
    std::thread other(run, 1);
    run(0);
    other.join();
    for (int d = 0; d < 2; ++d)
      for (const SettledResponse& r : result[d])
        o << fmt(n0) << ',' << name[d] << ',' << fmt(r.frequency_hz) << ',' << r.period << ',' << r.verdict << ','
          << (r.orbit ? 1 : 0) << ',' << (r.stable ? 1 : 0) << ',' << (r.asymmetric ? 1 : 0) << ','
          << fmt(r.tip_amplitude) << ',' << fmt(r.stick_fraction[0]) << ',' << fmt(r.stick_fraction[1]) << ','
          << fmt(r.max_multiplier) << ',' << fmt(r.cpu_seconds) << '\n';
  }
  std::printf("frc sweep: rows in %s\n", (out / "frc_sweep.csv").string().c_str());
}

}  // namespace blade

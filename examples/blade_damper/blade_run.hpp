#pragma once
/// \file blade_run.hpp
/// \brief One simulation of the blade-damper scene with the records the example writes:
/// sampled histories, the event log, regimes per damper, E (the paper's energy density), stats.

#include "blade_regime.hpp"
#include "blade_scene.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/stickslip.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace blade {

/// What to run and what to record.
struct RunSettings {
  double duration = 20.0;          ///< [s]
  double sample_interval = 1e-4;   ///< output rate through the dense output [s]
  double record_window = 1.0;      ///< full records over the last `record_window` seconds [s]
  /// The paper's E window [t1, t2] = [19, 19.5] s for its 20 s runs; shorter runs use the same
  /// position relative to the end, [T - 1, T - 0.5].
  double energy_t1 = 19.0, energy_t2 = 19.5;
  void fit_energy_window() {
    if (duration < energy_t2) {
      energy_t2 = std::max(0.0, duration - 0.5);
      energy_t1 = std::max(0.0, duration - 1.0);
    }
  }
  stickslip::RunOptions<double> run{};
};

/// One sampled row of the records.
struct Sample {
  double t, tip;
  double N[2], f[2], V[2], x[2], y[2], X[2];
  int state[2];
};

/// Regime of one damper over the last record window.
struct DamperRegime {
  double stick_fraction = 0;          ///< fraction of samples stuck
  double transitions_per_period = 0;  ///< contact switches per excitation period
  double separated_fraction = 0;      ///< fraction of samples separated from the platform (--restitution)
  /// damper_regime(stick_fraction) (blade_regime.hpp); none when the run stopped before the window.
  std::optional<Regime> regime;
  /// The regime's name, or "not reached".
  std::string name() const { return regime ? to_string(*regime) : "not reached"; }
};

/// Everything one run produces.
struct RunRecord {
  double preload = 0;
  stickslip::Status status = stickslip::Status::Success;
  std::string message;
  double t_end = 0;
  stickslip::StepperStats stats;
  double cpu_seconds = 0;
  std::vector<Sample> window;          ///< full samples over the record window
  std::vector<double> tip_t, tip_x;    ///< decimated tip history over the whole run (1 ms)
  double energy_density = 0;           ///< E = mean of x_tip^2 over [t1, t2] (paper section 3.4)
  double tip_max = 0, tip_rms = 0;     ///< over the record window
  DamperRegime regime[2];
  std::optional<Regime> common;        ///< common_regime() of the dampers; none if the run stopped
  /// The common regime's name, "<damper 1> / <damper 2>" when they differ, or why the run stopped.
  std::string overall_regime;
  double energy_residual = 0;          ///< final energy-audit residual [J]
  double energy_scale = 0;             ///< largest |term| of the audit, for a relative measure [J]
  std::vector<stickslip::FrictionDampedSystem<double>::ContactEvent> events;  ///< in the window
  long total_events = 0;
  std::string method;         ///< the integrator that ran (RunOptions::integrator, or Auto's choice)
  std::string method_reason;  ///< why (Integrator::Auto's rule)
};

namespace detail {

/// Samples the state through the stepper's dense output.
class Recorder : public stickslip::NullObserver {
 public:
  using System = BladeScene::System;
  Recorder(const BladeScene& scene, const RunSettings& s, RunRecord& r)
      : scene_(scene), settings_(s), record_(r) {}

  template <class Scalar, class State, class Mode>
  bool on_sample(Scalar t, const State& x, const Mode& mode) {
    const double tip = scene_.tip_displacement(x);
    if (t >= next_tip_ - 1e-12) {
      record_.tip_t.push_back(t);
      record_.tip_x.push_back(tip);
      next_tip_ += 1e-3;
    }
    const double t1 = settings_.energy_t1, t2 = settings_.energy_t2;
    if (t >= t1 - 1e-12 && t <= t2 + 1e-12) {
      if (have_prev_ && prev_t_ >= t1 - 1e-12)
        energy_integral_ += 0.5 * (t - prev_t_) * (tip * tip + prev_tip_ * prev_tip_);
    }
    prev_t_ = t;
    prev_tip_ = tip;
    have_prev_ = true;
    if (t >= settings_.duration - settings_.record_window - 1e-12) {
      System& sys = *scene_.system;
      const auto& e = sys.evaluate(mode, t, x);
      Sample s{};
      s.t = t;
      s.tip = tip;
      for (int i = 0; i < 2; ++i) {
        s.N[i] = e.N[i];
        s.f[i] = e.f[i];
        s.V[i] = e.V[i];
        s.x[i] = x[sys.x_offset() + i];
        s.y[i] = e.y[i];
        s.X[i] = e.X[i];
        s.state[i] = static_cast<int>(mode[i]);
      }
      record_.window.push_back(s);
    }
    return true;
  }

  double energy_integral() const { return energy_integral_; }

 private:
  const BladeScene& scene_;
  const RunSettings& settings_;
  RunRecord& record_;
  double next_tip_ = 0;
  double prev_t_ = 0, prev_tip_ = 0;
  bool have_prev_ = false;
  double energy_integral_ = 0;
};

}  // namespace detail

/// Runs the scene from rest (dampers stuck, preload applied at t = 0) and fills a RunRecord.
inline RunRecord run_scene(BladeScene& scene, const RunSettings& settings) {
  using namespace stickslip;
  RunRecord rec;
  rec.preload = scene.parameters.preload;
  auto& sys = *scene.system;
  sys.clear_events();
  auto x0 = sys.initial_state();
  auto mode = sys.requested_mode();
  RunOptions<double> run = settings.run;
  run.stepper.output_interval = settings.sample_interval;
  const double c0 = stickslip::detail::thread_cpu_seconds();  // this run's thread (sweeps run in parallel)
  if (!sys.make_consistent(mode, 0.0, x0)) {
    rec.status = Status::StoppedBySystem;
    rec.message = "inconsistent or lifted-off initial contact state at t = 0";
    return rec;
  }
  const double E0 = sys.options().energy_audit ? sys.mechanical_energy(mode, 0.0, x0) : 0.0;
  detail::Recorder recorder(scene, settings, rec);
  auto result = simulate(sys, mode, 0.0, x0, settings.duration, run, recorder);
  rec.cpu_seconds = stickslip::detail::thread_cpu_seconds() - c0;
  rec.status = result.status;
  rec.message = result.message;
  rec.t_end = result.t;
  rec.stats = result.stats;
  rec.method = result.method;
  rec.method_reason = result.method_reason;
  if (sys.options().energy_audit) {
    auto b = sys.energy_balance(result.mode, result.t, result.x, E0);
    rec.energy_residual = b.residual;
    rec.energy_scale = std::max({std::abs(b.mechanical - E0), std::abs(b.external_work),
                                 std::abs(b.friction_dissipation), std::abs(b.viscous_dissipation)});
  }
  const double t1 = settings.energy_t1, t2 = settings.energy_t2;
  rec.energy_density = (t2 > t1 && result.t >= t2) ? recorder.energy_integral() / (t2 - t1)
                                                    : std::numeric_limits<double>::quiet_NaN();

  // Window statistics.
  const double tw = settings.duration - settings.record_window;
  double sum2 = 0;
  int stuck[2] = {0, 0}, flying[2] = {0, 0};
  for (const Sample& s : rec.window) {
    rec.tip_max = std::max(rec.tip_max, std::abs(s.tip));
    sum2 += s.tip * s.tip;
    for (int i = 0; i < 2; ++i) {
      stuck[i] += s.state[i] == static_cast<int>(ContactState::Stick);
      flying[i] += s.state[i] == static_cast<int>(ContactState::Separated);
    }
  }
  // A run stopped before the recording window has no window statistics (NaN: null in the JSON).
  const bool reached = !rec.window.empty();
  const double none = std::numeric_limits<double>::quiet_NaN();
  const double count = double(rec.window.size());
  if (!reached) rec.tip_max = none;
  rec.tip_rms = reached ? std::sqrt(sum2 / count) : none;
  const double periods = settings.record_window * scene.parameters.force_omega / (2 * M_PI);
  long switches[2] = {0, 0};
  for (const auto& ev : sys.events()) {
    if (ev.t >= tw) {
      rec.events.push_back(ev);
      if (ev.damper >= 0 && ev.damper < 2) ++switches[ev.damper];
    }
  }
  rec.total_events = static_cast<long>(sys.events().size());
  for (int i = 0; i < 2; ++i) {
    DamperRegime& r = rec.regime[i];
    if (!reached) {
      r.stick_fraction = r.transitions_per_period = r.separated_fraction = none;
      continue;
    }
    r.stick_fraction = stuck[i] / count;
    r.transitions_per_period = static_cast<double>(switches[i]) / periods;
    r.separated_fraction = flying[i] / count;
    r.regime = damper_regime(r.stick_fraction, r.separated_fraction);
  }
  rec.common = common_regime(rec.regime[0].regime, rec.regime[1].regime);
  rec.overall_regime = rec.common ? to_string(*rec.common) : rec.regime[0].name() + " / " + rec.regime[1].name();
  if (result.status != Status::Success) {
    rec.common.reset();
    using Stop = BladeScene::System::StopReason;
    const Stop why = sys.stop_reason();
    rec.overall_regime = why == Stop::LiftOff ? "lift-off" : why == Stop::LeftMember ? "left platform" : "run stopped";
  }
  return rec;
}

}  // namespace blade

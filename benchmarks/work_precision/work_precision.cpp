// Work-precision study of stickslip (docs/performance.md): error against a tight reference
// versus CPU time for the integrators, event locators, friction regularisation and model
// reductions, on the paper's blade-damper scene in three contact regimes and on a single-DOF
// stick-slip oscillator on a moving belt; plus the numerical damping and dispersion of each
// integrator setting on the retained modes of the default scene.
//
// Usage: work_precision [--out DIR] [--threads N]
// Writes DIR/work_precision.csv, DIR/work_precision.json, DIR/numerical_damping.csv and
// DIR/tables.md (the markdown tables quoted in docs/performance.md).
#include "blade_damper/blade_scene.hpp"
#include "contact/single_dof_systems.hpp"

#include <stickslip/stickslip.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace stickslip;
using Index = Eigen::Index;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// CPU time of the calling thread (the runs execute in parallel; process CPU time would mix them).
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::string num(double v, const char* f = "%.4g") {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
std::string json_num(double v) { return std::isfinite(v) ? num(v, "%.6g") : "null"; }

// ---- scenes -------------------------------------------------------------------------------------

enum class Kind { Blade, Belt };

struct Scene {
  std::string name;
  std::string regime;
  Kind kind;
  double preload;    ///< N0 [N] (blade scenes)
  double horizon;    ///< simulated time [s]
  double window;     ///< error window at the end of the horizon [s]
  double sample_dt;  ///< sampling of tip and forces through the dense output [s]
};

/// Mass-spring on a belt (stick-slip limit cycle): m x'' + k x = f, v = x' - v_belt.
contact_test::SingleDofParameters belt_parameters() {
  contact_test::SingleDofParameters p;
  p.mass = 1.0;          // kg
  p.stiffness = 100.0;   // N/m  (omega = 10 rad/s)
  p.belt_speed = 0.1;    // m/s
  p.normal_force = 10.0; // N
  p.watch_lift_off = false;
  return p;
}
constexpr double kBeltMuS = 0.4, kBeltMuK = 0.3;

// ---- one run ------------------------------------------------------------------------------------

struct Config {
  RunOptions<double> run;
  blade::BladeParameters blade;  ///< model variant (blade scenes); the preload comes from the scene
  double v_eps = 0;              ///< > 0: regularised tanh friction (mu_k) with this velocity scale
};

struct Sample {
  double t, tip, N[2], f[2];
  bool stuck;
};
struct SwitchEvent {
  double t;
  Index who;
  ContactState to;
};

struct Trace {
  Status status = Status::Success;
  std::string message;
  double t_end = 0;
  StepperStats stats;
  double cpu = kNaN;  ///< median thread CPU seconds over the repeats
  int repeats = 0;
  std::vector<Sample> samples;  ///< over the error window
  std::vector<SwitchEvent> events;
  double energy_rel = kNaN;     ///< |energy-audit residual| / largest term of the audit
  std::string method;           ///< the method simulate() ran (Integrator::Auto's pick)
};

/// Records the raw state and mode at the output times inside the error window (flat buffer, no
/// work beyond a copy while timed); on_event logs switches (used by the belt oscillator).
template <class Mode>
struct WindowRecorder : NullObserver {
  double from = 0;
  Index width = 0;
  std::vector<double> t, x;
  std::vector<Mode> mode;
  std::vector<SwitchEvent> events;

  void reset(double from_, Index width_, std::size_t expected) {
    from = from_;
    width = width_;
    t.clear();
    x.clear();
    mode.clear();
    events.clear();
    t.reserve(expected);
    x.reserve(expected * static_cast<std::size_t>(width_));
    mode.reserve(expected);
  }
  template <class State>
  bool on_sample(double ts, const State& xs, const Mode& m) {
    if (ts >= from - 1e-12) {
      t.push_back(ts);
      x.insert(x.end(), xs.data(), xs.data() + xs.size());
      mode.push_back(m);
    }
    return true;
  }
  void on_event(const EventRecord<double, Mode>& r) {
    if constexpr (std::is_same_v<Mode, ContactState>) events.push_back({r.t, 0, r.to});
  }
  template <class State>
  State state(std::size_t k) const {
    return Eigen::Map<const State>(x.data() + k * static_cast<std::size_t>(width), width);
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? kNaN : v[v.size() / 2];
}

/// Every run is repeated 3 times and the median CPU time kept (a shared 2-core VM varies by up to
/// 2x between single runs), except a run that fails or takes longer than this on its own.
constexpr double kRepeatBelow = 10.0;

Trace run_blade(const Scene& sc, const Config& c) {
  using System = blade::BladeScene::System;
  blade::BladeParameters p = c.blade;
  p.preload = sc.preload;
  p.regularised_v_eps = c.v_eps;
  blade::BladeScene scene = blade::make_blade_scene(p);
  System& sys = *scene.system;
  RunOptions<double> run = c.run;
  run.stepper.output_interval = sc.sample_dt;
  Trace tr;
  std::vector<double> cpu;
  WindowRecorder<System::Mode> rec;
  HybridResult<double, System::State, System::Mode> result;
  double E0 = 0;
  for (int rep = 0; rep < 3; ++rep) {
    sys.clear_events();
    rec.reset(sc.horizon - sc.window, sys.state_size(), static_cast<std::size_t>(sc.window / sc.sample_dt) + 8);
    System::State x0 = sys.initial_state();
    System::Mode mode = sys.requested_mode();
    const double c0 = thread_cpu_seconds();
    if (!sys.make_consistent(mode, 0.0, x0)) {
      tr.status = Status::StoppedBySystem;
      tr.message = "no consistent initial contact state";
      return tr;
    }
    E0 = sys.mechanical_energy(mode, 0.0, x0);
    result = simulate(sys, mode, 0.0, x0, sc.horizon, run, rec);
    cpu.push_back(thread_cpu_seconds() - c0);
    if (cpu.back() > kRepeatBelow || !result.ok()) break;
  }
  tr.cpu = median(cpu);
  tr.repeats = static_cast<int>(cpu.size());
  tr.status = result.status;
  tr.message = result.message;
  tr.method = result.method;
  tr.t_end = result.t;
  tr.stats = result.stats;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const System::State x = rec.state<System::State>(k);
    const auto& e = sys.evaluate(rec.mode[k], rec.t[k], x);
    tr.samples.push_back({rec.t[k], scene.tip_displacement(x), {e.N[0], e.N[1]}, {e.f[0], e.f[1]},
                          rec.mode[k][0] == ContactState::Stick});
  }
  for (const auto& ev : sys.events()) tr.events.push_back({ev.t, ev.damper, ev.to});
  if (sys.options().energy_audit) {
    const auto b = sys.energy_balance(result.mode, result.t, result.x, E0);
    const double scale = std::max({std::abs(b.mechanical - E0), std::abs(b.external_work),
                                   std::abs(b.friction_dissipation), std::abs(b.viscous_dissipation)});
    tr.energy_rel = scale > 0 ? std::abs(b.residual) / scale : kNaN;
  }
  return tr;
}

template <class Law>
Trace run_belt_with(const Scene& sc, const Config& c, Law law) {
  using Osc = contact_test::SingleDofOscillator<Law>;
  Osc osc(belt_parameters(), typename Osc::Contact(law));
  RunOptions<double> run = c.run;
  run.stepper.output_interval = sc.sample_dt;
  Trace tr;
  std::vector<double> cpu;
  WindowRecorder<ContactState> rec;
  HybridResult<double, typename Osc::State, ContactState> result;
  for (int rep = 0; rep < 3; ++rep) {
    rec.reset(sc.horizon - sc.window, 4, static_cast<std::size_t>(sc.window / sc.sample_dt) + 8);
    const typename Osc::State x0 = Osc::State::Zero();
    const double c0 = thread_cpu_seconds();
    ContactState mode = osc.consistent_mode(0.0, x0);
    result = simulate(osc, mode, 0.0, x0, sc.horizon, run, rec);
    cpu.push_back(thread_cpu_seconds() - c0);
    if (cpu.back() > kRepeatBelow || !result.ok()) break;
  }
  tr.cpu = median(cpu);
  tr.repeats = static_cast<int>(cpu.size());
  tr.status = result.status;
  tr.message = result.message;
  tr.t_end = result.t;
  tr.stats = result.stats;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const auto x = rec.template state<typename Osc::State>(k);
    const double t = rec.t[k];
    tr.samples.push_back({t, x[0], {osc.normal_force(t), 0.0}, {osc.friction_force(rec.mode[k], t, x), 0.0},
                          rec.mode[k] == ContactState::Stick});
  }
  tr.events = rec.events;
  return tr;  // the oscillator's state has no audit of the belt's work: energy_rel stays NaN
}

Trace run_scene(const Scene& sc, const Config& c) {
  if (sc.kind == Kind::Blade) return run_blade(sc, c);
  if (c.v_eps > 0) return run_belt_with(sc, c, RegularisedLaw<double>(kBeltMuK, c.v_eps));
  return run_belt_with(sc, c, CoulombLaw<double>(kBeltMuS, kBeltMuK));
}

// ---- errors against the reference ---------------------------------------------------------------

struct Errors {
  double tip_max = kInf;    ///< max |tip - tip_ref| / max |tip_ref| over the window
  double tip_rms = kInf;    ///< rms(tip - tip_ref) / max |tip_ref|
  double switch_max = kNaN; ///< max over reference switches of |t - t_ref| of the nearest same switch [s]
  double force_max = kInf;  ///< max |N - N_ref|, |f - f_ref| / max |N_ref| over the window
};

Errors compare(const Trace& run, const Trace& ref) {
  Errors e;
  if (!ref.events.empty() && !run.events.empty()) {
    double worst = 0;
    for (const SwitchEvent& r : ref.events) {
      double best = kInf;
      for (const SwitchEvent& q : run.events)
        if (q.who == r.who && q.to == r.to) best = std::min(best, std::abs(q.t - r.t));
      worst = std::max(worst, best);
    }
    e.switch_max = worst;
  }
  if (run.status != Status::Success || run.samples.size() != ref.samples.size() || ref.samples.empty()) return e;
  double A = 0, F = 0;
  for (const Sample& s : ref.samples) {
    A = std::max(A, std::abs(s.tip));
    F = std::max({F, std::abs(s.N[0]), std::abs(s.N[1])});
  }
  double emax = 0, e2 = 0, fmax = 0;
  for (std::size_t k = 0; k < ref.samples.size(); ++k) {
    const Sample &a = run.samples[k], &b = ref.samples[k];
    if (std::abs(a.t - b.t) > 1e-9) return e;
    const double d = a.tip - b.tip;
    emax = std::max(emax, std::abs(d));
    e2 += d * d;
    for (int i = 0; i < 2; ++i)
      fmax = std::max({fmax, std::abs(a.N[i] - b.N[i]), std::abs(a.f[i] - b.f[i])});
  }
  e.tip_max = emax / A;
  e.tip_rms = std::sqrt(e2 / static_cast<double>(ref.samples.size())) / A;
  e.force_max = fmax / F;
  return e;
}

// ---- jobs ---------------------------------------------------------------------------------------

struct Job {
  std::size_t scene = 0;
  std::string family;   ///< curve of the plots: method + locator (+ model variant)
  std::string method, locator, setting;
  double value = 0;     ///< the swept number (dt, rtol, v_eps, modes, ...)
  bool model_variant = false;  ///< modes / elements / toggles: model error at a tight tolerance
  bool reference = false;
  double cost = 0;      ///< rough cost estimate, to start the expensive runs first
  Config config;
  Trace trace;
  Errors errors;
};

RunOptions<double> rk4(double dt, EventLocation loc) {
  RunOptions<double> r;
  r.integrator = Integrator::RungeKutta4;
  r.stepper.fixed_step = dt;
  r.stepper.event_location = loc;
  return r;
}
/// Adaptive method at rtol; atol = 1e-4 rtol (the example's ratio, rtol 1e-8 / atol 1e-12).
RunOptions<double> adaptive(Integrator i, double rtol, EventLocation loc) {
  RunOptions<double> r;
  r.integrator = i;
  r.stepper.rtol = rtol;
  r.stepper.atol = 1e-4 * rtol;
  r.stepper.event_location = loc;
  r.stepper.max_steps = 3'000'000;
  return r;
}
const char* loc_name(EventLocation l) { return l == EventLocation::Bisection ? "bisection" : "root"; }

std::vector<Job> make_jobs(const std::vector<Scene>& scenes) {
  std::vector<Job> jobs;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const Scene& sc = scenes[s];
    const bool belt = sc.kind == Kind::Belt;
    const double T = sc.horizon;
    auto add = [&](std::string family, const RunOptions<double>& run, std::string setting, double value,
                   double cost, bool model = false) {
      Job j;
      j.scene = s;
      j.family = std::move(family);
      j.method = to_string(run.integrator);
      j.locator = loc_name(run.stepper.event_location);
      j.setting = std::move(setting);
      j.value = value;
      j.model_variant = model;
      j.cost = cost;
      j.config.run = run;
      jobs.push_back(j);
      return &jobs.back();
    };
    // Reference: DOPRI 5(4), rtol 1e-12, root finding on the dense output.
    add("reference", adaptive(Integrator::DormandPrince54, 1e-12, EventLocation::DenseRootFinding),
        "rtol=1e-12", 1e-12, 1e9)->reference = true;

    const std::vector<double> rk4_dt = belt ? std::vector<double>{1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5}
                                            : std::vector<double>{1e-4, 5e-5, 2e-5, 1e-5, 5e-6, 2e-6, 1e-6};
    for (double dt : rk4_dt)
      add("rk4+bisection", rk4(dt, EventLocation::Bisection), "dt=" + num(dt), dt, 4 * T / dt);
    const std::vector<double> rk4_root_dt = belt ? std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5}
                                                 : std::vector<double>{1e-4, 3e-5, 1e-5, 3e-6};
    for (double dt : rk4_root_dt)
      add("rk4+root", rk4(dt, EventLocation::DenseRootFinding), "dt=" + num(dt), dt, 4 * T / dt);
    for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11})
      add("dopri5+root", adaptive(Integrator::DormandPrince54, rtol, EventLocation::DenseRootFinding),
          "rtol=" + num(rtol), rtol, T * 1e6 * std::pow(1e-8 / rtol, 0.2));
    for (double rtol : {1e-5, 1e-7, 1e-9})
      add("dopri5+bisection", adaptive(Integrator::DormandPrince54, rtol, EventLocation::Bisection),
          "rtol=" + num(rtol), rtol, T * 1e6 * std::pow(1e-8 / rtol, 0.2));
    for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6})
      add("rosenbrock23+root", adaptive(Integrator::Rosenbrock23, rtol, EventLocation::DenseRootFinding),
          "rtol=" + num(rtol), rtol, T * 1e6 * std::pow(1e-6 / rtol, 0.33));
    // Regularised friction (no stick state, no switches): the model error of the smoothing.
    for (double ve : belt ? std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5} : std::vector<double>{1e-2, 1e-3, 1e-4}) {
      Job* j = add("regularised dopri5 1e-8", adaptive(Integrator::DormandPrince54, 1e-8, EventLocation::DenseRootFinding),
                   "v_eps=" + num(ve), ve, T * 1e6 / std::sqrt(ve));
      j->config.v_eps = ve;
    }
    for (double ve : belt ? std::vector<double>{1e-3, 1e-4, 1e-5} : std::vector<double>{1e-3, 1e-4, 1e-5}) {
      Job* j = add("regularised rosenbrock23 1e-5", adaptive(Integrator::Rosenbrock23, 1e-5, EventLocation::DenseRootFinding),
                   "v_eps=" + num(ve), ve, T * 1e6);
      j->config.v_eps = ve;
    }
    // Integrator::Auto (simulate()'s default): the method it picks per scene, on DOPRI's rtol grid
    // (a coarser grid would compare Auto at a tighter rtol than the method it picks).
    if (!belt)
      for (double rtol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11})
        add("auto", adaptive(Integrator::Auto, rtol, EventLocation::DenseRootFinding), "rtol=" + num(rtol), rtol,
            T * 4e6 * std::pow(1e-8 / rtol, 0.2));
    if (belt) continue;
    // The exponential method (ExactLinearStepper on the model's linear part): exact in
    // stuck modes (rtol governs only its Lawson steps in the slipping modes with a moving contact),
    // and exact in every mode with the contact point fixed.
    for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10})
      add("exponential", adaptive(Integrator::Exponential, rtol, EventLocation::DenseRootFinding),
          "rtol=" + num(rtol), rtol, T * 4e6 * std::pow(1e-8 / rtol, 0.2));
    for (double rtol : {1e-6, 1e-10}) {
      Job* j = add("exponential fixed contact", adaptive(Integrator::Exponential, rtol, EventLocation::DenseRootFinding),
                   "rtol=" + num(rtol), rtol, T * 1e6, true);
      j->config.blade.model.moving_contact = false;
    }
    // Fewer modes with a loose tolerance: dropping the stiff high modes lifts DOPRI's stability limit.
    for (int n : {3, 4})
      for (double rtol : {1e-4, 1e-6, 1e-8}) {
        Job* j = add("dopri5+root " + std::to_string(n) + " modes",
                     adaptive(Integrator::DormandPrince54, rtol, EventLocation::DenseRootFinding),
                     "rtol=" + num(rtol), rtol, T * 1e5);
        j->config.blade.modes = n;
      }
    // Fewer modes with RK4 and root finding at steps up to just below the stability limit that
    // simulate() enforces for that model (the highest retained mode, or a slipping damper's free
    // oscillator sqrt(k/m) = 1695 rad/s at N0 = 2 N: 2 modes 1.67e-3 s, 3 modes 7.5e-4 s, 4
    // modes 4.0e-4 s). The paper's method on the trade's cheapest axis: its model error counts.
    for (auto [n, dts] : std::vector<std::pair<int, std::vector<double>>>{
             {2, {1.5e-3, 1e-3, 5e-4, 2e-4}}, {3, {7e-4, 5e-4, 2e-4, 1e-4}}, {4, {3.5e-4, 2e-4, 1e-4, 5e-5}}})
      for (double dt : dts) {
        Job* j = add("rk4+root " + std::to_string(n) + " modes", rk4(dt, EventLocation::DenseRootFinding),
                     "dt=" + num(dt), dt, 4 * T / dt);
        j->config.blade.modes = n;
      }
    // Model variants at a fixed tight tolerance: the model error against the reference model.
    const RunOptions<double> tight = adaptive(Integrator::DormandPrince54, 1e-10, EventLocation::DenseRootFinding);
    for (int n : {1, 2, 3, 4, 5, 8, 10}) {
      Job* j = add("modes", tight, "modes=" + std::to_string(n), n, T * 2e6 * n / 6, true);
      j->config.blade.modes = n;
    }
    for (auto [nb, np] : std::vector<std::pair<int, int>>{{5, 4}, {10, 4}, {10, 8}, {40, 8}, {40, 16}}) {
      Job* j = add("elements", tight, "blade=" + std::to_string(nb) + ",platform=" + std::to_string(np),
                   nb + np, T * 2e6, true);
      j->config.blade.blade_elements = nb;
      j->config.blade.platform_elements = np;
    }
    Job* j = add("normal load", tight, "constant N", 0, T * 2e6, true);
    j->config.blade.model.normal_load = NormalLoad::Constant;
    j = add("contact point", tight, "fixed contact", 0, T * 2e6, true);
    j->config.blade.model.moving_contact = false;
  }
  return jobs;
}

/// Runs work(job) for every job on `threads` threads, the most expensive first.
void run_parallel(std::vector<Job*> jobs, int threads, const std::function<void(Job&)>& work) {
  std::sort(jobs.begin(), jobs.end(), [](const Job* a, const Job* b) { return a->cost > b->cost; });
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex io;
  auto worker = [&] {
    for (;;) {
      const std::size_t k = next++;
      if (k >= jobs.size()) return;
      work(*jobs[k]);
      const std::size_t d = ++done;
      std::lock_guard<std::mutex> lock(io);
      std::fprintf(stderr, "\r  %zu/%zu runs done", d, jobs.size());
    }
  };
  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  std::fprintf(stderr, "\n");
}

// ---- numerical damping and dispersion -----------------------------------------------------------

/// Free vibration of one mode, q'' + omega^2 q = 0, as a hybrid system without guards.
struct FreeMode {
  using Scalar = double;
  using State = Eigen::Vector2d;
  using Mode = int;
  double omega = 1;
  void rhs(const Mode&, double, const State& x, State& dx) const {
    dx[0] = x[1];
    dx[1] = -omega * omega * x[0];
  }
  Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::VectorXd&) const {}
  CrossingDirection guard_direction(const Mode&, Index) const { return CrossingDirection::Either; }
  TransitionAction transition(Mode&, const TriggeredGuards&, double, State&) const { return TransitionAction::proceed(); }
};

/// Unwraps the phase of (q, q'/omega) at the output times.
struct PhaseTracker : NullObserver {
  double omega = 1, phase = 0, last = 0;
  bool on_sample(double, const Eigen::Vector2d& x, const int&) {
    const double p = std::atan2(-x[1] / omega, x[0]);
    phase += std::remainder(p - last, 2 * M_PI);
    last = p;
    return true;
  }
};

struct DampingRow {
  std::string setting;
  Index mode;
  double omega, decay_per_cycle, period_error;
  bool stable;
};

/// Integrates q(0) = 1, q'(0) = 0 over `cycles` periods with the setting; the amplitude decay per
/// cycle 1 - A^(1/cycles) and the relative period error T_num / T - 1 against the exact cos.
DampingRow free_vibration(const std::string& name, const RunOptions<double>& setting, Index j, double omega) {
  const double cycles = 20, T = 2 * M_PI / omega;
  FreeMode sys;
  sys.omega = omega;
  RunOptions<double> run = setting;
  run.stepper.atol = setting.stepper.rtol;  // unit amplitude: the tolerance is relative to it
  run.stepper.output_interval = T / 16;
  run.stepper.max_steps = 20'000'000;
  PhaseTracker obs;
  obs.omega = omega;
  const auto r = simulate(sys, 0, 0.0, Eigen::Vector2d(1.0, 0.0), cycles * T, run, obs);
  DampingRow row{name, j, omega, kNaN, kNaN, false};
  const double A = std::hypot(r.x[0], r.x[1] / omega);
  if (!r.ok() || !std::isfinite(A) || A > 10) return row;
  obs.on_sample(r.t, r.x, 0);
  row.decay_per_cycle = 1 - std::pow(A, 1 / cycles);
  row.period_error = omega * r.t / obs.phase - 1;
  row.stable = true;
  return row;
}

// ---- summaries ----------------------------------------------------------------------------------

std::string machine_description() {
  std::string model = "unknown CPU";
  std::ifstream cpu("/proc/cpuinfo");
  for (std::string line; std::getline(cpu, line);)
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  std::ostringstream o;
  o << model << ", " << std::thread::hardware_concurrency() << " hardware threads, compiler "
#if defined(__clang__)
    << "clang "
#elif defined(__GNUC__)
    << "gcc "
#endif
    << __VERSION__;
  return o.str();
}

bool is_paper(const Job& j) { return j.family == "rk4+bisection" && j.value == 1e-4; }

/// The fastest non-reference run of the scene with tip_max <= target among `pred`.
const Job* fastest(const std::vector<Job>& jobs, std::size_t scene, double target,
                   const std::function<bool(const Job&)>& pred) {
  const Job* best = nullptr;
  for (const Job& j : jobs)
    if (j.scene == scene && !j.reference && pred(j) && j.errors.tip_max <= target &&
        (!best || j.trace.cpu < best->trace.cpu))
      best = &j;
  return best;
}

std::string label(const Job& j) {
  return j.family + (j.family.find(j.method) == std::string::npos && !j.model_variant ? " " + j.method : "") +
         ", " + j.setting;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "work_precision_out";
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--threads" && i + 1 < argc) threads = std::max(1, std::stoi(argv[++i]));
    else {
      std::printf("Usage: work_precision [--out DIR] [--threads N]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  std::filesystem::create_directories(out);
  const double periods5 = 5 * 2 * M_PI / 200.0;  // five excitation periods of the blade scene
  const std::vector<Scene> scenes = {
      {"blade_gross_slip", "gross slip", Kind::Blade, 2.0, 0.5, periods5, 1e-4},
      {"blade_stick_slip", "stick-slip", Kind::Blade, 2.6, 0.5, periods5, 1e-4},
      {"blade_stick", "stick", Kind::Blade, 26.0, 0.5, periods5, 1e-4},
      {"belt_sdof", "stick-slip (1 DOF)", Kind::Belt, 0.0, 5.0, 2.0, 1e-3},
  };
  const double wall0 = static_cast<double>(std::time(nullptr));
  std::vector<Job> jobs = make_jobs(scenes);
  auto work = [&](Job& j) {
    try {
      j.trace = run_scene(scenes[j.scene], j.config);
    } catch (const std::exception& e) {
      j.trace.status = Status::StoppedBySystem;
      j.trace.message = std::string("exception: ") + e.what();
    }
  };
  std::vector<Job*> refs, rest;
  for (Job& j : jobs) (j.reference ? refs : rest).push_back(&j);
  std::fprintf(stderr, "work_precision: %zu references, then %zu runs on %d threads\n", refs.size(), rest.size(), threads);
  run_parallel(refs, threads, work);
  run_parallel(rest, threads, work);
  std::vector<const Job*> ref_of(scenes.size(), nullptr);
  for (const Job* r : refs) ref_of[r->scene] = r;
  for (Job& j : jobs) j.errors = compare(j.trace, ref_of[j.scene]->trace);

  // Numerical damping / dispersion on the retained modes of the default scene.
  const blade::BladeScene base = blade::make_blade_scene(blade::BladeParameters{});
  const Eigen::VectorXd omegas = base.basis.omega();
  std::vector<std::pair<std::string, RunOptions<double>>> settings;
  for (double dt : {1e-4, 5e-5, 1e-5, 1e-6}) settings.emplace_back("rk4 dt=" + num(dt), rk4(dt, EventLocation::Bisection));
  for (double rtol : {1e-3, 1e-6, 1e-9})
    settings.emplace_back("dopri5 rtol=" + num(rtol), adaptive(Integrator::DormandPrince54, rtol, EventLocation::DenseRootFinding));
  for (double rtol : {1e-3, 1e-5})
    settings.emplace_back("rosenbrock23 rtol=" + num(rtol), adaptive(Integrator::Rosenbrock23, rtol, EventLocation::DenseRootFinding));
  std::vector<DampingRow> damping;
  for (const auto& [name, run] : settings)
    for (Index j = 0; j < omegas.size(); ++j) damping.push_back(free_vibration(name, run, j, omegas[j]));
  const double wall = static_cast<double>(std::time(nullptr)) - wall0;

  // ---- CSV / JSON ----
  {
    std::ofstream o(out + "/work_precision.csv");
    o << "scene,regime,family,method,locator,setting,value,model_variant,status,tip_max_rel,tip_rms_rel,"
         "switch_max_s,events,events_ref,force_max_rel,energy_residual_rel,cpu_s,repeats,rhs_evaluations,"
         "steps,rejected_steps,guard_evaluations,t_end\n";
    for (const Job& j : jobs) {
      const Scene& sc = scenes[j.scene];
      const Trace& t = j.trace;
      o << sc.name << ',' << sc.regime << ',' << j.family << ',' << j.method << ',' << j.locator << ",\""
        << j.setting << "\"," << num(j.value, "%.6g") << ',' << (j.model_variant ? 1 : 0) << ','
        << to_string(t.status) << ',' << num(j.errors.tip_max, "%.6g") << ',' << num(j.errors.tip_rms, "%.6g") << ','
        << num(j.errors.switch_max, "%.6g") << ',' << t.events.size() << ',' << ref_of[j.scene]->trace.events.size()
        << ',' << num(j.errors.force_max, "%.6g") << ',' << num(t.energy_rel, "%.6g") << ',' << num(t.cpu, "%.6g")
        << ',' << t.repeats << ',' << t.stats.rhs_evaluations << ',' << t.stats.accepted_steps << ','
        << t.stats.rejected_steps << ',' << t.stats.guard_evaluations << ',' << num(t.t_end, "%.9g") << '\n';
    }
    std::ofstream d(out + "/numerical_damping.csv");
    d << "setting,mode,omega_rad_s,frequency_hz,decay_per_cycle,period_error_rel,stable\n";
    for (const DampingRow& r : damping)
      d << r.setting << ',' << r.mode + 1 << ',' << num(r.omega, "%.6g") << ',' << num(r.omega / (2 * M_PI), "%.6g")
        << ',' << num(r.decay_per_cycle, "%.6g") << ',' << num(r.period_error, "%.6g") << ',' << (r.stable ? 1 : 0) << '\n';
  }
  {
    std::ofstream o(out + "/work_precision.json");
    o << "{\n  \"machine\": \"" << machine_description() << "\",\n  \"threads\": " << threads
      << ",\n  \"wall_seconds\": " << wall << ",\n  \"scenes\": [\n";
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      const Scene& sc = scenes[s];
      const Trace& r = ref_of[s]->trace;
      double stuck = 0, A = 0;
      for (const Sample& x : r.samples) {
        stuck += x.stuck;
        A = std::max(A, std::abs(x.tip));
      }
      o << "    {\"name\": \"" << sc.name << "\", \"regime\": \"" << sc.regime << "\", \"preload_N\": " << sc.preload
        << ", \"horizon_s\": " << sc.horizon << ", \"window_s\": " << json_num(sc.window)
        << ", \"sample_dt_s\": " << sc.sample_dt << ", \"tip_amplitude\": " << json_num(A)
        << ", \"stick_fraction_in_window\": " << json_num(stuck / std::max<double>(1.0, static_cast<double>(r.samples.size())))
        << ", \"reference_events\": " << r.events.size() << ", \"reference_status\": \"" << to_string(r.status)
        << "\", \"reference_cpu_s\": " << json_num(r.cpu) << "}" << (s + 1 < scenes.size() ? "," : "") << "\n";
    }
    o << "  ],\n  \"runs\": [\n";
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const Job& j = jobs[k];
      const Trace& t = j.trace;
      o << "    {\"scene\": \"" << scenes[j.scene].name << "\", \"family\": \"" << j.family << "\", \"method\": \""
        << j.method << "\", \"locator\": \"" << j.locator << "\", \"setting\": \"" << j.setting
        << "\", \"value\": " << json_num(j.value) << ", \"model_variant\": " << (j.model_variant ? "true" : "false")
        << ", \"status\": \"" << to_string(t.status) << "\", \"tip_max_rel\": " << json_num(j.errors.tip_max)
        << ", \"tip_rms_rel\": " << json_num(j.errors.tip_rms) << ", \"switch_max_s\": " << json_num(j.errors.switch_max)
        << ", \"events\": " << t.events.size() << ", \"force_max_rel\": " << json_num(j.errors.force_max)
        << ", \"energy_residual_rel\": " << json_num(t.energy_rel) << ", \"cpu_s\": " << json_num(t.cpu)
        << ", \"rhs_evaluations\": " << t.stats.rhs_evaluations << ", \"steps\": " << t.stats.accepted_steps << "}"
        << (k + 1 < jobs.size() ? "," : "") << "\n";
    }
    o << "  ],\n  \"numerical_damping\": [\n";
    for (std::size_t k = 0; k < damping.size(); ++k) {
      const DampingRow& r = damping[k];
      o << "    {\"setting\": \"" << r.setting << "\", \"mode\": " << r.mode + 1 << ", \"omega\": " << json_num(r.omega)
        << ", \"decay_per_cycle\": " << json_num(r.decay_per_cycle) << ", \"period_error_rel\": "
        << json_num(r.period_error) << ", \"stable\": " << (r.stable ? "true" : "false") << "}"
        << (k + 1 < damping.size() ? "," : "") << "\n";
    }
    o << "  ]\n}\n";
  }

  // ---- markdown tables ----
  std::ostringstream md;
  md << "Machine: " << machine_description() << "; " << threads << " worker threads; whole study " << wall
     << " s wall.\n\n";
  md << "### Scenes and reference validation\n\n"
        "| scene | N0 [N] | horizon [s] | stick fraction (window) | reference events | reference CPU [s] | "
        "DOPRI rtol 1e-11 vs reference (tip max) | RK4 dt=1e-6 (belt 1e-5) vs reference (tip max) | switch-time difference [s] |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const Trace& r = ref_of[s]->trace;
    double stuck = 0;
    for (const Sample& x : r.samples) stuck += x.stuck;
    const Job *d11 = nullptr, *rk = nullptr;
    for (const Job& j : jobs) {
      if (j.scene != s) continue;
      if (j.family == "dopri5+root" && j.value == 1e-11) d11 = &j;
      if (j.family == "rk4+bisection" && j.value == (scenes[s].kind == Kind::Belt ? 1e-5 : 1e-6)) rk = &j;
    }
    md << "| " << scenes[s].name << " | " << num(scenes[s].preload) << " | " << num(scenes[s].horizon) << " | "
       << num(stuck / std::max<double>(1.0, static_cast<double>(r.samples.size())), "%.3f") << " | " << r.events.size()
       << " | " << num(r.cpu, "%.3g") << " | " << (d11 ? num(d11->errors.tip_max, "%.2e") : "-") << " | "
       << (rk ? num(rk->errors.tip_max, "%.2e") : "-") << " | "
       << (d11 ? num(d11->errors.switch_max, "%.2e") : "-") << " |\n";
  }
  auto numeric = [](const Job& j) { return !j.model_variant; };
  auto paper_family = [](const Job& j) { return j.family == "rk4+bisection"; };
  md << "\n### Fastest setting per tip accuracy (max tip error over the last window / tip amplitude)\n\n"
        "Speed-up = CPU time of the cheapest RK4 + bisection run (the paper's method) reaching the same "
        "accuracy / CPU time of the fastest setting, both from this run.\n\n"
        "| scene | target | fastest setting | its error | CPU [s] | RHS evals | cheapest RK4+bisection reaching it | "
        "CPU [s] | speed-up |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const Job* paper = nullptr;
    for (const Job& j : jobs)
      if (j.scene == s && is_paper(j)) paper = &j;
    std::vector<std::pair<std::string, double>> targets = {{"1 %", 1e-2}, {"0.1 %", 1e-3}, {"0.01 %", 1e-4}};
    if (paper && std::isfinite(paper->errors.tip_max))
      targets.insert(targets.begin(), {"paper's error " + num(paper->errors.tip_max, "%.2e"), paper->errors.tip_max});
    for (const auto& [name, target] : targets) {
      const Job* best = fastest(jobs, s, target, numeric);
      const Job* rk = fastest(jobs, s, target, paper_family);
      md << "| " << scenes[s].name << " | " << name << " | ";
      if (!best) {
        md << "none reached it | | | | | | |\n";
        continue;
      }
      md << label(*best) << " | " << num(best->errors.tip_max, "%.2e") << " | " << num(best->trace.cpu, "%.3g")
         << " | " << best->trace.stats.rhs_evaluations << " | ";
      if (rk)
        md << "dt=" << num(rk->value) << " | " << num(rk->trace.cpu, "%.3g") << " | "
           << num(rk->trace.cpu / best->trace.cpu, "%.3g") << "x |\n";
      else {
        const Job* finest = nullptr;
        for (const Job& j : jobs)
          if (j.scene == s && paper_family(j) && (!finest || j.value < finest->value)) finest = &j;
        md << "not reached down to dt=" << num(finest->value) << " | > " << num(finest->trace.cpu, "%.3g") << " | > "
           << num(finest->trace.cpu / best->trace.cpu, "%.3g") << "x |\n";
      }
    }
  }
  // Integrator::Auto against the fastest of the library's methods on the same model and law (RK4,
  // DOPRI, Rosenbrock23, exponential; no fewer modes, no regularised law), per tip accuracy.
  auto same_model_method = [](const Job& j) {
    return !j.model_variant && j.family != "auto" && j.family.find("modes") == std::string::npos &&
           j.family.find("regularised") == std::string::npos;
  };
  auto is_auto = [](const Job& j) { return j.family == "auto"; };
  // The methods a user tunes by a tolerance, as Auto is (no fixed-step RK4, whose step is chosen
  // here in hindsight from the error against the reference).
  auto adaptive_method = [&](const Job& j) { return same_model_method(j) && j.family.rfind("rk4", 0) != 0; };
  md << "\n### Integrator::Auto against the fastest method reaching the same tip accuracy\n\n"
        "Ratio = CPU of the cheapest Auto run reaching the target / CPU of the fastest run reaching it "
        "among the adaptive methods (DOPRI, Rosenbrock23, exponential; same model and law; rtol "
        "grids as listed above), and among all methods including fixed-step RK4 (its step picked "
        "in hindsight), this run.\n\n"
        "| scene | target | Auto setting (method run) | CPU [s] | fastest adaptive | CPU [s] | ratio | "
        "fastest of all | CPU [s] | ratio |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    if (scenes[s].kind == Kind::Belt) continue;
    for (double target : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8}) {
      const Job* a = fastest(jobs, s, target, is_auto);
      md << "| " << scenes[s].name << " | " << num(target) << " | ";
      if (a) md << a->setting << " (" << a->trace.method << ") | " << num(a->trace.cpu, "%.3g") << " | ";
      else md << "not reached | | ";
      for (const Job* b : {fastest(jobs, s, target, adaptive_method), fastest(jobs, s, target, same_model_method)}) {
        if (b) md << label(*b) << " | " << num(b->trace.cpu, "%.3g") << " | ";
        else md << "not reached | | ";
        md << (a && b ? num(a->trace.cpu / b->trace.cpu, "%.3g") + "x" : std::string("-")) << " | ";
      }
      md << "\n";
    }
  }
  md << "\n### Model variants (model error against the reference model, DOPRI rtol 1e-10, root finding)\n\n"
        "| scene | variant | tip max | tip rms | switch time [s] | events (ref) | force max | CPU [s] |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const Job& j : jobs)
    if (j.model_variant)
      md << "| " << scenes[j.scene].name << " | " << j.family << ": " << j.setting << " | "
         << num(j.errors.tip_max, "%.2e") << " | " << num(j.errors.tip_rms, "%.2e") << " | "
         << num(j.errors.switch_max, "%.2e") << " | " << j.trace.events.size() << " ("
         << ref_of[j.scene]->trace.events.size() << ") | " << num(j.errors.force_max, "%.2e") << " | "
         << num(j.trace.cpu, "%.3g") << (j.trace.status == Status::Success ? "" : std::string(" ") + to_string(j.trace.status))
         << " |\n";
  md << "\n### Numerical damping and dispersion on the retained modes (free vibration, 20 periods)\n\n"
        "Each cell: amplitude decay per cycle / relative period error (negative decay = growth; "
        "\"unstable\" = amplitude beyond 10x).\n\n| setting |";
  for (Index j = 0; j < omegas.size(); ++j) md << " mode " << j + 1 << " (" << num(omegas[j] / (2 * M_PI), "%.4g") << " Hz) |";
  md << "\n|---|";
  for (Index j = 0; j < omegas.size(); ++j) md << "---|";
  md << "\n";
  for (std::size_t k = 0; k < damping.size(); k += static_cast<std::size_t>(omegas.size())) {
    md << "| " << damping[k].setting << " |";
    for (Index j = 0; j < omegas.size(); ++j) {
      const DampingRow& r = damping[k + static_cast<std::size_t>(j)];
      md << " " << (r.stable ? num(r.decay_per_cycle, "%.1e") + " / " + num(r.period_error, "%.1e") : std::string("unstable")) << " |";
    }
    md << "\n";
  }
  std::ofstream(out + "/tables.md") << md.str();
  std::cout << md.str();
  for (const Job& j : jobs)
    if (!j.trace.message.empty() && !j.model_variant)
      std::fprintf(stderr, "note: %s %s %s: %s\n", scenes[j.scene].name.c_str(), j.family.c_str(), j.setting.c_str(),
                   j.trace.message.substr(0, 160).c_str());
  return 0;
}

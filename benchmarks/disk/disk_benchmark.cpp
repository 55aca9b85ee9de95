// Cost of the bladed disk (docs/measurements/disk_cost.md): a program writing CSV (one run; ratios from
// that run; wall seconds on this thread):
//   disk_benchmark [--modes m] [--orbit-modes m] [--frc-points n] [--skip-transient] [--rhs-only]
//                  [--transient-only] [--blades N] [--duration T] [--integrator name] [--out file.csv]
// (--rhs-only: the right-hand sides only, a few seconds; --transient-only: the transient only, of
// --blades blades (default 24) over --duration seconds (default 1) with --integrator (default
// auto), its CPU time and, with the exponential method, the stepper's work counters)
// - rhs: one right-hand side of the example's disk (bladed_disk/disk_scene.hpp) of 6, 12, 24 and
//   48 blades, m modes per nodal diameter (m N annulus modes, default 6), one damper per pair of
//   neighbours, in the all-stuck mode at rest and in a sliding mode; the ratio 48 / 24 (target <= 2.2);
// - transient: 1 s of the 24-blade disk from rest at the EO 3 resonance (target <= 3 s);
// - orbit: one travelling-wave orbit of the 24-blade disk (TravellingWaveShooting from the state
//   after 10 periods, --orbit-modes per family) against one orbit of the blade example's single
//   blade (Shooting after 10 periods, its FRC options) (target <= 5x);
// - frc: an EO frequency-response curve of --frc-points travelling waves (default 100; target
//   <= 30 s), --orbit-modes per family.
#include "bladed_disk/disk_linear.hpp"
#include "bladed_disk/disk_scene.hpp"
#include "blade_damper/blade_frc.hpp"

#include <stickslip/disk.hpp>
#include <stickslip/steady_state.hpp>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace stickslip;
using bladed_disk::Index;
using bladed_disk::System;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

struct Row {
  std::string name;
  double value;
  std::string unit, note;
};
std::vector<Row> rows;

void report(const std::string& name, double value, const std::string& unit, const std::string& note = "") {
  rows.push_back({name, value, unit, note});
  std::printf("%-34s %12.5g %-4s %s\n", name.c_str(), value, unit.c_str(), note.c_str());
  std::fflush(stdout);
}

TravellingWaveOptions<double> wave_options() {
  TravellingWaveOptions<double> o;  // the example's options
  o.shooting.control_sensitivities = false;
  o.shooting.tolerance = 1e-7;
  o.shooting.stepper.rtol = 1e-9;
  o.shooting.stepper.atol = 1e-11;
  return o;
}

void write_rows(const std::string& out) {
  std::ofstream f(out);
  f << "name,value,unit,note\n";
  for (const auto& r : rows) f << r.name << ',' << r.value << ',' << r.unit << ",\"" << r.note << "\"\n";
  std::printf("rows in %s\n", out.c_str());
}

/// Mean seconds of one rhs call in `mode` at `x` (calls repeated for at least 0.2 s).
double rhs_seconds(System& sys, const System::Mode& mode, const System::State& x) {
  System::State dx(x.size());
  long calls = 0;
  const auto t0 = Clock::now();
  do {
    for (int i = 0; i < 50; ++i) sys.rhs(mode, 0.0, x, dx);
    calls += 50;
  } while (since(t0) < 0.2);
  return since(t0) / double(calls);
}

/// The example's disk of `blades` blades and `modes` modes per nodal diameter.
bladed_disk::DiskParameters disk_parameters(Index blades, Index modes) {
  bladed_disk::DiskParameters p;
  p.sectors = blades;
  p.modes_per_family = modes;
  return p;
}

/// Rest, in the requested mode made consistent.
void at_rest(System& sys, System::State& x, System::Mode& mode) {
  x = sys.initial_state();
  mode = sys.requested_mode();
  sys.make_consistent(mode, 0.0, x);
}

/// The transient of `blades` blades from rest at the EO resonance over `duration` seconds with
/// `integrator`: wall and CPU seconds, steps, events; with the exponential method (chosen or
/// asked) also a second run by ExactLinearStepper itself for its work counters.
void transient_run(Index blades, Index modes, double duration, Integrator integrator, double N0) {
  const bladed_disk::DiskScene scene(disk_parameters(blades, modes));
  System sys = scene.system(scene.engine_order_frequency(), N0);
  System::State x;
  System::Mode mode;
  at_rest(sys, x, mode);
  RunOptions<double> opt;
  opt.integrator = integrator;
  const std::string name = "transient_N" + std::to_string(blades) + "_" + std::to_string(duration) + "s";
  const auto t0 = Clock::now();
  const double c0 = cpu_seconds();
  const auto r = simulate(sys, mode, 0.0, x, duration, opt);
  const double wall = since(t0), cpu = cpu_seconds() - c0;
  report(name, wall, "s",
         r.method + ", " + std::to_string(r.stats.accepted_steps) + " steps, " + std::to_string(r.stats.rejected_steps) +
             " rejected, " + std::to_string(r.stats.events) + " events, " + std::to_string(r.stats.rhs_evaluations) +
             " rhs, " + std::string(to_string(r.status)));
  report(name + "_cpu", cpu, "s", r.method_reason);
  std::printf("final |x| %.17g\n", r.x.norm());
  if (r.method != std::string(to_string(Integrator::Exponential))) return;
  System again = scene.system(scene.engine_order_frequency(), N0);
  ExactLinearStepper<System> stepper(again);
  const double c1 = cpu_seconds();
  stepper.integrate(mode, 0.0, x, duration);
  const ExactStepperStats& w = stepper.work();
  report(name + "_exponential_cpu", cpu_seconds() - c1, "s",
         std::to_string(w.exact_steps) + " exact steps, " + std::to_string(w.exponential_steps) + " Lawson steps, " +
             std::to_string(w.linear_part_calls) + " linear parts, " + std::to_string(w.eigen_decompositions) +
             " eigen-decompositions, " + std::to_string(w.propagator_exponentials) + " exponentials, " +
             std::to_string(w.mode_cache_hits) + " cache hits, " + std::to_string(w.matvecs) + " matvecs, " +
             std::to_string(w.long_steps) + " long steps, " + std::to_string(w.grazing_refinements) + " grazing");
}

}  // namespace

int main(int argc, char** argv) {
  Index modes = 6, orbit_modes = 2;
  int frc_points = 100;
  bool transient = true, rhs_only = false, transient_only = false;
  Index blades = 24;
  double duration = 1.0;
  std::string integrator = "auto";
  std::string out = "disk_benchmark.csv";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--modes" && i + 1 < argc) modes = std::stol(argv[++i]);
    else if (a == "--orbit-modes" && i + 1 < argc) orbit_modes = std::stol(argv[++i]);
    else if (a == "--frc-points" && i + 1 < argc) frc_points = std::stoi(argv[++i]);
    else if (a == "--skip-transient") transient = false;
    else if (a == "--rhs-only") rhs_only = true;
    else if (a == "--transient-only") transient_only = true;
    else if (a == "--blades" && i + 1 < argc) blades = std::stol(argv[++i]);
    else if (a == "--duration" && i + 1 < argc) duration = std::stod(argv[++i]);
    else if (a == "--integrator" && i + 1 < argc) integrator = argv[++i];
    else if (a == "--out" && i + 1 < argc) out = argv[++i];
    else {
      std::fprintf(stderr, "usage: disk_benchmark [--modes m] [--orbit-modes m] [--frc-points n] [--skip-transient] "
                           "[--rhs-only] [--transient-only] [--blades N] [--duration T] [--integrator name] [--out f]\n");
      return 2;
    }
  }
  const double N0 = 8.0;
  if (transient_only) {
    transient_run(blades, modes, duration, parse_integrator(integrator), N0);
    write_rows(out);
    return 0;
  }
  // 1. The right-hand side against the number of blades.
  double stuck24 = 0, stuck48 = 0, slip24 = 0, slip48 = 0;
  for (Index N : {Index(6), Index(12), Index(24), Index(48)}) {
    const bladed_disk::DiskScene scene(disk_parameters(N, modes));
    System sys = scene.system(scene.engine_order_frequency(), N0);
    System::State x;
    System::Mode mode;
    at_rest(sys, x, mode);
    const double stuck = rhs_seconds(sys, mode, x);
    // Sliding: the stuck closed form's rates at a frequency where the load beats friction.
    const bladed_disk::LinearDisk lin(scene, false);
    const Eigen::VectorXcd Q = lin.modal(scene.engine_order_frequency());
    const Index n = scene.basis.size();
    x.head(n) = Q.real();
    x.segment(n, n) = (std::complex<double>(0, scene.engine_order_frequency()) * Q).real();
    System::Mode sliding = sys.requested_mode();
    sys.make_consistent(sliding, 0.0, x);
    const double slip = rhs_seconds(sys, sliding, x);
    report("rhs_stuck_N" + std::to_string(N), stuck * 1e6, "us", std::to_string(n) + " modes");
    report("rhs_sliding_N" + std::to_string(N), slip * 1e6, "us", sliding.to_string());
    if (N == 24) stuck24 = stuck, slip24 = slip;
    if (N == 48) stuck48 = stuck, slip48 = slip;
  }
  report("rhs_ratio_stuck_48_24", stuck48 / stuck24, "", "target <= 2.2");
  report("rhs_ratio_sliding_48_24", slip48 / slip24, "", "target <= 2.2");
  if (rhs_only) {
    write_rows(out);
    return 0;
  }

  // 2. A 1 s transient of the 24-blade disk.
  bladed_disk::DiskParameters p24;
  p24.modes_per_family = modes;
  if (transient) {
    const bladed_disk::DiskScene scene(p24);
    System sys = scene.system(scene.engine_order_frequency(), N0);
    System::State x = sys.initial_state();
    System::Mode mode = sys.requested_mode();
    sys.make_consistent(mode, 0.0, x);
    const auto t0 = Clock::now();
    const auto r = simulate(sys, mode, 0.0, x, 1.0);
    report("transient_1s_N24", since(t0), "s",
           r.method + ", " + std::to_string(r.stats.accepted_steps) + " steps, " + std::to_string(r.stats.events) +
               " events, target <= 3 s");
  }

  // 3. One travelling-wave orbit against one orbit of the single blade.
  p24.modes_per_family = orbit_modes;
  const bladed_disk::DiskScene scene(p24);
  const double w = scene.engine_order_frequency();
  double wave_seconds = 0;
  {
    System sys = scene.system(w, N0);
    System::State x = sys.initial_state();
    System::Mode mode = sys.requested_mode();
    sys.make_consistent(mode, 0.0, x);
    const double T = 2 * M_PI / w;
    const auto tr = simulate(sys, mode, 0.0, x, 10 * T);
    const auto shift = travelling_wave_shift(scene.disk, scene.basis, sys, p24.engine_order);
    TravellingWaveShooting<System> tw(sys, shift, wave_options());
    const auto t0 = Clock::now();
    const auto orbit = tw.solve(tr.mode, 10 * T, tr.x, T);
    wave_seconds = since(t0);
    report("orbit_wave_N24", wave_seconds, "s",
           std::string(orbit.ok() ? "converged" : "FAILED") + ", " + std::to_string(orbit.iterations) + " runs over tau, " +
               std::to_string(orbit.stats.accepted_steps) + " steps in the last, " + std::to_string(scene.basis.size()) +
               " modes");
  }
  {
    blade::BladeParameters bp;
    bp.damping_ratio = 0.005;
    blade::BladeScene blade_scene = blade::make_blade_scene(bp);
    auto& sys = *blade_scene.system;
    auto opt = blade::blade_shooting_options(sys, false);
    const double T = 2 * M_PI / bp.force_omega;
    auto x = sys.initial_state();
    auto mode = sys.requested_mode();
    sys.make_consistent(mode, 0.0, x);
    const auto tr = simulate(sys, mode, 0.0, x, 10 * T);
    Shooting<blade::BladeScene::System> shooting(sys, opt);
    const auto t0 = Clock::now();
    const auto orbit = shooting.forced(tr.mode, 10 * T, tr.x, T);
    const double blade_seconds = since(t0);
    report("orbit_single_blade", blade_seconds, "s",
           std::string(orbit.ok() ? "converged" : "FAILED") + ", " + std::to_string(orbit.iterations) + " runs");
    report("orbit_ratio_wave_blade", wave_seconds / blade_seconds, "", "target <= 5");
  }

  // 4. An EO frequency-response curve of frc_points travelling waves.
  {
    const bladed_disk::LinearDisk stuck(scene, true);
    std::vector<double> omegas;
    for (int i = 0; i < frc_points; ++i) omegas.push_back(w * (0.92 + 0.5 * i / std::max(1, frc_points - 1)));
    System first = scene.system(omegas.front(), N0);
    System::State guess = first.initial_state();
    const Index n = scene.basis.size();
    const Eigen::VectorXcd Q = stuck.modal(omegas.front());
    guess.head(n) = Q.real();
    guess.segment(n, n) = (std::complex<double>(0, omegas.front()) * Q).real();
    System::Mode mode = first.requested_mode();
    first.make_consistent(mode, 0.0, guess);
    int ok = 0;
    std::string first_failure;
    const auto t0 = Clock::now();
    const auto points = travelling_wave_sweep<System>(
        [&](double om) { return scene.system(om, N0); },
        [&](const System& s) { return travelling_wave_shift(scene.disk, scene.basis, s, p24.engine_order); }, omegas,
        mode, guess, wave_options(), [&](const TravellingWaveSweepPoint<System>& pt) {
          ok += pt.orbit.ok() ? 1 : 0;
          if (!pt.orbit.ok() && first_failure.empty())
            first_failure = "; first failure at Omega = " + std::to_string(pt.omega) + " rad/s: " +
                            std::string(to_string(pt.orbit.status)) + ", residual " + std::to_string(pt.orbit.residual) + ", " +
                            pt.orbit.message;
        });
    report("frc_N24_" + std::to_string(frc_points) + "_points", since(t0), "s",
           std::to_string(ok) + " converged, target <= 30 s for 100" + first_failure);
  }

  write_rows(out);
  return 0;
}

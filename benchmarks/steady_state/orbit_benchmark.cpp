// Cost of the blade's periodic orbits (targets: one orbit <= 50 ms, a 200-point
// frequency-response curve <= 10 s on 2 cores, and the ratio against reaching the same steady
// state by a transient). A program writing JSON (one run; ratios from that run), CPU seconds of
// this thread:
//   orbit_benchmark [--preloads a,b] [--frc-points n] [--frc-parts n] [--repeats k] [--quick]
//                   [--mu-s m] [--mu-k m] [--out file.json]
// Per preload (5 % modal damping, 200 rad/s, energy audit off, the example's shooting options):
// one plain period and one variational period (steps, RHS evaluations); shooting from rest and
// from transients of 10 and 60 periods, with the finite-difference and the variational
// monodromy (the one after 60 periods with the variational monodromy, the "one orbit",
// also as the median of k repeats, default 5); the transient from rest until x(kT) equals the shot orbit's x0 to the shooting
// tolerance (periods and CPU); the variational period with Phi out of the error control and the
// finite-difference monodromy, both monodromies against the latter; --quick skips the shootings
// after 10 periods and from rest; and, with --frc-points n > 0, a frequency branch of n points
// from 190 rad/s (its CPU per point, extrapolated to 200 points), with --frc-parts n in n parts
// on n threads (stickslip::SplitContinuation; its elapsed time too).
#include "blade_damper/blade_frc.hpp"

#include <stickslip/detail/cpu_time.hpp>
#include <stickslip/steady_state.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using System = blade::BladeScene::System;
using stickslip::detail::thread_cpu_seconds;

struct Timed {
  double cpu = 0;
  int runs = 0;
  bool ok = false;
  std::string note;
};

std::string json_timed(const Timed& t) {
  std::ostringstream o;
  o << "{\"cpu_s\": " << blade::jnum(t.cpu) << ", \"runs\": " << t.runs << ", \"ok\": " << (t.ok ? "true" : "false")
    << ", \"note\": \"" << blade::json_escape(t.note) << "\"}";
  return o.str();
}

// Shooting from a transient of `periods` periods (0: from rest made consistent); the CPU time
// of the shooting alone and of transient + shooting.
Timed shoot_after(blade::BladeScene& scene, int periods, bool fd, Timed& with_transient,
                  stickslip::PeriodicOrbit<System>* keep = nullptr) {
  auto opt = blade::blade_shooting_options(*scene.system, fd);
  const double c0 = thread_cpu_seconds();
  auto& sys = *scene.system;
  const double T = 2 * M_PI / scene.parameters.force_omega;
  System::State x = sys.initial_state();
  System::Mode mode = sys.requested_mode();
  sys.make_consistent(mode, 0.0, x);
  if (periods > 0) {
    stickslip::HybridStepper<System, stickslip::DormandPrince54> stepper(sys, opt.stepper);
    const auto tr = stepper.integrate(mode, 0.0, x, periods * T);
    x = tr.x;
    mode = tr.mode;
  }
  const double c1 = thread_cpu_seconds();
  stickslip::Shooting<System> shooting(sys, opt);
  const auto orbit = shooting.forced(mode, 0.0, x, T);
  const double c2 = thread_cpu_seconds();
  Timed t{c2 - c1, orbit.iterations, orbit.ok(), orbit.message};
  with_transient = Timed{c2 - c0, orbit.iterations, orbit.ok(), orbit.message};
  if (keep) *keep = orbit;
  return t;
}

// The blade's system without its jacobian() (has_jacobian_v false): the variational run then
// takes central differences of rhs for df/dx, as before lever (a) - its baseline in this run.
struct WithoutJacobian {
  using Scalar = System::Scalar;
  using State = System::State;
  using Mode = System::Mode;
  System sys;
  void rhs(const Mode& m, double t, const State& x, State& dxdt) { sys.rhs(m, t, x, dxdt); }
  Eigen::Index num_guards(const Mode& m) const { return sys.num_guards(m); }
  void guards(const Mode& m, double t, const State& x, System::GuardVector& g) { sys.guards(m, t, x, g); }
  stickslip::CrossingDirection guard_direction(const Mode& m, Eigen::Index i) const {
    return sys.guard_direction(m, i);
  }
  stickslip::TransitionAction transition(Mode& m, const stickslip::TriggeredGuards& w, double t, State& x) {
    return sys.transition(m, w, t, x);
  }
};
static_assert(!stickslip::has_jacobian_v<WithoutJacobian>, "the baseline must not see the jacobian");
static_assert(stickslip::has_jacobian_v<System>, "FrictionDampedSystem provides jacobian()");

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> preloads{1.0, 26.0};
  int frc_points = 0;
  int frc_parts = 1;
  bool quick = false;  // skip the shootings after 10 periods and from rest (the slow ones)
  int repeats = 5;     // of the shooting after 60 periods (variational): its median
  std::string out = "orbit_benchmark.json";
  blade::BladeParameters base;  // the paper's friction coefficients unless --mu-s / --mu-k
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--preloads" && i + 1 < argc) {
      preloads.clear();
      std::stringstream ss(argv[++i]);
      for (std::string v; std::getline(ss, v, ',');) preloads.push_back(std::stod(v));
    } else if (a == "--frc-points" && i + 1 < argc) {
      frc_points = std::stoi(argv[++i]);
    } else if (a == "--frc-parts" && i + 1 < argc) {
      frc_parts = std::max(1, std::stoi(argv[++i]));
    } else if (a == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::stoi(argv[++i]));
    } else if (a == "--quick") {
      quick = true;
    } else if (a == "--mu-s" && i + 1 < argc) {
      base.mu_s = std::stod(argv[++i]);
    } else if (a == "--mu-k" && i + 1 < argc) {
      base.mu_k = std::stod(argv[++i]);
    } else if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::fprintf(stderr, "usage: orbit_benchmark [--preloads a,b] [--frc-points n] [--frc-parts n] [--repeats k] [--quick] "
                           "[--mu-s m] [--mu-k m] [--out file.json]\n");
      return 2;
    }
  }
  std::ofstream j(out);
  j << "{\n  \"scene\": \"blade, 5 % modal damping, 200 rad/s, rtol 1e-10, Newton tolerance 1e-7\",\n  \"mu_s\": "
    << blade::jnum(base.mu_s) << ", \"mu_k\": " << blade::jnum(base.mu_k) << ",\n  \"preloads\": [";
  for (std::size_t k = 0; k < preloads.size(); ++k) {
    blade::BladeParameters p = base;
    p.preload = preloads[k];
    p.damping_ratio = 0.05;
    p.model.energy_audit = false;
    blade::BladeScene scene = blade::make_blade_scene(p);
    auto& sys = *scene.system;
    const double T = 2 * M_PI / p.force_omega;
    std::printf("N0 %g N (mu_s %g, mu_k %g)\n", p.preload, p.mu_s, p.mu_k);
    // The orbit (the reference for the transient) from the 60-period start, variational.
    stickslip::PeriodicOrbit<System> orbit;
    Timed v60t, v10t, v0t, f60t, f10t;
    const Timed v60 = shoot_after(scene, 60, false, v60t, &orbit);
    std::vector<double> v60_cpu{v60.cpu};
    for (int r = 1; r < repeats; ++r) {
      Timed with_transient;
      v60_cpu.push_back(shoot_after(scene, 60, false, with_transient).cpu);
    }
    std::sort(v60_cpu.begin(), v60_cpu.end());
    const std::size_t mid = v60_cpu.size() / 2;
    const double v60_median = v60_cpu.size() % 2 ? v60_cpu[mid] : (v60_cpu[mid - 1] + v60_cpu[mid]) / 2;
    std::printf("  one orbit (shooting after 60 periods, variational, rtol %.0e, %d run(s)): median of %d %.4f s "
                "(min %.4f, max %.4f)\n",
                blade::blade_shooting_options(sys, false).stepper.rtol, v60.runs, repeats, v60_median,
                v60_cpu.front(), v60_cpu.back());
    const Timed f60 = shoot_after(scene, 60, true, f60t);
    const Timed skipped{0, 0, false, "skipped (--quick)"};
    const Timed v10 = quick ? skipped : shoot_after(scene, 10, false, v10t);
    const Timed f10 = quick ? skipped : shoot_after(scene, 10, true, f10t);
    const Timed v0 = quick ? skipped : shoot_after(scene, 0, false, v0t);
    std::printf("  shooting after 60 / 10 / 0 periods: variational %.3f / %.3f / %.3f s, finite differences %.3f / %.3f s\n",
                v60.cpu, v10.cpu, v0.cpu, f60.cpu, f10.cpu);
    // One plain and one variational period of the orbit.
    auto opt = blade::blade_shooting_options(sys, false);
    opt.control_sensitivities = true;  // the example's options leave Phi out: measured below
    double c0 = thread_cpu_seconds();
    const auto plain = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, T, opt, false);
    const double plain_cpu = thread_cpu_seconds() - c0;
    c0 = thread_cpu_seconds();
    const auto var = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, T, opt, true);
    const double var_cpu = thread_cpu_seconds() - c0;
    std::printf("  one period: plain %.4f s (%ld steps, %ld RHS), variational %.4f s (%ld steps, %ld RHS)\n", plain_cpu,
                plain.stats.accepted_steps, plain.stats.rhs_evaluations, var_cpu, var.stats.accepted_steps,
                var.stats.rhs_evaluations);
    // Lever (b): Phi out of the error control; both variational monodromies against the
    // finite-difference one (an independent computation: 2n plain periods).
    auto free_opt = opt;
    free_opt.control_sensitivities = false;
    c0 = thread_cpu_seconds();
    const auto var_free = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, T, free_opt, true);
    const double var_free_cpu = thread_cpu_seconds() - c0;
    auto fd_opt = blade::blade_shooting_options(sys, true);
    c0 = thread_cpu_seconds();
    const auto fdm = stickslip::run_period(sys, orbit.mode, 0.0, orbit.x0, T, fd_opt, true);
    const double fd_cpu = thread_cpu_seconds() - c0;
    // Lever (a): the same variational period without the model's jacobian (central differences).
    WithoutJacobian bare{sys};
    c0 = thread_cpu_seconds();
    const auto var_bare = stickslip::run_period(bare, orbit.mode, 0.0, orbit.x0, T, opt, true);
    const double var_bare_cpu = thread_cpu_seconds() - c0;
    auto bare_free_opt = free_opt;
    c0 = thread_cpu_seconds();
    const auto var_bare_free = stickslip::run_period(bare, orbit.mode, 0.0, orbit.x0, T, bare_free_opt, true);
    const double var_bare_free_cpu = thread_cpu_seconds() - c0;
    std::printf("  variational period without the model's jacobian (differences): %.4f s (%ld steps), Phi free %.4f s "
                "(%ld steps)\n",
                var_bare_cpu, var_bare.stats.accepted_steps, var_bare_free_cpu, var_bare_free.stats.accepted_steps);
    const auto P = static_cast<Eigen::Index>(opt.periodic.size());
    const auto block_diff = [&](const auto& a) {
      return (a.monodromy.topLeftCorner(P, P) - fdm.monodromy.topLeftCorner(P, P)).cwiseAbs().maxCoeff() /
             std::max(1.0, fdm.monodromy.topLeftCorner(P, P).cwiseAbs().maxCoeff());
    };
    const double diff_var = var.ok() && fdm.ok() ? block_diff(var) : NAN;
    const double diff_free = var_free.ok() && fdm.ok() ? block_diff(var_free) : NAN;
    std::printf("  variational period, Phi out of the error control: %.4f s (%ld steps, %ld RHS); finite-difference "
                "monodromy %.4f s; max |M - M_fd| / max(1, |M_fd|) over the periodic block: %.2e (Phi controlled), "
                "%.2e (Phi free)\n",
                var_free_cpu, var_free.stats.accepted_steps, var_free.stats.rhs_evaluations, fd_cpu, diff_var,
                diff_free);
    // The transient from rest until x(kT) is the orbit's x0 to the shooting tolerance.
    System::State x = sys.initial_state();
    System::Mode mode = sys.requested_mode();
    sys.make_consistent(mode, 0.0, x);
    stickslip::HybridStepper<System, stickslip::DormandPrince54> stepper(sys, opt.stepper);
    const double scale = std::max(1.0, orbit.x0.head(static_cast<Eigen::Index>(opt.periodic.size())).cwiseAbs().maxCoeff());
    int periods = 0;
    double diff = INFINITY;
    c0 = thread_cpu_seconds();
    while (orbit.ok() && periods < 5000) {
      const auto r = stepper.integrate(mode, periods * T, x, (periods + 1) * T);
      if (!r.ok()) break;
      x = r.x;
      mode = r.mode;
      ++periods;
      diff = 0;
      for (Eigen::Index i : opt.periodic) diff = std::max(diff, std::abs(x[i] - orbit.x0[i]));
      if (diff <= opt.tolerance * scale) break;
    }
    const double transient_cpu = thread_cpu_seconds() - c0;
    std::printf("  transient to the orbit (|x(kT) - x0| <= %.0e): %d periods, %.3f s; ratio to shooting after 60 "
                "periods (with the transient): %.2f\n",
                opt.tolerance * scale, periods, transient_cpu, transient_cpu / v60t.cpu);
    j << (k ? "," : "") << "\n    {\"preload_N\": " << blade::jnum(p.preload) << ", \"orbit_ok\": " << (orbit.ok() ? "true" : "false")
      << ", \"events_per_period\": " << orbit.events.size() << ",\n     \"shooting_variational\": {\"after_60\": "
      << json_timed(v60) << ", \"after_60_median_cpu_s\": " << blade::jnum(v60_median) << ", \"after_60_repeats\": "
      << repeats << ", \"after_60_with_transient\": " << json_timed(v60t) << ", \"after_10\": " << json_timed(v10)
      << ", \"after_10_with_transient\": " << json_timed(v10t) << ", \"from_rest\": " << json_timed(v0) << "},\n"
      << "     \"shooting_finite_difference\": {\"after_60\": " << json_timed(f60) << ", \"after_60_with_transient\": "
      << json_timed(f60t) << ", \"after_10\": " << json_timed(f10) << ", \"after_10_with_transient\": " << json_timed(f10t)
      << "},\n     \"plain_period\": {\"cpu_s\": " << blade::jnum(plain_cpu) << ", \"steps\": " << plain.stats.accepted_steps
      << ", \"rhs\": " << plain.stats.rhs_evaluations << "}, \"variational_period\": {\"cpu_s\": " << blade::jnum(var_cpu)
      << ", \"steps\": " << var.stats.accepted_steps << ", \"rhs\": " << var.stats.rhs_evaluations
      << ", \"monodromy_vs_fd\": " << blade::jnum(diff_var) << "},\n     \"variational_period_phi_free\": {\"cpu_s\": "
      << blade::jnum(var_free_cpu) << ", \"steps\": " << var_free.stats.accepted_steps << ", \"rhs\": "
      << var_free.stats.rhs_evaluations << ", \"monodromy_vs_fd\": " << blade::jnum(diff_free)
      << "}, \"fd_monodromy_period\": {\"cpu_s\": " << blade::jnum(fd_cpu) << "},\n     "
      << "\"variational_period_without_jacobian\": {\"cpu_s\": " << blade::jnum(var_bare_cpu) << ", \"steps\": "
      << var_bare.stats.accepted_steps << ", \"phi_free_cpu_s\": " << blade::jnum(var_bare_free_cpu)
      << ", \"phi_free_steps\": " << var_bare_free.stats.accepted_steps << "},\n     \"transient_to_orbit\": {\"periods\": " << periods << ", \"cpu_s\": " << blade::jnum(transient_cpu)
      << ", \"final_difference\": " << blade::jnum(diff) << ", \"ratio_to_shooting_after_60_with_transient\": "
      << blade::jnum(transient_cpu / v60t.cpu) << "}";
    if (frc_points > 0) {
      blade::FrcSettings s;
      s.f_lo = 190 / (2 * M_PI);
      s.f_hi = 260 / (2 * M_PI);
      s.max_points = frc_points;
      s.parts = frc_parts;
      const auto b = blade::frc_branch(scene, s, blade::frc_state_scale(scene, s), {});
      const double per_point = b.points.empty() ? NAN : b.cpu_seconds / static_cast<double>(b.points.size());
      const double wall_per_point = b.points.empty() ? NAN : b.wall_seconds / static_cast<double>(b.points.size());
      std::printf("  frequency branch in %d part(s): %s, %zu points, %.2f s CPU (%.3f s per point; 200 points ~%.0f s), "
                  "%.2f s elapsed (200 points ~%.0f s)\n",
                  frc_parts, b.status.c_str(), b.points.size(), b.cpu_seconds, per_point, 200 * per_point,
                  b.wall_seconds, 200 * wall_per_point);
      for (std::size_t q = 0; q < b.parts.size(); ++q)
        std::printf("    %s, %.2f s CPU\n", blade::frc_part_line(q, b.parts[q]).c_str(), b.parts[q].cpu_seconds);
      j << ",\n     \"frc\": {\"parts\": " << frc_parts << ", \"points\": " << b.points.size()
        << ", \"cpu_s\": " << blade::jnum(b.cpu_seconds) << ", \"wall_s\": " << blade::jnum(b.wall_seconds)
        << ", \"cpu_per_point_s\": " << blade::jnum(per_point) << ", \"wall_per_point_s\": " << blade::jnum(wall_per_point)
        << ", \"status\": \"" << b.status << "\"}";
    }
    j << "}";
    std::fflush(stdout);
  }
  j << "\n  ]\n}\n";
  std::printf("wrote %s\n", out.c_str());
  return 0;
}

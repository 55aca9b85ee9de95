// grounded_slider: a clamped cantilever (20 elements, 6 modes) with a grounded Coulomb slider at
// mid-span and a harmonic tip force; the frequency-response curve of its periodic orbits through
// the first resonance, by shooting and pseudo-arclength continuation, restarted past the places
// where the continuation stalls (RestartingContinuation: with mu_s > mu_k the period map is
// discontinuous where a stick phase appears), between the linear curves of the free and the
// pinned slider.
//
// Usage: grounded_slider [--points-out FILE.csv] [--json FILE.json] [--range lo:hi]
//                        [--restarts n] [--gap g] [--settle periods] [--stall-points n]
//                        [--integrator exponential|dopri5] [--fixed-section]
//   (range and gap in units of the free cantilever's first frequency; default range 0.8:2.2,
//   4 restarts, gap 0.01, 200 periods of transient before each restart's Poincare sections, a
//   segment stalls when 40 points advance the frequency by less than 1e-3 omega_1; the orbits'
//   runs by the exact method on the slider's linear modes by default, or by Dormand-Prince;
//   --fixed-section keeps the section at the end of the start's transient, t0 = 40 T, instead of
//   t0 mod T: ContinuationOptions::wrap_section = false, the helix that stalls the corrector)
// Writes the curve (frequency, tip amplitude, stability, stick fraction, segment) as CSV, a JSON
// summary with the elapsed and CPU time and the segments, and prints one line per point.

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

using namespace stickslip;
using System = ContactSystem<double>;
constexpr double kPi = 3.14159265358979323846;

namespace {

struct Scene {
  FrameModel<double> frame;
  MemberId beam = 0;
  NodeId tip = 0, mid = 0;
  ModalBasis<double> basis;
  double length = 0.2, F0 = 2.0, mu_s = 0.35, mu_k = 0.3, N = 10.0;

  Scene() {
    const NodeId root = frame.add_node(0, 0);
    tip = frame.add_node(0, length);
    beam = frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, 20);
    frame.clamp(root);
    mid = frame.member(beam).nodes[10];
    ModalOptions<double> mo;
    mo.num_modes = 6;
    basis = compute_modes(frame.assemble(), mo).with_modal_damping(Eigen::VectorXd::Constant(6, 0.01));
  }
  /// The system at excitation frequency w [rad/s].
  System system(double w) const {
    std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
        {beam, length / 2}, PlaneDirection<double>::global_x(), CoulombLaw<double>(mu_s, mu_k), N)};
    std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(beam, length, LoadDirection::GlobalX, F0, w)};
    ContactSystemOptions<double> o;
    o.energy_audit = false;  // the steady states need only the mechanical states
    return System(frame, basis, contacts, loads, o);
  }
  /// Linear tip receptance amplitude at w: free slider (modal sum) or pinned (Lagrange solve).
  double linear_tip(double w, bool pinned) const {
    const Eigen::Index n = basis.size();
    const Eigen::VectorXd phi = basis.nodal(tip, Dof::X).transpose(), wr = basis.nodal(mid, Dof::X).transpose();
    Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(n + 1, n + 1);
    Eigen::VectorXcd b = Eigen::VectorXcd::Zero(n + 1);
    for (Eigen::Index j = 0; j < n; ++j)
      A(j, j) = {basis.omega()(j) * basis.omega()(j) - w * w, w * basis.damping_coefficients()(j)};
    if (pinned) {
      A.block(0, n, n, 1) = -wr.cast<std::complex<double>>();
      A.block(n, 0, 1, n) = wr.transpose().cast<std::complex<double>>();
    } else {
      A(n, n) = 1;
    }
    b.head(n) = (phi * F0).cast<std::complex<double>>();
    const Eigen::VectorXcd q = A.fullPivLu().solve(b);
    return std::abs(phi.cast<std::complex<double>>().dot(q.head(n)));
  }
};

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

/// All of `text` as a finite number; throws std::invalid_argument naming `option` otherwise.
double number(const std::string& text, const std::string& option) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw std::invalid_argument(option + " expects a finite number, got '" + text + "'");
  return v;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string csv = "grounded_slider_frc.csv", json = "grounded_slider_frc.json";
  double lo = 0.8, hi = 2.2, gap = 0.01;
  int restarts = 4, settle = 200, stall = 40;
  OrbitIntegrator integrator = OrbitIntegrator::Exponential;
  bool wrap_section = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--points-out") csv = next();
    else if (a == "--json") json = next();
    else if (a == "--integrator") {
      const std::string m = next();
      if (m == "exponential") integrator = OrbitIntegrator::Exponential;
      else if (m == "dopri5") integrator = OrbitIntegrator::DormandPrince54;
      else throw std::invalid_argument("--integrator expects exponential or dopri5, got " + m);
    }
    else if (a == "--fixed-section") wrap_section = false;
    else if (a == "--restarts") {
      const double r = number(next(), a);
      if (!(r >= 0 && r <= 1000 && r == std::floor(r))) throw std::invalid_argument("--restarts expects an integer in [0, 1000]");
      restarts = static_cast<int>(r);
    }
    else if (a == "--settle") {
      const double n = number(next(), a);
      if (!(n >= 0 && n <= 100000 && n == std::floor(n))) throw std::invalid_argument("--settle expects an integer in [0, 100000]");
      settle = static_cast<int>(n);
    }
    else if (a == "--stall-points") {
      const double n = number(next(), a);
      if (!(n >= 2 && n <= 100000 && n == std::floor(n))) throw std::invalid_argument("--stall-points expects an integer in [2, 100000]");
      stall = static_cast<int>(n);
    }
    else if (a == "--gap") {
      gap = number(next(), a);
      if (!(gap > 0)) throw std::invalid_argument("--gap expects a number > 0");
    }
    else if (a == "--range") {
      const std::string r = next();
      const auto colon = r.find(':');
      if (colon == std::string::npos) throw std::invalid_argument("--range expects lo:hi, got " + r);
      lo = number(r.substr(0, colon), a);
      hi = number(r.substr(colon + 1), a);
      if (!(lo > 0 && hi > lo)) throw std::invalid_argument("--range expects 0 < lo < hi, got " + r);
    } else if (a == "--help") {
      std::printf("grounded_slider [--points-out FILE.csv] [--json FILE.json] [--range lo:hi] [--restarts n] [--gap g] "
                  "[--settle periods] [--stall-points n] [--integrator exponential|dopri5] [--fixed-section]\n");
      return 0;
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  const Scene scene;
  const double w1 = scene.basis.omega()(0);  // parameter p = w / w1 (order one, as the states' scale)
  System system = scene.system(lo * w1);

  ShootingOptions<double> so;
  so.integrator = integrator;
  ContinuationOptions<double> co;
  co.parameter_min = lo;
  co.parameter_max = hi;
  co.initial_step = 0.005;
  co.max_step = 0.02;
  co.max_points = 2000;
  // (section_margin: the default 0.02 keeps the section t0 away from the slider's switches)
  co.max_corrector_distance = 2;
  co.chord_iterations = 4;
  // The start's section t0 = 40 T is taken modulo T (the default): at a fixed t0 the orbit's state
  // turns with the forcing phase w t0, 40 turns per unit of p, which the predictor cannot follow.
  co.wrap_section = wrap_section;
  // A line per point: the branch's CPU so far and its estimate of what remains.
  co.progress = [w1](const ContinuationProgress& pr) {
    std::printf("grounded_slider: point %d at %.3f Hz (%.0f %% of the range), %.2f s CPU", pr.points,
                pr.parameter * w1 / (2 * kPi), 100 * pr.covered, pr.cpu_seconds);
    if (pr.remaining_seconds >= 0) std::printf(", ~%.1f s to go", pr.remaining_seconds);
    std::printf("\n");
    std::fflush(stdout);
  };
  // Restarts: past a stall (the step below min_step, or `stall` points that advance the frequency by
  // less than 1e-3 omega_1 together: the corrector crawling towards a discontinuity of the period
  // map), the response settles one gap further, and its Poincare sections give the period of the
  // next segment. 200 periods by default: with 1 % modal damping a sliding transient decays as
  // exp(-2 pi zeta n) per n periods, 3e-6 after 200, within a factor 10 of the sections'
  // recurrence tolerance 1e-5 (an Undecided candidate is shot: Newton decides).
  RestartOptions<double> ro;
  ro.gap = gap;
  ro.max_restarts = restarts;
  ro.settle_periods = settle;
  ro.stall_points = stall;
  ro.stall_progress = 1e-3;
  auto set_parameter = [&scene, w1](System& sys, double p) { sys = scene.system(p * w1); };
  auto period = [w1](double p) { return 2 * kPi / (p * w1); };
  RestartingContinuation<System> branch(system, set_parameter, period, so, co, ro);
  // The mode at t0 from the state: sliding where |v| > 0, else stuck unless mu_s N is exceeded.
  branch.start_mode([](System& sys, double t0, const System::State& x, const System::Mode& previous) {
    System::State y = x;
    auto mode = previous;
    sys.make_consistent(mode, t0, y);
    sys.clear_events();
    return mode;
  });
  const auto wall0 = std::chrono::steady_clock::now();
  const double cpu0 = cpu_seconds();
  // The start guess: the end of a transient of 40 periods from rest.
  auto x = system.initial_state();
  auto mode = system.requested_mode();
  system.make_consistent(mode, 0.0, x);
  RunOptions<double> run0;
  run0.integrator = integrator == OrbitIntegrator::Exponential ? Integrator::Exponential : Integrator::DormandPrince54;
  run0.stepper.rtol = 1e-9;
  run0.stepper.atol = 1e-12;
  const double T0 = period(lo);
  const auto settled = simulate(system, mode, 0.0, x, 40 * T0, run0);
  const auto result = branch.run(settled.mode, 40 * T0, settled.x, lo);
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = cpu_seconds() - cpu0;

  // Tip amplitude of each orbit: one period sampled from the orbit's state.
  const Eigen::VectorXd tip_row = scene.basis.nodal(scene.tip, Dof::X).transpose();
  std::FILE* f = std::fopen(csv.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + csv);
  std::fprintf(f, "omega_rad_s,frequency_hz,tip_amplitude_m,stable,stick_fraction,linear_free_m,linear_pinned_m,"
                  "segment,kind,period_multiple\n");
  std::size_t count = 0;
  for (std::size_t s = 0; s < result.segments.size(); ++s) {
    const auto& seg = result.segments[s];
    for (const auto& pt : seg.branch.points) {
      const double w = pt.parameter * w1;
      System sys = scene.system(w);
      struct TipRange : NullObserver {
        const Eigen::VectorXd* row;
        double lo = 1e300, hi = -1e300;
        long stuck = 0, samples = 0;
        bool on_sample(double, const System::State& x, const System::Mode& m) {
          const double tip = row->dot(x.head(row->size()));
          lo = std::min(lo, tip);
          hi = std::max(hi, tip);
          stuck += m[0] == ContactState::Stick;
          ++samples;
          return true;
        }
      } range;
      range.row = &tip_row;
      RunOptions<double> run;
      run.integrator = run0.integrator;
      run.stepper.rtol = 1e-10;
      run.stepper.atol = 1e-13;
      run.stepper.output_interval = pt.orbit.period / (400 * seg.period_multiple);
      simulate(sys, pt.orbit.mode, pt.orbit.t0, pt.orbit.x0, pt.orbit.t0 + pt.orbit.period, run, range);
      std::fprintf(f, "%.10g,%.10g,%.10g,%d,%.6g,%.10g,%.10g,%zu,%s,%d\n", w, w / (2 * kPi), (range.hi - range.lo) / 2,
                   pt.orbit.floquet.stable ? 1 : 0, double(range.stuck) / double(std::max(1L, range.samples)),
                   scene.linear_tip(w, false), scene.linear_tip(w, true), s, to_string(seg.kind), seg.period_multiple);
      if (count++ % 10 == 0)
        std::printf("grounded_slider: point %zu at %.2f Hz, tip amplitude %.4g m (segment %zu)\n", count - 1, w / (2 * kPi),
                    (range.hi - range.lo) / 2, s);
    }
  }
  std::fclose(f);
  std::FILE* j = std::fopen(json.c_str(), "w");
  if (!j) throw std::runtime_error("cannot write " + json);
  std::fprintf(j,
               "{\n  \"points\": %zu,\n  \"completed\": %s,\n  \"status\": \"%s\",\n  \"integrator\": \"%s\",\n"
               "  \"restarts\": %d,\n  \"failed_restarts\": %zu,\n"
               "  \"elapsed_s\": %.3f,\n  \"cpu_s\": %.3f,\n  \"range_hz\": [%.6g, %.6g],\n  \"segments\": [",
               result.points(), result.completed() ? "true" : "false", to_string(result.status), to_string(integrator),
               result.restarts, result.failed.size(), elapsed, cpu, lo * w1 / (2 * kPi), hi * w1 / (2 * kPi));
  for (std::size_t s = 0; s < result.segments.size(); ++s) {
    const auto& seg = result.segments[s];
    const auto& pts = seg.branch.points;
    std::fprintf(j, "%s\n    {\"kind\": \"%s\", \"period_multiple\": %d, \"points\": %zu, \"from_hz\": %.6g, \"to_hz\": %.6g, "
                    "\"status\": \"%s\", \"cpu_s\": %.3f}",
                 s ? "," : "", to_string(seg.kind), seg.period_multiple, pts.size(),
                 pts.empty() ? 0.0 : pts.front().parameter * w1 / (2 * kPi),
                 pts.empty() ? 0.0 : pts.back().parameter * w1 / (2 * kPi), to_string(seg.branch.status), seg.cpu_seconds);
  }
  std::fprintf(j, "\n  ]\n}\n");
  std::fclose(j);
  for (std::size_t s = 0; s < result.segments.size(); ++s) {
    const auto& seg = result.segments[s];
    if (seg.branch.points.empty()) continue;
    std::printf("grounded_slider: segment %zu (%s, period %d T): %zu points, %.3f-%.3f Hz, %s%s%s\n", s, to_string(seg.kind),
                seg.period_multiple, seg.branch.points.size(), seg.branch.points.front().parameter * w1 / (2 * kPi),
                seg.branch.points.back().parameter * w1 / (2 * kPi), to_string(seg.branch.status),
                seg.branch.message.empty() ? "" : ": ", seg.branch.message.c_str());
  }
  for (const auto& fr : result.failed)
    std::printf("grounded_slider: restart at %.3f Hz failed: %s\n", fr.parameter * w1 / (2 * kPi), fr.reason.c_str());
  if (!result.completed()) std::printf("grounded_slider: %s\n", result.message.c_str());
  std::printf("grounded_slider: %zu points over %.1f-%.1f Hz (%s) in %zu segments (%d restarts, %zu failed) in %.2f s elapsed, "
              "%.2f s CPU, %s; %s, %s\n",
              result.points(), lo * w1 / (2 * kPi), hi * w1 / (2 * kPi), to_string(result.status), result.segments.size(),
              result.restarts, result.failed.size(), elapsed, cpu, to_string(integrator), csv.c_str(), json.c_str());
  return result.completed() ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "grounded_slider: %s\n", e.what());
  return 2;
}

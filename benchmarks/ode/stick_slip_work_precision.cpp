// Work-precision on a single-DOF stick-slip oscillator (mass-spring on a moving belt, mu_s > mu_k)
// with closed-form switch times: the paper's RK4 + bisection against Dormand-Prince + dense root
// finding. Prints a CSV (method, parameter, seconds per run, max switch-time error, final-state
// error, steps, RHS evaluations, events) and a summary: the speed-up at equal switch-time error and
// the smallest final-state error each method reaches.

#include <stickslip/ode.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "ode/ode_bench_systems.hpp"

namespace {

using stickslip::bench::BeltOscillator;

struct Point {
  std::string method;
  double parameter, seconds, switch_error, final_error;
  long steps, rhs, events;
};

struct SwitchLog : stickslip::NullObserver {
  std::vector<double> times;
  void on_event(const stickslip::EventRecord<double, int>& e) { times.push_back(e.t); }
};

constexpr double kEnd = 60.0;

template <class Method>
Point run(const std::string& name, double parameter, stickslip::StepperOptions<double> opt) {
  BeltOscillator sys;
  stickslip::HybridStepper<BeltOscillator, Method> stepper(sys, opt);
  const Eigen::Vector2d x0(0.0, sys.v_b);
  SwitchLog log;
  auto r = stepper.integrate(0, 0.0, x0, kEnd, log);
  Point p{name, parameter, 0, 0, 0, r.stats.accepted_steps, r.stats.rhs_evaluations,
          r.stats.events};
  if (!r.ok()) {
    std::fprintf(stderr, "%s %g: %s\n", name.c_str(), parameter, r.message.c_str());
    p.switch_error = p.final_error = std::numeric_limits<double>::infinity();
  } else {
    for (std::size_t k = 0; k < log.times.size(); ++k)
      p.switch_error = std::max(p.switch_error,
                                std::abs(log.times[k] - sys.switch_time(static_cast<int>(k))));
    p.final_error = (r.x - sys.exact(kEnd)).cwiseAbs().maxCoeff();
  }
  p.seconds = stickslip::bench::seconds_per_run([&] {
    const auto rr = stepper.integrate(0, 0.0, x0, kEnd);
    if (rr.x[0] == 12345.0) std::puts("");
  });
  return p;
}

// Seconds the curve `c` (sorted by error) needs for switch-time error e (log-log interpolation);
// NaN when e is outside its range.
double seconds_at(const std::vector<Point>& c, double e) {
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const double e0 = c[i].switch_error, e1 = c[i + 1].switch_error;
    if ((e <= e0 && e >= e1) || (e >= e0 && e <= e1)) {
      if (e0 == e1) return c[i].seconds;
      const double w = std::log(e / e0) / std::log(e1 / e0);
      return std::exp(std::log(c[i].seconds) + w * (std::log(c[i + 1].seconds) - std::log(c[i].seconds)));
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

int main() {
  using stickslip::EventLocation;
  std::vector<Point> rk4_bis, rk4_root, dp_root, dp_bis;
  for (double h : {2e-2, 1e-2, 5e-3, 2e-3, 1e-3, 5e-4, 2e-4, 1e-4}) {
    stickslip::StepperOptions<double> opt;
    opt.fixed_step = h;
    opt.event_time_tolerance = 1e-13;
    opt.event_location = EventLocation::Bisection;
    rk4_bis.push_back(run<stickslip::RungeKutta4>("rk4_bisection", h, opt));
    opt.event_location = EventLocation::DenseRootFinding;
    rk4_root.push_back(run<stickslip::RungeKutta4>("rk4_root", h, opt));
  }
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13}) {
    stickslip::StepperOptions<double> opt;
    opt.rtol = tol;
    opt.atol = tol * 1e-2;
    opt.event_time_tolerance = 1e-13;
    opt.event_location = EventLocation::DenseRootFinding;
    dp_root.push_back(run<stickslip::DormandPrince54>("dopri_root", tol, opt));
    opt.event_location = EventLocation::Bisection;
    dp_bis.push_back(run<stickslip::DormandPrince54>("dopri_bisection", tol, opt));
  }
  std::printf("method,parameter,seconds,switch_error,final_error,steps,rhs,events\n");
  for (const auto* c : {&rk4_bis, &rk4_root, &dp_root, &dp_bis})
    for (const auto& p : *c)
      std::printf("%s,%g,%.4e,%.3e,%.3e,%ld,%ld,%ld\n", p.method.c_str(), p.parameter, p.seconds,
                  p.switch_error, p.final_error, p.steps, p.rhs, p.events);

  std::printf("\n# speed-up of dopri_root over rk4_bisection at equal switch-time error\n");
  for (const auto& p : dp_root) {
    const double ref = seconds_at(rk4_bis, p.switch_error);
    if (std::isfinite(ref))
      std::printf("# switch error %.2e: rk4_bisection %.3e s, dopri_root %.3e s, speed-up %.1fx\n",
                  p.switch_error, ref, p.seconds, ref / p.seconds);
  }
  auto best = [](const std::vector<Point>& c) {
    double e = std::numeric_limits<double>::infinity();
    for (const auto& p : c) e = std::min(e, p.final_error);
    return e;
  };
  std::printf("# smallest final-state error: rk4_bisection %.2e, rk4_root %.2e, dopri_root %.2e, "
              "dopri_bisection %.2e\n",
              best(rk4_bis), best(rk4_root), best(dp_root), best(dp_bis));
  return 0;
}

// The state at a root-found event: the dense output at the located time (EventState::DenseOutput)
// against re-integrating one step of the method to it and refining the root on that step
// (EventState::Reintegrate). Two systems with closed forms: the belt stick-slip oscillator
// (switch times and final state) and an elastic bouncing ball (impact times, final state).
// Prints a CSV (system, method, parameter, event state, RHS evaluations, guard evaluations,
// events, extra RHS per event of Reintegrate, max event-time error, final-state error, seconds
// per run) and, per row pair, the share of a Reintegrate run's RHS evaluations spent on events.

#include <stickslip/ode.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ode/ode_bench_systems.hpp"

namespace {

using stickslip::EventState;
using stickslip::bench::BeltOscillator;
using stickslip::bench::ElasticBall;

struct Times : stickslip::NullObserver {
  std::vector<double> t;
  template <class Mode>
  void on_event(const stickslip::EventRecord<double, Mode>& e) { t.push_back(e.t); }
};

// Closed forms of the two systems.
struct BeltCase {
  using System = BeltOscillator;
  static constexpr const char* name = "belt";
  static constexpr double t_end = 60.0;
  BeltOscillator sys;
  Eigen::Vector2d x0() const { return {0.0, sys.v_b}; }
  double event_time(int k) const { return sys.switch_time(k); }
  Eigen::Vector2d exact(double t) const { return sys.exact(t); }
};

struct BallCase {
  using System = ElasticBall;
  static constexpr const char* name = "elastic_ball";
  static constexpr double t_end = 20.0;
  static constexpr double g = 9.81, h0 = 1.0;
  ElasticBall sys;
  Eigen::Vector2d x0() const { return {h0, 0.0}; }
  double fall() const { return std::sqrt(2.0 * h0 / g); }
  double event_time(int k) const { return (2.0 * k + 1.0) * fall(); }
  Eigen::Vector2d exact(double t) const {
    // Time since the last apex (apexes at 2 k fall, height h0, at rest).
    const double tau = std::fmod(t + fall(), 2.0 * fall()) - fall();
    return {h0 - 0.5 * g * tau * tau, -g * tau};
  }
};

struct Row {
  long rhs, guards, events;
  double time_error, final_error, seconds;
};

template <class Method, class Case>
Row run(Case& c, stickslip::StepperOptions<double> opt) {
  stickslip::HybridStepper<typename Case::System, Method> stepper(c.sys, opt);
  Times log;
  const auto r = stepper.integrate(0, 0.0, c.x0(), Case::t_end, log);
  Row row{r.stats.rhs_evaluations, r.stats.guard_evaluations, r.stats.events, 0, 0, 0};
  if (!r.ok()) {
    std::fprintf(stderr, "%s: %s\n", Case::name, r.message.c_str());
    return row;
  }
  for (std::size_t k = 0; k < log.t.size(); ++k)
    row.time_error = std::max(row.time_error, std::abs(log.t[k] - c.event_time(static_cast<int>(k))));
  row.final_error = (r.x - c.exact(Case::t_end)).cwiseAbs().maxCoeff();
  long runs = 0;
  const auto start = std::chrono::steady_clock::now();
  do {
    const auto rr = stepper.integrate(0, 0.0, c.x0(), Case::t_end);
    if (rr.x[0] == 12345.0) std::puts("");
    ++runs;
    row.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (row.seconds < 0.1);
  row.seconds /= static_cast<double>(runs);
  return row;
}

template <class Method, class Case>
void compare(const char* method, double parameter, stickslip::StepperOptions<double> opt) {
  Case c;
  opt.event_state = EventState::DenseOutput;
  const Row d = run<Method>(c, opt);
  opt.event_state = EventState::Reintegrate;
  const Row r = run<Method>(c, opt);
  const double extra = static_cast<double>(r.rhs - d.rhs) / static_cast<double>(std::max(1L, r.events));
  for (const auto& [state, row] : {std::pair{"dense_output", d}, std::pair{"reintegrate", r}})
    std::printf("%s,%s,%g,%s,%ld,%ld,%ld,%.1f,%.3e,%.3e,%.4e\n", Case::name, method, parameter,
                state, row.rhs, row.guards, row.events, extra, row.time_error, row.final_error,
                row.seconds);
  std::printf("# %s %s %g: re-integration share of the RHS evaluations %.0f %%, time ratio %.2f\n",
              Case::name, method, parameter,
              100.0 * static_cast<double>(r.rhs - d.rhs) / static_cast<double>(r.rhs),
              r.seconds / d.seconds);
}

template <class Case>
void all() {
  for (double h : {1e-2, 1e-3, 1e-4}) {
    stickslip::StepperOptions<double> opt;
    opt.fixed_step = h;
    compare<stickslip::RungeKutta4, Case>("rk4", h, opt);
  }
  for (double tol : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-13}) {
    stickslip::StepperOptions<double> opt;
    opt.rtol = tol;
    opt.atol = tol * 1e-2;
    compare<stickslip::DormandPrince54, Case>("dopri", tol, opt);
  }
}

}  // namespace

int main() {
  std::printf("system,method,parameter,event_state,rhs,guards,events,extra_rhs_per_event,"
              "max_event_time_error,final_error,seconds\n");
  all<BeltCase>();
  all<BallCase>();
  return 0;
}

// Google Benchmark of HybridStepper: cost per step and per RHS evaluation (state sizes 2..128,
// fixed and dynamic), cost per located event (bisection vs dense root finding), and the price of
// being generic (against a hand-written Dormand-Prince loop on the same right-hand side).

#include <stickslip/ode.hpp>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "ode/ode_bench_systems.hpp"

namespace {

using stickslip::HybridStepper;
using stickslip::StepperOptions;
using stickslip::bench::ElasticBall;
using stickslip::bench::SpringChain;

template <int N>
typename SpringChain<N>::State chain_start(Eigen::Index n) {
  typename SpringChain<N>::State x = SpringChain<N>::State::Zero(n);
  x[0] = 1.0;
  return x;
}

void report(benchmark::State& s, const stickslip::StepperStats& st, long runs) {
  using benchmark::Counter;
  s.counters["steps"] = static_cast<double>(st.accepted_steps);
  s.counters["time_per_step"] =
      Counter(static_cast<double>(st.accepted_steps * runs), Counter::kIsRate | Counter::kInvert);
  s.counters["time_per_rhs"] =
      Counter(static_cast<double>(st.rhs_evaluations * runs), Counter::kIsRate | Counter::kInvert);
}

// Steps of exactly 0.01 over [0, 10]: 1000 steps per run.
template <class Method, int N>
void BM_StepCost(benchmark::State& s) {
  const Eigen::Index n = N == Eigen::Dynamic ? static_cast<Eigen::Index>(s.range(0)) : N;
  SpringChain<N> sys;
  StepperOptions<double> opt;
  opt.fixed_step = opt.initial_step = opt.max_step = 0.01;
  opt.rtol = opt.atol = 1.0;
  HybridStepper<SpringChain<N>, Method> stepper(sys, opt);
  const auto x0 = chain_start<N>(n);
  stickslip::StepperStats st;
  long runs = 0;
  for (auto _ : s) {
    auto r = stepper.integrate(0, 0.0, x0, 10.0);
    benchmark::DoNotOptimize(r.x.data());
    st = r.stats;
    ++runs;
  }
  report(s, st, runs);
}

#define STICKSLIP_STEP_COST(METHOD)                                  \
  BENCHMARK_TEMPLATE(BM_StepCost, stickslip::METHOD, 2);             \
  BENCHMARK_TEMPLATE(BM_StepCost, stickslip::METHOD, 8);             \
  BENCHMARK_TEMPLATE(BM_StepCost, stickslip::METHOD, 32);            \
  BENCHMARK_TEMPLATE(BM_StepCost, stickslip::METHOD, 128);           \
  BENCHMARK_TEMPLATE(BM_StepCost, stickslip::METHOD, Eigen::Dynamic) \
      ->Arg(2)->Arg(8)->Arg(32)->Arg(128)
STICKSLIP_STEP_COST(RungeKutta4);
STICKSLIP_STEP_COST(DormandPrince54);
STICKSLIP_STEP_COST(Rosenbrock23);

// 50 impacts of an elastic ball; the stepping between impacts is the same for both locators,
// so the difference of time_per_event is the cost of locating one event.
template <class Method>
void BM_EventLocation(benchmark::State& s) {
  ElasticBall ball;
  StepperOptions<double> opt;
  opt.event_location = s.range(0) == 0 ? stickslip::EventLocation::DenseRootFinding
                                       : stickslip::EventLocation::Bisection;
  opt.fixed_step = 0.05;  // y is quadratic: RK4 is exact with any step; few steps per flight
  opt.event_time_tolerance = 1e-12;
  HybridStepper<ElasticBall, Method> stepper(ball, opt);
  const double t_end = 50 * 2.0 * std::sqrt(2.0 / 9.81);
  stickslip::StepperStats st;
  long runs = 0;
  for (auto _ : s) {
    auto r = stepper.integrate(0, 0.0, Eigen::Vector2d(1.0, 0.0), t_end);
    benchmark::DoNotOptimize(r.x.data());
    st = r.stats;
    ++runs;
  }
  using benchmark::Counter;
  s.SetLabel(s.range(0) == 0 ? "dense_root_finding" : "bisection");
  s.counters["events"] = static_cast<double>(st.events);
  s.counters["rhs_per_event"] =
      static_cast<double>(st.rhs_evaluations) / static_cast<double>(std::max(1L, st.events));
  s.counters["time_per_event"] =
      Counter(static_cast<double>(st.events * runs), Counter::kIsRate | Counter::kInvert);
}
BENCHMARK_TEMPLATE(BM_EventLocation, stickslip::RungeKutta4)->Arg(0)->Arg(1);
BENCHMARK_TEMPLATE(BM_EventLocation, stickslip::DormandPrince54)->Arg(0)->Arg(1);

// Hand-written, non-generic Dormand-Prince 5(4) with the same step control as HybridStepper
// (RMS error norm, safety 0.9, factor in [0.2, 5], no growth after a rejection).
template <int N>
long handwritten_dopri(const SpringChain<N>& sys, Eigen::Matrix<double, N, 1> x, double t_end,
                       double rtol, double atol, double h, long& rhs_evals) {
  using V = Eigen::Matrix<double, N, 1>;
  V k1, k2, k3, k4, k5, k6, k7, xs, x1;
  double t = 0;
  sys.rhs(0, t, x, k1);
  rhs_evals = 1;
  long accepted = 0;
  bool rejected = false;
  while (t < t_end) {
    if (t + h > t_end) h = t_end - t;
    xs = x + h * (1.0 / 5.0) * k1;
    sys.rhs(0, t + h / 5.0, xs, k2);
    xs = x + h * (3.0 / 40.0 * k1 + 9.0 / 40.0 * k2);
    sys.rhs(0, t + 0.3 * h, xs, k3);
    xs = x + h * (44.0 / 45.0 * k1 - 56.0 / 15.0 * k2 + 32.0 / 9.0 * k3);
    sys.rhs(0, t + 0.8 * h, xs, k4);
    xs = x + h * (19372.0 / 6561.0 * k1 - 25360.0 / 2187.0 * k2 + 64448.0 / 6561.0 * k3 -
                  212.0 / 729.0 * k4);
    sys.rhs(0, t + 8.0 / 9.0 * h, xs, k5);
    xs = x + h * (9017.0 / 3168.0 * k1 - 355.0 / 33.0 * k2 + 46732.0 / 5247.0 * k3 +
                  49.0 / 176.0 * k4 - 5103.0 / 18656.0 * k5);
    sys.rhs(0, t + h, xs, k6);
    x1 = x + h * (35.0 / 384.0 * k1 + 500.0 / 1113.0 * k3 + 125.0 / 192.0 * k4 -
                  2187.0 / 6784.0 * k5 + 11.0 / 84.0 * k6);
    sys.rhs(0, t + h, x1, k7);
    rhs_evals += 6;
    const V e = h * (71.0 / 57600.0 * k1 - 71.0 / 16695.0 * k3 + 71.0 / 1920.0 * k4 -
                     17253.0 / 339200.0 * k5 + 22.0 / 525.0 * k6 - 1.0 / 40.0 * k7);
    const double err = std::sqrt(
        (e.array() / (atol + rtol * x.array().abs().max(x1.array().abs()))).square().mean());
    double fac = std::min(5.0, std::max(0.2, 0.9 * std::pow(err, -0.2)));
    if (err > 1.0) {
      h *= std::max(0.2, 0.9 * std::pow(err, -0.2));
      rejected = true;
      continue;
    }
    t += h;
    x = x1;
    k1 = k7;
    ++accepted;
    if (rejected) fac = std::min(fac, 1.0);
    rejected = false;
    h *= fac;
  }
  benchmark::DoNotOptimize(x.data());
  return accepted;
}

template <int N>
void BM_HandWrittenDopri(benchmark::State& s) {
  SpringChain<N> sys;
  const auto x0 = chain_start<N>(N);
  long steps = 0, rhs = 0, runs = 0;
  for (auto _ : s) {
    steps = handwritten_dopri<N>(sys, x0, 100.0, 1e-8, 1e-10, 0.01, rhs);
    ++runs;
  }
  using benchmark::Counter;
  s.counters["steps"] = static_cast<double>(steps);
  s.counters["time_per_step"] =
      Counter(static_cast<double>(steps * runs), Counter::kIsRate | Counter::kInvert);
}

template <int N>
void BM_GenericDopri(benchmark::State& s) {
  SpringChain<N> sys;
  StepperOptions<double> opt;
  opt.rtol = 1e-8;
  opt.atol = 1e-10;
  opt.initial_step = 0.01;
  HybridStepper<SpringChain<N>, stickslip::DormandPrince54> stepper(sys, opt);
  const auto x0 = chain_start<N>(N);
  stickslip::StepperStats st;
  long runs = 0;
  for (auto _ : s) {
    auto r = stepper.integrate(0, 0.0, x0, 100.0);
    benchmark::DoNotOptimize(r.x.data());
    st = r.stats;
    ++runs;
  }
  report(s, st, runs);
}
BENCHMARK_TEMPLATE(BM_HandWrittenDopri, 2);
BENCHMARK_TEMPLATE(BM_GenericDopri, 2);
BENCHMARK_TEMPLATE(BM_HandWrittenDopri, 8);
BENCHMARK_TEMPLATE(BM_GenericDopri, 8);

}  // namespace

BENCHMARK_MAIN();

// ExactLinearStepper against Dormand-Prince 5(4) on a linear scene: a chain of 10 unit masses
// with unit springs, harmonically forced on the first mass, t in [0, 200]. Counters: final error
// against a Dormand-Prince reference at rtol 1e-14 (computed once), steps, RHS evaluations.

#include <stickslip/ode.hpp>
#include <stickslip/ode/exact_linear_stepper.hpp>

#include <benchmark/benchmark.h>

#include <cmath>

#include "ode/ode_bench_systems.hpp"

namespace {

constexpr int kStates = 20;
using Chain = stickslip::bench::SpringChain<kStates>;

/// The chain with F cos(W t) on its first mass, and its linear part (exact).
struct ForcedChain : Chain {
  double F = 0.3, W = 1.3;
  void rhs(const Mode& m, double t, const State& x, State& d) const {
    Chain::rhs(m, t, x, d);
    d[kStates / 2] += F * std::cos(W * t);
  }
  bool linear_part(const Mode&, double, const State&, stickslip::LinearPart<double>& lp) const {
    constexpr int m = kStates / 2;
    lp.A.setZero(kStates, kStates);
    lp.A.topRightCorner(m, m).setIdentity();
    for (int i = 0; i < m; ++i) {
      lp.A(m + i, i) = -2.0;
      if (i > 0) lp.A(m + i, i - 1) = 1.0;
      if (i + 1 < m) lp.A(m + i, i + 1) = 1.0;
    }
    lp.b0.setZero(kStates);
    lp.omega = {W};
    lp.bc.setZero(kStates, 1);
    lp.bs.setZero(kStates, 1);
    lp.bc(m, 0) = F;
    lp.exact = true;
    lp.version = 1;
    return true;
  }
};

constexpr double kEnd = 200.0;

Chain::State initial() {
  Chain::State x0 = Chain::State::Zero();
  x0[0] = 0.5;
  x0[3] = -0.2;
  return x0;
}

const Chain::State& reference() {
  static const Chain::State ref = [] {
    ForcedChain sys;
    stickslip::StepperOptions<double> opt;
    opt.rtol = 1e-14;
    opt.atol = 1e-16;
    stickslip::HybridStepper<ForcedChain, stickslip::DormandPrince54> s(sys, opt);
    return s.integrate(0, 0.0, initial(), kEnd).x;
  }();
  return ref;
}

// Run the stepper in the benchmark loop; counters of the last run.
template <class Stepper>
stickslip::StepperStats run(benchmark::State& state, Stepper& stepper) {
  stickslip::HybridResult<double, Chain::State, int> r;
  for (auto _ : state) {
    r = stepper.integrate(0, 0.0, initial(), kEnd);
    benchmark::DoNotOptimize(r.x.data());
  }
  state.counters["error"] = (r.x - reference()).lpNorm<Eigen::Infinity>();
  state.counters["steps"] = static_cast<double>(r.stats.accepted_steps);
  state.counters["rhs"] = static_cast<double>(r.stats.rhs_evaluations);
  return r.stats;
}

void BM_ExactLinearChain(benchmark::State& state) {
  ForcedChain sys;
  stickslip::ExactLinearStepper<ForcedChain> stepper(sys);
  run(state, stepper);
  state.counters["matvecs"] = static_cast<double>(stepper.work().matvecs);
}
BENCHMARK(BM_ExactLinearChain)->Unit(benchmark::kMillisecond);

void BM_DormandPrinceChain(benchmark::State& state) {
  ForcedChain sys;
  stickslip::StepperOptions<double> opt;
  opt.rtol = std::pow(10.0, -static_cast<double>(state.range(0)));
  opt.atol = opt.rtol * 1e-2;
  stickslip::HybridStepper<ForcedChain, stickslip::DormandPrince54> stepper(sys, opt);
  run(state, stepper);
}
BENCHMARK(BM_DormandPrinceChain)->DenseRange(8, 13, 1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

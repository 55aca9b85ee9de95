// CoulombContact hot-path costs (friction force, guards, decision) and the speed/accuracy trade
// of exact vs regularised laws on the stick-slip oscillator of the energy audit.

#include "contact/single_dof_systems.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>

namespace {

using S = stickslip::ContactState;

template <class Law>
Law make_law();
template <>
stickslip::CoulombLaw<double> make_law() { return {0.5, 0.3}; }
template <>
stickslip::StribeckLaw<double> make_law() { return {0.5, 0.3, 0.05}; }
template <>
stickslip::RegularisedLaw<double> make_law() { return {0.4, 1e-3}; }

template <class Law>
void BM_FrictionForce(benchmark::State& state) {
  const stickslip::CoulombContact<Law> contact(make_law<Law>());
  double v = 0.3, acc = 0;
  for (auto _ : state) {
    acc += contact.friction_force(S::SlipPositive, v, 2.0, 0.1);
    benchmark::DoNotOptimize(acc);
    v = -v;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK_TEMPLATE(BM_FrictionForce, stickslip::CoulombLaw<double>);
BENCHMARK_TEMPLATE(BM_FrictionForce, stickslip::StribeckLaw<double>);
BENCHMARK_TEMPLATE(BM_FrictionForce, stickslip::RegularisedLaw<double>);

void BM_GuardsStick(benchmark::State& state) {
  using C = stickslip::CoulombContact<stickslip::CoulombLaw<double>>;
  const C contact(make_law<stickslip::CoulombLaw<double>>());
  std::array<double, C::max_guards> g{};
  double f = 0.1;
  for (auto _ : state) {
    contact.guards(S::Stick, 0.0, 2.0, f, true, g.data());
    benchmark::DoNotOptimize(g);
    f = -f;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GuardsStick);

void BM_Decide(benchmark::State& state) {
  const stickslip::CoulombContact<stickslip::CoulombLaw<double>> contact(
      make_law<stickslip::CoulombLaw<double>>());
  double f = 0.7;
  for (auto _ : state) {
    benchmark::DoNotOptimize(contact.decide(S::SlipPositive, 1e-12, 2.0, f));
    f = f > 1.0 ? 0.7 : f + 0.6;
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Decide);

// 40 s of the forced stick-slip oscillator (DP54, rtol 1e-8): wall time, steps and events.
template <class Law>
void BM_StickSlipOscillator(benchmark::State& state) {
  contact_test::SingleDofParameters p;
  p.stiffness = 10.0;
  p.force_amplitude = 5.0;
  p.force_frequency = 1.5;
  p.normal_force = 8.0;
  p.normal_amplitude = 3.0;
  p.normal_frequency = 3.0;
  using Sys = contact_test::SingleDofOscillator<Law>;
  Sys sys(p, stickslip::CoulombContact<Law>(make_law<Law>()));
  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-8;
  opt.atol = 1e-11;
  opt.max_step = 0.02;
  stickslip::HybridStepper<Sys, stickslip::DormandPrince54> stepper(sys, opt);
  const Eigen::Vector4d x0(0.1, 0.0, 0.0, 0.0);
  stickslip::StepperStats stats;
  for (auto _ : state) {
    const auto r = stepper.integrate(sys.consistent_mode(0.0, x0), 0.0, x0, 40.0);
    benchmark::DoNotOptimize(r.x);
    stats = r.stats;
  }
  state.counters["steps"] = static_cast<double>(stats.accepted_steps);
  state.counters["rhs"] = static_cast<double>(stats.rhs_evaluations);
  state.counters["events"] = static_cast<double>(stats.events);
}
BENCHMARK_TEMPLATE(BM_StickSlipOscillator, stickslip::CoulombLaw<double>)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_StickSlipOscillator, stickslip::StribeckLaw<double>)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_StickSlipOscillator, stickslip::RegularisedLaw<double>)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// Micro-benchmarks of the composition layer (docs/measurements/micro_benchmarks.md):
//  * one right-hand side of FrictionDampedSystem vs the bare modal right-hand side
//    q'' = -omega^2 q + sum_i (N_i psi_w(X_i) - f_i psi_u(X_i)) with the shapes evaluated at the
//    D moving contact points, for n = 6, 24, 96 modes and D = 2, 8, 32 dampers (all slipping /
//    all stuck); the ratio composed / bare is formed from the same run's JSON
//    (benchmarks/model/micro_table.py);
//  * one integrator step (RK4, DOPRI 5(4), Rosenbrock 2(3)) of the default blade scene;
//  * one located event (root finding vs bisection) and the same window without an event;
//  * 20 s of the default scene at N0 = 1, 12, 26 N (Iterations(1)).
#include "blade_damper/blade_run.hpp"
#include "blade_damper/blade_scene.hpp"

#include <benchmark/benchmark.h>
#include <stickslip/stickslip.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

namespace {

using namespace stickslip;
using Index = Eigen::Index;
using System = FrictionDampedSystem<double>;

// ---- right-hand side: composed vs bare ----------------------------------------------------------

/// An L-shaped steel frame (column and beam of 0.2 m, 40 elements each: 240 free DOFs) clamped at
/// its foot; the dampers are spread evenly along the beam.
struct RhsFrame {
  FrameModel<double> frame;
  Index member = 0;
  ModalBasis<double> basis;
  std::vector<double> X;
};

RhsFrame make_frame(Index n, Index D) {
  RhsFrame s;
  const SectionProperties<double> section{2.06e11, 7800.0, 6e-5, 2e-11};
  const Index foot = s.frame.add_node(0.0, 0.0), corner = s.frame.add_node(0.0, 0.2), end = s.frame.add_node(0.2, 0.2);
  s.frame.add_member(foot, corner, section, 40);
  s.member = s.frame.add_member(corner, end, section, 40);
  s.frame.clamp(foot);
  ModalOptions<double> mo;
  mo.num_modes = n;
  s.basis = compute_modes(s.frame.assemble(), mo);
  for (Index i = 0; i < D; ++i) s.X.push_back(0.2 * (static_cast<double>(i) + 0.5) / static_cast<double>(D));
  return s;
}

/// Random modal state (fixed seed 7) with sliding velocities of alternating sign.
Eigen::VectorXd random_modal_state(Index n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd qqd(2 * n);
  for (Index k = 0; k < n; ++k) {
    qqd[k] = 1e-5 * u(rng);
    qqd[n + k] = 1e-3 * u(rng);
  }
  return qqd;
}

/// The composed right-hand side of one (n, D, stuck) case; `Sys` is FrictionDampedSystem<double>
/// or its fixed-Modes form. call() evaluates it once.
template <class Sys>
class ComposedRhs {
 public:
  ComposedRhs(Index n, Index D, bool stuck) : f_(make_frame(n, D)), sys_(make_system(f_, D)) {
    x_ = sys_.initial_state();
    x_.head(2 * n) = random_modal_state(n);
    mode_ = typename Sys::Mode(D);
    for (Index i = 0; i < D; ++i) {
      const double sign = i % 2 == 0 ? 1.0 : -1.0;
      const double follow = x_.segment(n, n).dot(sys_.point_shape(f_.member, f_.X[static_cast<std::size_t>(i)], LoadDirection::Axial));
      x_[sys_.xd_offset() + i] = follow + (stuck ? 0.0 : 0.01 * sign);
      x_[sys_.x_offset() + i] = 1e-5 * sign;
      mode_[i] = stuck ? ContactState::Stick : (sign > 0 ? ContactState::SlipPositive : ContactState::SlipNegative);
    }
    // Successive calls alternate between two states, as integrator stages do: q, q', x, x'
    // differ, and so do the contact coordinates of slipping dampers (stuck dampers' X is constant
    // in a run). Every call therefore redoes what a stage redoes: the evaluation cache never hits,
    // and the acceleration solve keeps its factorisation, and a damper its shapes, only where a
    // run would (stuck dampers).
    xb_ = x_;
    xb_.head(2 * n + 2 * D) *= 1.0 + 1e-3;
    if (!stuck) xb_.segment(sys_.contact_offset(), D).array() += 1e-7;
    dx_.resize(x_.size());
  }
  void call() {
    t_ += 1e-9;
    sys_.rhs(mode_, t_, (++k_ & 1) ? xb_ : x_, dx_);
    benchmark::DoNotOptimize(dx_.data());
    benchmark::ClobberMemory();
  }

 private:
  static Sys make_system(const RhsFrame& f, Index D) {
    std::vector<PointDamper<double>> dampers;
    for (Index i = 0; i < D; ++i)
      dampers.emplace_back(f.member, f.X[static_cast<std::size_t>(i)], 0.02, 1e4, 10.0, CoulombLaw<double>(0.35, 0.3),
                           0.5);
    return Sys(f.frame, f.basis, dampers, {}, ModelOptions<double>{});
  }
  RhsFrame f_;
  Sys sys_;
  typename Sys::State x_, xb_, dx_;
  typename Sys::Mode mode_;
  double t_ = 0;
  long k_ = 0;
};

/// The bare modal right-hand side with the same moving-shape evaluations and no contact algebra:
/// q'' = -omega^2 q + sum_i (N_i psi_w(X_i) - f_i psi_u(X_i)), N and f given. Modes = 6 gives the
/// fixed-size form (MemberShapes<double, 6>, fixed-size vectors).
template <int Modes>
class BareRhs {
  using Vec = Eigen::Matrix<double, Modes, 1>;

 public:
  BareRhs(Index n, Index D)
      : n_(n), D_(D), f_(make_frame(n, D)), shapes_(f_.frame, f_.member, f_.basis, EndPolicy::Extrapolate),
        values_(static_cast<std::size_t>(D)), cursors_(static_cast<std::size_t>(D)),
        omega2_(f_.basis.omega().array().square().matrix()), x_(2 * n + D), dx_(2 * n),
        N_(Eigen::VectorXd::Constant(D, 10.0)), fr_(Eigen::VectorXd::Constant(D, 3.0)) {
    for (auto& v : values_) v.resize(n);
    x_.head(2 * n) = random_modal_state(n);
    for (Index i = 0; i < D; ++i) x_[2 * n + i] = f_.X[static_cast<std::size_t>(i)];
  }
  void call() {
    const Index n = n_;
    dx_.head(n) = x_.segment(n, n);
    auto acc = dx_.template segment<Modes>(n, n);
    acc.noalias() = -omega2_.cwiseProduct(x_.template segment<Modes>(0, n));
    for (Index i = 0; i < D_; ++i) {
      auto& v = values_[static_cast<std::size_t>(i)];
      shapes_.evaluate(x_[2 * n + i], v, cursors_[static_cast<std::size_t>(i)]);
      acc.noalias() += N_[i] * v.psi_w - fr_[i] * v.psi_u;
    }
    benchmark::DoNotOptimize(dx_.data());
    benchmark::ClobberMemory();
  }

 private:
  Index n_, D_;
  RhsFrame f_;
  MemberShapes<double, Modes> shapes_;
  std::vector<ShapeValues<double, Modes>> values_;
  std::vector<ElementCursor> cursors_;
  Vec omega2_;
  Eigen::VectorXd x_, dx_, N_, fr_;
};

using FixedSystem6 = FrictionDampedSystem<double, FrictionLawVariant<double>, 6>;

void BM_RhsComposed(benchmark::State& st) {
  ComposedRhs<System> rhs(st.range(0), st.range(1), st.range(2) != 0);
  for (auto _ : st) rhs.call();
  st.SetLabel(st.range(2) != 0 ? "stuck" : "slipping");
}

/// The composed right-hand side with the number of modes fixed at compile time (Modes = 6).
void BM_RhsComposedFixed6(benchmark::State& st) {
  ComposedRhs<FixedSystem6> rhs(6, st.range(0), st.range(1) != 0);
  for (auto _ : st) rhs.call();
  st.SetLabel(st.range(1) != 0 ? "stuck" : "slipping");
}

void BM_RhsBare(benchmark::State& st) {
  BareRhs<Eigen::Dynamic> rhs(st.range(0), st.range(1));
  for (auto _ : st) rhs.call();
}

void BM_RhsBareFixed6(benchmark::State& st) {
  BareRhs<6> rhs(6, st.range(0));
  for (auto _ : st) rhs.call();
}

/// The ratio composed / bare as a paired measurement: each benchmark iteration times a block of
/// kBlock bare calls and then a block of kBlock composed calls (steady clock), and the counters
/// report the medians over the iterations of the two per-call times and of the per-iteration
/// ratio. Both halves of a pair run within 7 us (n = 6, D = 2) to 2 ms (n = 96, D = 32) of each
/// other, so a slow phase of a shared machine (which moved separate benchmarks' medians by 10 % to
/// 2x on the VM of docs/performance.md) affects both; the median discards pairs hit by a preemption.
template <class Composed, class Bare>
void rhs_paired(benchmark::State& st, Composed& composed, Bare& bare) {
  constexpr int kBlock = 128;
  using Clock = std::chrono::steady_clock;
  std::vector<double> bare_ns, composed_ns, ratio;
  for (int k = 0; k < kBlock; ++k) {  // warm both (caches, the solve's first factorisation)
    bare.call();
    composed.call();
  }
  for (auto _ : st) {
    const auto t0 = Clock::now();
    for (int k = 0; k < kBlock; ++k) bare.call();
    const auto t1 = Clock::now();
    for (int k = 0; k < kBlock; ++k) composed.call();
    const auto t2 = Clock::now();
    const double b = std::chrono::duration<double, std::nano>(t1 - t0).count() / kBlock;
    const double c = std::chrono::duration<double, std::nano>(t2 - t1).count() / kBlock;
    bare_ns.push_back(b);
    composed_ns.push_back(c);
    ratio.push_back(c / b);
  }
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  if (ratio.empty()) return;
  st.counters["bare_ns"] = median(bare_ns);
  st.counters["composed_ns"] = median(composed_ns);
  st.counters["ratio"] = median(ratio);
  st.counters["pairs"] = static_cast<double>(ratio.size());
}

void BM_RhsPaired(benchmark::State& st) {
  const Index n = st.range(0), D = st.range(1);
  const bool stuck = st.range(2) != 0;
  ComposedRhs<System> composed(n, D, stuck);
  BareRhs<Eigen::Dynamic> bare(n, D);
  rhs_paired(st, composed, bare);
  st.SetLabel(stuck ? "stuck" : "slipping");
}

void BM_RhsPairedFixed6(benchmark::State& st) {
  const bool stuck = st.range(1) != 0;
  ComposedRhs<FixedSystem6> composed(6, st.range(0), stuck);
  BareRhs<6> bare(6, st.range(0));
  rhs_paired(st, composed, bare);
  st.SetLabel(stuck ? "stuck" : "slipping");
}

BENCHMARK(BM_RhsBare)->ArgsProduct({{6, 24, 96}, {2, 8, 32}});
BENCHMARK(BM_RhsBareFixed6)->Arg(2)->Arg(8)->Arg(32);
BENCHMARK(BM_RhsComposed)->ArgsProduct({{6, 24, 96}, {2, 8, 32}, {0, 1}});
BENCHMARK(BM_RhsComposedFixed6)->ArgsProduct({{2, 8, 32}, {0, 1}});
// (a fixed number of pairs: those of the largest case, 128 x (8 + 13) us each, take ~1 s)
BENCHMARK(BM_RhsPaired)->ArgsProduct({{6, 24, 96}, {2, 8, 32}, {0, 1}})->Iterations(401);
BENCHMARK(BM_RhsPairedFixed6)->ArgsProduct({{2, 8, 32}, {0, 1}})->Iterations(401);

// ---- the default blade scene: one step, one located event ---------------------------------------

/// The default scene at N0 = 2.6 N (stick-slip with this model), a state inside the run, and a
/// short window around one isolated contact switch.
struct EventSetup {
  blade::BladeScene scene;
  System::State x_mid;       ///< state at t_mid (for the step benchmarks)
  System::Mode mode_mid;
  double t_mid = 0.1;
  double t_event = 0;        ///< an isolated switch
  double t_start = 0, t_control = 0;  ///< window starts: [t, t + 1e-4] with / without the switch
  System::State x_start, x_control;
  System::Mode mode_start, mode_control;
};

const EventSetup& setup() {
  static EventSetup s = [] {
    EventSetup e;
    blade::BladeParameters p;
    p.preload = 2.6;
    e.scene = blade::make_blade_scene(p);
    System& sys = *e.scene.system;
    RunOptions<double> run;
    run.stepper.rtol = 1e-10;
    run.stepper.atol = 1e-14;
    NullObserver none;
    auto run_to = [&](double t_end, System::State& x, System::Mode& mode) {
      sys.clear_events();
      System::State x0 = sys.initial_state();
      System::Mode m0 = sys.requested_mode();
      sys.make_consistent(m0, 0.0, x0);
      const auto r = simulate(sys, m0, 0.0, x0, t_end, run, none);
      x = r.x;
      mode = r.mode;
    };
    run_to(0.3, e.x_mid, e.mode_mid);
    std::vector<double> times;
    for (const auto& ev : sys.events()) times.push_back(ev.t);
    for (double te : times) {
      if (te < e.t_mid) continue;
      bool isolated = true;
      for (double o : times)
        if (std::abs(o - te) > 1e-9 && o > te - 4e-4 && o < te + 1e-4) isolated = false;
      if (isolated) {
        e.t_event = te;
        break;
      }
    }
    e.t_start = e.t_event - 5e-5;
    e.t_control = e.t_event - 2.5e-4;
    run_to(e.t_mid, e.x_mid, e.mode_mid);
    run_to(e.t_start, e.x_start, e.mode_start);
    run_to(e.t_control, e.x_control, e.mode_control);
    return e;
  }();
  return s;
}

template <class Method>
void BM_Step(benchmark::State& st) {
  const EventSetup& e = setup();
  System& sys = *e.scene.system;
  const double h = static_cast<double>(st.range(0)) * 1e-6;
  typename Method::template Core<System> core;
  core.initialize(e.x_mid);
  System::State f0(e.x_mid.size()), x1(e.x_mid.size()), f1(e.x_mid.size());
  sys.rhs(e.mode_mid, e.t_mid, e.x_mid, f0);
  StepperStats stats;
  for (auto _ : st) {
    core.new_point();  // a new step start: Rosenbrock23 re-forms its Jacobian, as in a run
    core.step(sys, e.mode_mid, e.t_mid, e.x_mid, f0, h, x1, f1, 1e-8, 1e-12, stats);
    benchmark::DoNotOptimize(x1.data());
  }
  st.counters["rhs_per_step"] = benchmark::Counter(static_cast<double>(stats.rhs_evaluations),
                                                   benchmark::Counter::kAvgIterations);
}
BENCHMARK_TEMPLATE(BM_Step, RungeKutta4)->Arg(100);
BENCHMARK_TEMPLATE(BM_Step, DormandPrince54)->Arg(10);
BENCHMARK_TEMPLATE(BM_Step, Rosenbrock23)->Arg(100);

/// Integrates the 1e-4 s window [t_start, t_start + 1e-4] that contains one contact switch
/// (range(1) = 1) or the control window without one (range(1) = 0); range(0) = 1: bisection
/// (HybridStepper only; ExactLinearStepper locates on its exact solution).
template <class Stepper>
void BM_EventWindow(benchmark::State& st) {
  const EventSetup& e = setup();
  if (e.t_event <= 0) {
    st.SkipWithError("no isolated contact switch found after t = 0.1 s");
    return;
  }
  System& sys = *e.scene.system;
  StepperOptions<double> opt;
  opt.fixed_step = 1e-4;
  opt.rtol = 1e-8;
  opt.atol = 1e-12;
  opt.event_location = st.range(0) != 0 ? EventLocation::Bisection : EventLocation::DenseRootFinding;
  const bool with_event = st.range(1) != 0;
  const double t0 = with_event ? e.t_start : e.t_control;
  const System::State& x0 = with_event ? e.x_start : e.x_control;
  const System::Mode& m0 = with_event ? e.mode_start : e.mode_control;
  Stepper stepper(sys, opt);
  StepperStats total;
  for (auto _ : st) {
    const auto r = stepper.integrate(m0, t0, x0, t0 + 1e-4);
    total.rhs_evaluations += r.stats.rhs_evaluations;
    total.guard_evaluations += r.stats.guard_evaluations;
    total.events += r.stats.events;
    total.accepted_steps += r.stats.accepted_steps;
  }
  using C = benchmark::Counter;
  st.counters["rhs"] = C(static_cast<double>(total.rhs_evaluations), C::kAvgIterations);
  st.counters["guards"] = C(static_cast<double>(total.guard_evaluations), C::kAvgIterations);
  st.counters["events"] = C(static_cast<double>(total.events), C::kAvgIterations);
  st.counters["steps"] = C(static_cast<double>(total.accepted_steps), C::kAvgIterations);
  st.SetLabel(std::string(with_event ? "window with 1 switch, " : "control window, ") + to_string(opt.event_location));
}
using Rk4Stepper = HybridStepper<System, RungeKutta4>;
using DopriStepper = HybridStepper<System, DormandPrince54>;
using ExponentialStepper = ExactLinearStepper<System>;
BENCHMARK_TEMPLATE(BM_EventWindow, Rk4Stepper)->ArgsProduct({{1, 0}, {1, 0}});
BENCHMARK_TEMPLATE(BM_EventWindow, DopriStepper)->ArgsProduct({{0, 1}, {1, 0}});
BENCHMARK_TEMPLATE(BM_EventWindow, ExponentialStepper)->ArgsProduct({{0}, {1, 0}});

// ---- 20 s of the default scene ------------------------------------------------------------------

/// The example's default run (DOPRI 5(4), rtol 1e-8, atol 1e-12, root finding, samples every
/// 1e-4 s with full records over the last second) at N0 = range(0) N, once; range(1) = 1: the
/// exponential method (ExactLinearStepper) instead of DOPRI.
void BM_DefaultScene20s(benchmark::State& st) {
  blade::BladeParameters p;
  p.preload = static_cast<double>(st.range(0));
  blade::BladeScene scene = blade::make_blade_scene(p);
  blade::RunSettings settings;
  settings.run.stepper.rtol = 1e-8;
  settings.run.stepper.atol = 1e-12;
  if (st.range(1) != 0) settings.run.integrator = Integrator::Exponential;
  blade::RunRecord rec;
  for (auto _ : st) rec = blade::run_scene(scene, settings);
  st.counters["rhs"] = static_cast<double>(rec.stats.rhs_evaluations);
  st.counters["events"] = static_cast<double>(rec.stats.events);
  st.counters["steps"] = static_cast<double>(rec.stats.accepted_steps);
  st.counters["t_end"] = rec.t_end;
  st.SetLabel(std::string(to_string(rec.status)) + ", " + rec.overall_regime + ", " +
             to_string(settings.run.integrator));
}
BENCHMARK(BM_DefaultScene20s)->ArgsProduct({{1, 12, 26}, {0, 1}})->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();

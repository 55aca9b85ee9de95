// ContactSystem: the composed right-hand side of the grounded-slider cantilever (20 elements,
// 6 modes, a Coulomb slider at mid-span: examples/grounded_slider) stuck and slipping, and of a
// wedge damper between two platform cantilevers (a rigid body, two unilateral faces) stuck and
// slipping; the cost per point of the slider's frequency-response curve (shooting and
// continuation from 0.8 omega_1) with Dormand-Prince and with the exact method; the paper's blade
// scene (examples/blade_damper, two point dampers) through FrictionDampedSystem and through
// ContactSystem (each damper a rigid body on a moving contact, point_damper_body), paired.
//
//   contact_system_benchmark [--benchmark_filter=...]
// BM_FrcPerPoint reports s_per_point (CPU of the thread) and the points traced.

#include "blade_damper/blade_scene.hpp"

#include <benchmark/benchmark.h>
#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <random>
#include <vector>

namespace {

using namespace stickslip;
using Slider = ContactSystem<double>;
using Wedge = ContactSystem<double, BodyContact<double>>;
constexpr double kPi = 3.14159265358979323846;

/// The grounded_slider example's scene at excitation frequency W (W <= 0: omega_1).
struct SliderScene {
  FrameModel<double> frame;
  MemberId beam = 0;
  ModalBasis<double> basis;
  double length = 0.2;
  SliderScene() {
    const NodeId root = frame.add_node(0, 0), tip = frame.add_node(0, length);
    beam = frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, 20);
    frame.clamp(root);
    ModalOptions<double> mo;
    mo.num_modes = 6;
    basis = compute_modes(frame.assemble(), mo).with_modal_damping(Eigen::VectorXd::Constant(6, 0.01));
  }
  Slider system(double W, bool audit) const {
    std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
        {beam, length / 2}, PlaneDirection<double>::global_x(), CoulombLaw<double>(0.35, 0.3), 10.0)};
    std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(beam, length, LoadDirection::GlobalX, 2.0, W)};
    ContactSystemOptions<double> o;
    o.energy_audit = audit;
    return Slider(frame, basis, contacts, loads, o);
  }
};

/// A random state of small amplitude (the model's scale: modal coordinates ~1e-4).
template <class System>
typename System::State random_state(const System& sys) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  typename System::State x = sys.initial_state();
  for (Eigen::Index k = 0; k < 2 * sys.num_coordinates(); ++k) x[k] = 1e-5 * u(rng);
  return x;
}

template <class System>
void rhs_loop(benchmark::State& st, System& sys, const typename System::Mode& mode) {
  typename System::State x = random_state(sys), dx;
  sys.rhs(mode, 0.0, x, dx);
  double t = 0;
  for (auto _ : st) {
    sys.rhs(mode, t, x, dx);
    benchmark::DoNotOptimize(dx.data());
    t += 1e-7;
  }
}

// Arg: 0 stuck, 1 slipping.
void BM_SliderRhs(benchmark::State& st) {
  static const SliderScene scene;
  Slider sys = scene.system(scene.basis.omega()(0), true);
  auto mode = sys.requested_mode();
  mode[0] = st.range(0) ? ContactState::SlipPositive : ContactState::Stick;
  rhs_loop(st, sys, mode);
}
BENCHMARK(BM_SliderRhs)->Arg(0)->Arg(1);

/// Two horizontal platform cantilevers (0.125 m, 4 elements each, 8 modes, 1 % damping) and a
/// wedge between their tips: faces at 30 and 45 degrees, one contact point each, 100 N radial
/// load (the wedge of tests/model/body_contact_test.cpp).
struct WedgeScene {
  FrameModel<double> frame;
  MemberId left = 0, right = 0;
  ModalBasis<double> basis;
  WedgeScene() {
    const SectionProperties<double> platform{2.06e11, 7800, 1e-4, 1e-8};
    const NodeId root_l = frame.add_node(-0.25, 0.0), root_r = frame.add_node(0.25, 0.0);
    const NodeId tip_l = frame.add_node(-0.125, 0.0), tip_r = frame.add_node(0.125, 0.0);
    left = frame.add_member(root_l, tip_l, platform, 4);
    right = frame.add_member(root_r, tip_r, platform, 4);
    frame.clamp(root_l);
    frame.clamp(root_r);
    ModalOptions<double> mo;
    mo.num_modes = 8;
    basis = compute_modes(frame.assemble(), mo).with_modal_damping(Eigen::VectorXd::Constant(8, 0.01));
  }
  Wedge system() const {
    const Eigen::Vector2d rl(-0.01, 0.004), rr(0.01, 0.004);
    WedgeFace<double> l{{StructurePoint<double>{left, 0.125}}, rl, kPi / 6, 0.0};
    WedgeFace<double> r{{StructurePoint<double>{right, 0.125}}, rr, kPi / 4, 0.0};
    const auto wedge = wedge_damper<double>(0, 0.05, 2e-5, 100.0, l, r, CoulombLaw<double>(0.25, 0.2));
    std::vector<PointLoad<double>> loads{
        PointLoad<double>::harmonic(left, 0.125, LoadDirection::GlobalY, 30.0, 0.6 * basis.omega()(0))};
    return Wedge(frame, basis, {wedge.body}, wedge.contacts, loads);
  }
};

// Arg: 0 both faces stuck, 1 both slipping (closed: their normal forces are unknowns too).
void BM_WedgeRhs(benchmark::State& st) {
  static const WedgeScene scene;
  Wedge sys = scene.system();
  auto mode = sys.requested_mode();
  for (Eigen::Index i = 0; i < sys.num_contacts(); ++i)
    mode[i] = st.range(0) ? ContactState::SlipPositive : ContactState::Stick;
  rhs_loop(st, sys, mode);
}
BENCHMARK(BM_WedgeRhs)->Arg(0)->Arg(1);

// The slider's frequency-response curve from 0.8 omega_1 upwards, range(1) points, one part,
// by the grounded_slider example's options; range(0): 0 Dormand-Prince, 1 exponential.
void BM_FrcPerPoint(benchmark::State& st) {
  static const SliderScene scene;
  const bool exact = st.range(0) != 0;
  const double w1 = scene.basis.omega()(0);
  for (auto _ : st) {
    const std::clock_t c0 = std::clock();
    std::vector<Slider> systems{scene.system(0.8 * w1, false)};
    std::vector<Slider*> ptrs{&systems[0]};
    ShootingOptions<double> so;
    so.integrator = exact ? OrbitIntegrator::Exponential : OrbitIntegrator::DormandPrince54;
    ContinuationOptions<double> co;
    co.parameter_min = 0.8;
    co.parameter_max = 2.2;
    co.initial_step = 0.005;
    co.max_step = 0.02;
    co.max_points = static_cast<int>(st.range(1));
    co.section_margin = 0.02;
    co.max_corrector_distance = 2;
    co.chord_iterations = 4;
    auto set_parameter = [w1](Slider& sys, double p) { sys = scene.system(p * w1, false); };
    auto period = [w1](double p) { return 2 * kPi / (p * w1); };
    SplitContinuation<Slider> split(ptrs, set_parameter, period, so, co);
    split.start_mode([](Slider& sys, double t0, const Slider::State& x, const Slider::Mode& previous) {
      Slider::State y = x;
      auto mode = previous;
      sys.make_consistent(mode, t0, y);
      sys.clear_events();
      return mode;
    });
    auto guess = [&](Slider& sys, double p) {
      auto x = sys.initial_state();
      auto mode = sys.requested_mode();
      sys.make_consistent(mode, 0.0, x);
      RunOptions<double> run;
      run.integrator = exact ? Integrator::Exponential : Integrator::DormandPrince54;
      run.stepper.rtol = 1e-9;
      run.stepper.atol = 1e-12;
      const double T = period(p);
      auto r = simulate(sys, mode, 0.0, x, 40 * T, run);
      return SplitContinuation<Slider>::Guess{r.mode, 40 * T, r.x};
    };
    const auto result = split.run(guess);
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    const double points = static_cast<double>(result.branch.points.size());
    st.counters["points"] = points;
    st.counters["s_per_point"] = points > 0 ? cpu / points : 0.0;
    st.counters["cpu_s"] = cpu;
  }
}
BENCHMARK(BM_FrcPerPoint)->Args({0, 10})->Args({1, 10})->Iterations(1)->Unit(benchmark::kSecond);

/// The blade scene's composed right-hand side through both assemblies, paired: each iteration
/// times a block of kBlock FrictionDampedSystem calls, then a block of kBlock ContactSystem calls
/// (steady clock), and the counters report the medians of the two per-call times and of the
/// per-pair ratio (contact / fds), so a slow phase of a shared machine hits both halves of a pair.
/// Both start from the consistent state at rest plus the same small random modal state; calls
/// alternate between two states (as integrator stages do), so no evaluation cache hits. Arg: 0
/// both dampers stuck, 1 both slipping (FrictionDampedSystem's sign; the body's tangent is
/// mirrored, so its mode is SlipNegative).
void BM_BladeRhsPaired(benchmark::State& st) {
  using Fds = blade::BladeScene::System;
  using Bodies = ContactSystem<double, BodyContact<double>>;
  static const blade::BladeScene scene = blade::make_blade_scene(blade::BladeParameters{});
  const bool slipping = st.range(0) != 0;
  Fds& fds = *scene.system;
  std::vector<RigidBody<double>> bodies;
  std::vector<BodyContact<double>> contacts;
  for (std::size_t i = 0; i < fds.dampers().size(); ++i) {
    const auto part = point_damper_body(scene.frame, Eigen::Index(i), fds.dampers()[i], scene.parameters.model);
    bodies.push_back(part.body);
    contacts.push_back(part.contact);
  }
  Bodies body_sys(scene.frame, scene.basis, bodies, contacts, fds.loads());
  const Eigen::Index n = scene.basis.size();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd q(2 * n);
  for (Eigen::Index k = 0; k < 2 * n; ++k) q[k] = 1e-5 * u(rng);

  Fds::State xf = fds.initial_state(), dxf(xf.size());
  Fds::Mode mf = fds.requested_mode();
  Bodies::State xc = body_sys.initial_state(), dxc(xc.size());
  Bodies::Mode mc = body_sys.requested_mode();
  for (Eigen::Index i = 0; i < fds.num_dampers(); ++i) {
    mf[i] = slipping ? ContactState::SlipPositive : ContactState::Stick;
    mc[i] = slipping ? ContactState::SlipNegative : ContactState::Stick;
  }
  xf.head(2 * n) = q;  // q, q' lead FrictionDampedSystem's state
  xc.head(n) = q.head(n);
  xc.segment(body_sys.num_coordinates(), n) = q.tail(n);
  Fds::State xf2 = xf;
  Bodies::State xc2 = xc;
  xf2.head(n) *= 1.0 + 1e-3;
  xc2.head(n) *= 1.0 + 1e-3;
  if (slipping && fds.contact_offset() >= 0) {
    xf2.segment(fds.contact_offset(), fds.num_dampers()).array() += 1e-7;
    xc2.segment(body_sys.contact_offset(), body_sys.num_moving()).array() += 1e-7;
  }
  constexpr int kBlock = 256;
  using Clock = std::chrono::steady_clock;
  double t = 0;
  long k = 0;
  auto fds_call = [&] {
    t += 1e-9;
    fds.rhs(mf, t, (++k & 1) ? xf2 : xf, dxf);
    benchmark::DoNotOptimize(dxf.data());
  };
  auto body_call = [&] {
    t += 1e-9;
    body_sys.rhs(mc, t, (++k & 1) ? xc2 : xc, dxc);
    benchmark::DoNotOptimize(dxc.data());
  };
  for (int b = 0; b < kBlock; ++b) {
    fds_call();
    body_call();
  }
  std::vector<double> fds_ns, body_ns, ratio;
  for (auto _ : st) {
    const auto t0 = Clock::now();
    for (int b = 0; b < kBlock; ++b) fds_call();
    const auto t1 = Clock::now();
    for (int b = 0; b < kBlock; ++b) body_call();
    const auto t2 = Clock::now();
    fds_ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / kBlock);
    body_ns.push_back(std::chrono::duration<double, std::nano>(t2 - t1).count() / kBlock);
    ratio.push_back(body_ns.back() / fds_ns.back());
  }
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  if (ratio.empty()) return;
  st.counters["fds_ns"] = median(fds_ns);
  st.counters["contact_ns"] = median(body_ns);
  st.counters["ratio"] = median(ratio);
  st.SetLabel(slipping ? "slipping" : "stuck");
}
BENCHMARK(BM_BladeRhsPaired)->Arg(0)->Arg(1)->Iterations(201);

}  // namespace

BENCHMARK_MAIN();

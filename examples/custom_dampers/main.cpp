// Your own damper configuration: an L-shaped frame (a clamped blade with a one-sided platform)
// carrying three dampers with different masses and friction laws, driven at the blade tip.
// Prints the run's status, switches per damper, tip amplitude and energy-audit residual; exits
// non-zero when the run fails or the audit does not close.
#include <stickslip/stickslip.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace stickslip;
using System = FrictionDampedSystem<double>;

// Tracks the largest |tip displacement| over the second half of the run.
struct TipAmplitude : NullObserver {
  Eigen::VectorXd tip_shape;
  double from = 0, amplitude = 0;
  template <class Scalar, class State, class Mode>
  bool on_sample(Scalar t, const State& x, const Mode&) {
    if (t >= from) amplitude = std::max(amplitude, std::abs(tip_shape.dot(x.head(tip_shape.size()))));
    return true;
  }
};

int main() {
  // 1. The frame: blade (0,0) -> (0,0.2) clamped at the root, platform arm to (0.06, 0.2).
  FrameModel<double> frame;
  const SectionProperties<double> steel{2.06e11, 7800.0, 6e-5, 2e-11};
  const auto root = frame.add_node(0.0, 0.0), tip = frame.add_node(0.0, 0.2);
  const auto arm_end = frame.add_node(0.06, 0.2);
  const auto blade = frame.add_member(root, tip, steel, 16);
  const auto arm = frame.add_member(tip, arm_end, steel, 6);
  frame.clamp(root);

  // 2. Its lowest modes, with 0.5 % modal damping.
  ModalOptions<double> modal;
  modal.num_modes = 6;
  const auto basis = compute_modes(frame.assemble(), modal)
                         .with_modal_damping(Eigen::VectorXd::Constant(6, 0.005));

  // 3. Three dampers under the arm: Coulomb, Stribeck, and a regularised (tanh) law with a
  //    constant normal load.
  std::vector<PointDamper<double>> dampers;
  dampers.emplace_back(arm, 0.01, 0.02, 1e4, 4.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  dampers.emplace_back(arm, 0.03, 0.03, 2e4, 6.0, StribeckLaw<double>(0.4, 0.25, 1e-3), 0.5);
  dampers.emplace_back(arm, 0.045, 0.01, 5e3, 3.0, RegularisedLaw<double>(0.3, 1e-4), 1.0);
  dampers.back().normal_load = NormalLoad::Constant;

  // 4. A harmonic load at the blade tip, 2 sin(150 t) N along global X (below the dampers' total
  //    friction capacity of ~3.6 N, so they stick and slip).
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(blade, 0.2, LoadDirection::GlobalX, 2.0, 150.0)};

  // 5. The hybrid system, a consistent start from rest, and a 1 s run.
  System system(frame, basis, dampers, loads);
  auto x0 = system.initial_state();
  auto mode = system.requested_mode();
  if (!system.make_consistent(mode, 0.0, x0)) {
    std::printf("no consistent initial contact state\n");
    return 1;
  }
  const double E0 = system.mechanical_energy(mode, 0.0, x0), t_end = 1.0;
  RunOptions<double> run;
  run.stepper.rtol = 1e-8;
  run.stepper.atol = 1e-14;
  run.stepper.output_interval = 1e-4;
  TipAmplitude observer;
  observer.tip_shape = system.point_shape(blade, 0.2, LoadDirection::GlobalX);
  observer.from = 0.5 * t_end;
  const auto result = simulate(system, mode, 0.0, x0, t_end, run, observer);

  // 6. Summary.
  std::printf("status: %s at t = %.4f s %s\n", to_string(result.status), result.t, result.message.c_str());
  std::vector<long> switches(dampers.size(), 0);
  for (const auto& event : system.events()) ++switches[static_cast<std::size_t>(event.damper)];
  for (std::size_t i = 0; i < dampers.size(); ++i)
    std::printf("damper %zu: %ld switches, final state %s\n", i, switches[i], to_string(result.mode[static_cast<Eigen::Index>(i)]));
  const auto audit = system.energy_balance(result.mode, result.t, result.x, E0);
  const double scale = std::max({std::abs(audit.external_work), audit.friction_dissipation, audit.viscous_dissipation});
  std::printf("tip amplitude (last %.1f s): %.4e m\n", t_end - observer.from, observer.amplitude);
  std::printf("energy: W_ext %.4e J, D_fric %.4e J, D_visc %.4e J, residual %.3e J (%.1e relative)\n",
              audit.external_work, audit.friction_dissipation, audit.viscous_dissipation, audit.residual,
              std::abs(audit.residual) / scale);
  const bool ok = result.ok() && std::abs(audit.residual) <= 1e-5 * scale;
  return ok ? 0 : 1;
}

// A user program in the compiled mode (links stickslip::compiled): builds a cantilever, keeps its
// first mode, and runs simulate() - whose runs on FrictionDampedSystem<double> come from the
// library, not from this translation unit - on the undamped free vibration q(t) = q0 cos(w t),
// checked against that closed form with every integrator.
#include <stickslip/stickslip.hpp>

#include <cmath>
#include <cstdio>

int main() {
#ifndef STICKSLIP_COMPILED
  return 1;  // linking stickslip::compiled must define it
#else
  using namespace stickslip;
  FrameModel<double> frame;
  const auto root = frame.add_node(0.0, 0.0);
  const auto tip = frame.add_node(0.0, 0.2);
  frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, 10);
  frame.clamp(root);
  ModalOptions<double> modal;
  modal.num_modes = 1;
  FrictionDampedSystem<double> system(frame, compute_modes(frame.assemble(), modal), {});
  const double w = std::sqrt(system.omega_squared()[0]), q0 = 1e-3, t_end = 0.05;
  auto x0 = system.initial_state();
  x0[0] = q0;
  int failures = 0;
  for (const char* name : {"rk4", "dopri5", "rosenbrock23", "exponential"}) {
    RunOptions<double> run;
    run.integrator = parse_integrator(name);
    run.stepper.rtol = 1e-10;
    run.stepper.atol = 1e-14;
    run.stepper.fixed_step = 1e-5;
    const auto r = simulate(system, system.requested_mode(), 0.0, x0, t_end, run);
    const double error = std::abs(r.x[0] - q0 * std::cos(w * t_end)) / q0;
    std::printf("compiled mode, %-12s q(t_end) relative error %.2e (%s)\n", name, error,
                r.ok() ? "ok" : r.message.c_str());
    // RK4 at w h ~ 0.002 and the adaptive methods at rtol 1e-10 all stay below 1e-6; the stiff
    // second-order Rosenbrock method is the loosest.
    if (!r.ok() || !(error < 1e-6)) ++failures;
  }
  return failures;
#endif
}

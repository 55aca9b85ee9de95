// The README's usage example, compiled and run by the tests (label model): a cantilever blade
// with one friction damper under a harmonic load, simulated for 1 s.
#include <stickslip/stickslip.hpp>

#include <cmath>
#include <cstdio>

int main() {
  using namespace stickslip;
  // --- README excerpt begins ---
  FrameModel<double> frame;                                   // 1. beam elements
  auto root = frame.add_node(0, 0), tip = frame.add_node(0, 0.2);
  auto blade = frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, 20);
  frame.clamp(root);
  ModalOptions<double> mo;
  mo.num_modes = 6;
  auto basis = compute_modes(frame.assemble(), mo);           // 2. mass-normalised modes
  std::vector<PointDamper<double>> dampers;                   // 4. any number of friction contacts
  dampers.emplace_back(blade, 0.15, 0.01, 5e3, 5.0, CoulombLaw<double>(0.35, 0.3));
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(blade, 0.05, LoadDirection::GlobalX, 20, 200)};
  FrictionDampedSystem<double> system(frame, basis, dampers, loads);   // 3 + 4 composed
  auto x = system.initial_state();
  auto mode = system.requested_mode();
  system.make_consistent(mode, 0.0, x);
  NullObserver observer;
  auto result = simulate(system, mode, 0.0, x, 1.0, RunOptions<double>{}, observer);  // 5. hybrid stepper
  // --- README excerpt ends ---
  const double E0 = 0.0;  // rest, stuck, no deflection: zero mechanical energy at t = 0
  const auto audit = system.energy_balance(result.mode, result.t, result.x, E0);
  std::printf("status %s at t = %g s, %ld contact switches, %ld steps, energy residual %.3e J of %.3e J\n",
              to_string(result.status), result.t, result.stats.events, result.stats.accepted_steps,
              audit.residual, std::abs(audit.external_work));
  // The run must finish and balance its energy to well within the default tolerance (rtol 1e-6).
  return result.ok() && std::abs(audit.residual) <= 1e-4 * std::abs(audit.external_work) ? 0 : 1;
}

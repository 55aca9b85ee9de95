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
  // --- README excerpt (ContactSystem) begins ---
  std::vector<PointContact<double>> contacts{PointContact<double>::grounded(
      {blade, 0.1}, PlaneDirection<double>::global_x(), CoulombLaw<double>(0.35, 0.3), /*N=*/10.0)};
  ContactSystem<double> sliders(frame, basis, contacts, loads);   // then simulate(), shooting, ...
  // --- README excerpt (ContactSystem) ends ---
  auto xs = sliders.initial_state();
  auto ms = sliders.requested_mode();
  sliders.make_consistent(ms, 0.0, xs);
  const auto slider_run = simulate(sliders, ms, 0.0, xs, 0.2, RunOptions<double>{}, observer);
  const auto slider_audit = sliders.energy_balance(slider_run.x, 0.0);
  std::printf("grounded slider: status %s, %zu switches, energy audit relative residual %.2e\n",
              to_string(slider_run.status), sliders.events().size(), slider_audit.relative_residual());
  // The runs must finish and balance their energy to well within the default tolerance (rtol 1e-6).
  return result.ok() && std::abs(audit.residual) <= 1e-4 * std::abs(audit.external_work) && slider_run.ok() &&
                 slider_audit.relative_residual() <= 1e-4
             ? 0
             : 1;
}

// custom_contact: a contact kind of one's own, defined outside the library and run through
// ContactSystem, simulate(), shooting and the energy audit.
//
// The kind: a rotational friction hinge. A bolted joint whose faces turn against each other
// transmits a friction moment M = -mu N r sgn(theta_a' - theta_b') while it slips and any moment
// up to mu_s N r while it sticks: a Coulomb contact on the relative rotation of two nodes (or of
// one node against ground), with an effective "normal force" N r [N m]. It satisfies the
// contact concept (stickslip/model/contact_concept.hpp) with five members; ContactSystem never
// learns that its "sliding velocity" is an angular velocity.
//
// The scene: a clamped cantilever whose tip is held against rotation by such a hinge to ground,
// forced at its tip. Prints the run's events and energy audit, then shoots the periodic orbit
// and checks that it repeats. Exit status 0 when the audit closes and the orbit converges.

#include <stickslip/model/contact_system.hpp>
#include <stickslip/stickslip.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using namespace stickslip;

/// A rotational friction hinge between node a and node b (none: ground).
struct FrictionHinge {
  using Scalar = double;
  using Law = CoulombLaw<double>;
  NodeId a = 0;
  std::optional<NodeId> b;
  Law friction{0.35, 0.3};
  double normal = 100.0;  ///< clamping force N [N]
  double radius = 0.01;   ///< friction radius r [m]: the moment capacity is mu N r

  /// Relative rotation theta_a - theta_b = row . q: the nodes' rotation rows (component 2).
  Eigen::VectorXd tangential_row(const FrameModel<double>& frame, const ModalBasis<double>& basis,
                                 const std::string& where) const {
    if (a < 0 || a >= frame.num_nodes()) throw std::invalid_argument(where + ": node a is not a node of the frame");
    Eigen::VectorXd row = basis.nodal(a, Dof::Rz).transpose();
    if (b) row -= basis.nodal(*b, Dof::Rz).transpose();
    return row;
  }
  const Law& law() const { return friction; }
  /// The Coulomb law sees an effective normal force N r, so its force is a moment [N m].
  double normal_force(double) const { return normal * radius; }
  ContactState start_state() const { return ContactState::Stick; }
  void validate(const std::string& where) const {
    if (!(normal > 0)) throw std::invalid_argument(where + ": normal must be > 0");
    if (!(radius > 0)) throw std::invalid_argument(where + ": radius must be > 0");
  }
};
static_assert(is_contact_v<FrictionHinge>, "FrictionHinge must satisfy the contact concept");

int main() {
  FrameModel<double> frame;
  const NodeId root = frame.add_node(0, 0), tip = frame.add_node(0, 0.2);
  const MemberId beam = frame.add_member(root, tip, SectionProperties<double>{2.06e11, 7800, 6e-5, 2e-11}, 10);
  frame.clamp(root);
  ModalOptions<double> mo;
  mo.num_modes = 4;
  const auto basis = compute_modes(frame.assemble(), mo).with_modal_damping(Eigen::VectorXd::Constant(4, 0.02));

  FrictionHinge hinge;
  hinge.a = tip;
  const double w = 0.9 * basis.omega()(0);
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(beam, 0.2, LoadDirection::GlobalX, 20.0, w)};
  ContactSystem<double, FrictionHinge> system(frame, basis, {hinge}, loads);

  auto x = system.initial_state();
  auto mode = system.requested_mode();
  if (!system.make_consistent(mode, 0.0, x)) return 1;
  RunOptions<double> run;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-14;
  const double T = 2 * 3.14159265358979323846 / w;
  const auto result = simulate(system, mode, 0.0, x, 60 * T, run);
  const auto audit = system.energy_balance(result.x, 0.0);
  long slips = 0;
  for (const auto& e : system.events()) slips += e.from == ContactState::Stick;
  std::printf("custom_contact: friction hinge at the tip, %s after %.3f s: %zu switches (%ld stick -> slip), "
              "friction dissipation %.4g J, audit relative residual %.2e\n",
              to_string(result.status), result.t, system.events().size(), slips, audit.friction_dissipation,
              audit.relative_residual());

  // The periodic orbit by shooting from the end of the transient (the audit states excluded).
  ShootingOptions<double> so;
  so.periodic = ShootingOptions<double>::first(2 * system.num_modes());
  Shooting<ContactSystem<double, FrictionHinge>> shooting(system, so);
  const auto orbit = shooting.forced(result.mode, result.t, result.x, T);
  std::printf("custom_contact: periodic orbit %s after %d iterations, residual %.2e, max |multiplier| %.3f\n",
              to_string(orbit.status), orbit.iterations, orbit.residual, orbit.floquet.max_modulus);
  // rtol 1e-10: the audit closes to ~1e-9 of the work; 1e-6 flags a missing power term.
  const bool ok = result.status == Status::Success && slips > 0 && audit.relative_residual() < 1e-6 &&
                  orbit.status == ShootingStatus::Converged;
  return ok ? 0 : 1;
}

#pragma once
/// \file blade_scene.hpp
/// \brief The paper's blade with two under-platform dampers (section 3), built from stickslip's
/// components. The choices the paper leaves open are fixed here and written in
/// docs/blade_damper.md: a T-shaped frame, the blade clamped at its root, the platform centred on
/// the blade tip (rigid joint), the dampers under the middle of each platform wing.

#include "blade_contact_options.hpp"

#include <stickslip/stickslip.hpp>

#include <memory>
#include <vector>

namespace blade {

using Index = Eigen::Index;

/// Parameters of the default scene (paper section 3 plus the documented open choices).
struct BladeParameters {
  double k = 1.0e4;          ///< damper spring [N/m]
  double spin = 50.0;        ///< Omega [rad/s]
  double radius = 0.46;      ///< r [m]
  double E = 2.06e11;        ///< [Pa]
  double rho = 7800.0;       ///< [kg/m^3]
  double A = 6e-5;           ///< [m^2]
  double I = 2e-11;          ///< [m^4]
  double L1 = 0.2;           ///< blade length [m]
  double L2 = 0.04;          ///< platform length [m]
  double mu_s = 0.35;
  double mu_k = 0.3;
  double force = 20.0;       ///< F amplitude [N]
  double force_omega = 200;  ///< excitation [rad/s]
  double y0 = 0.05;          ///< excitation point above the root [m]
  double preload = 12.0;     ///< N0 [N]; damper mass m = 2 N0 / (r Omega^2)
  double share = 0.5;        ///< a damper shared by two blades
  double damper_offset = 0.01;  ///< dampers at -/+ this distance from the blade axis [m]
  int blade_elements = 20;
  int platform_elements = 8;   ///< even, so that the blade tip is a platform node
  int modes = 6;
  double damping_ratio = 0.0;  ///< modal damping ratio of every retained mode
  /// Friction law: exact Coulomb (default) or regularised tanh with this v_eps when > 0.
  double regularised_v_eps = 0.0;
  stickslip::ModelOptions<double> model{};
  ContactOptions contact{};  ///< separation at lift-off (--restitution), blade_contact_options.hpp

  /// Damper mass from the preload: N0 = share m r Omega^2  (paper: N0 = F/2 = m r Omega^2 / 2).
  double damper_mass() const { return preload / (share * radius * spin * spin); }
};

/// The frame, its modes and the friction-damped system of the default scene.
struct BladeScene {
  using System = stickslip::FrictionDampedSystem<double>;
  stickslip::FrameModel<double> frame;
  Eigen::Index blade_member = 0;     ///< root (0,0) -> tip (0, L1)
  Eigen::Index platform_member = 0;  ///< (-L2/2, L1) -> (L2/2, L1)
  Eigen::Index tip_node = 0;
  stickslip::ModalBasis<double> basis;
  std::unique_ptr<System> system;
  BladeParameters parameters;

  /// Lateral (global X) displacement of the blade tip for the state x.
  double tip_displacement(const System::State& x) const { return tip_shape.dot(x.head(basis.size())); }
  System::Vector tip_shape;
};

/// The friction-damped system of scene `s` (its frame, members and modes) with the dampers and
/// the load of `p`: for parameter studies that change the friction, the preload or the load but
/// not the structure (frequency-response curves, blade_frc.hpp).
inline BladeScene::System make_blade_system(const BladeScene& s, const BladeParameters& p) {
  using namespace stickslip;
  FrictionLawVariant<double> law = CoulombLaw<double>(p.mu_s, p.mu_k);
  if (p.regularised_v_eps > 0) law = RegularisedLaw<double>(p.mu_k, p.regularised_v_eps);
  const double m = p.damper_mass();
  const double X_left = p.L2 / 2 - p.damper_offset, X_right = p.L2 / 2 + p.damper_offset;
  std::vector<PointDamper<double>> dampers;
  dampers.emplace_back(s.platform_member, X_left, m, p.k, p.preload, law, p.share);
  dampers.emplace_back(s.platform_member, X_right, m, p.k, p.preload, law, p.share);
  apply_contact_options(p.contact, dampers);
  std::vector<PointLoad<double>> loads{PointLoad<double>::harmonic(
      s.blade_member, p.y0, LoadDirection::GlobalX, p.force, p.force_omega)};
  return BladeScene::System(s.frame, s.basis, std::move(dampers), std::move(loads), p.model);
}

/// The ids of one blade + platform frame added by add_blade_frame.
struct BladeFrame {
  Index root = 0;             ///< clamped root node, at origin
  Index left = 0, right = 0;  ///< platform wing ends, origin + (-/+ L2/2, L1)
  Index tip_node = 0;         ///< blade tip = platform middle
  Index platform_member = 0;  ///< left -> right
  Index blade_member = 0;     ///< root -> tip
};

/// Adds the paper's blade + platform (the T-shaped frame of docs/blade_damper.md) to `f` with
/// its root at `origin`, the Young's modulus scaled by `stiffness_factor` (blade-to-blade
/// mistuning of a disk; 1 for the single blade). Nodes and members are added in the same order
/// at every call: root, left, right, platform, blade.
inline BladeFrame add_blade_frame(stickslip::FrameModel<double>& f, const BladeParameters& p,
                                  const Eigen::Vector2d& origin = Eigen::Vector2d::Zero(),
                                  double stiffness_factor = 1.0) {
  const stickslip::SectionProperties<double> section{p.E * stiffness_factor, p.rho, p.A, p.I};
  BladeFrame b;
  b.root = f.add_node(origin.x(), origin.y());
  b.left = f.add_node(origin.x() - p.L2 / 2, origin.y() + p.L1);
  b.right = f.add_node(origin.x() + p.L2 / 2, origin.y() + p.L1);
  b.platform_member = f.add_member(b.left, b.right, section, p.platform_elements);
  b.tip_node = f.member(b.platform_member).nodes[static_cast<std::size_t>(p.platform_elements / 2)];
  b.blade_member = f.add_member(b.root, b.tip_node, section, p.blade_elements);
  f.clamp(b.root);
  return b;
}

/// Builds the default blade-damper scene for the given parameters.
inline BladeScene make_blade_scene(const BladeParameters& p) {
  using namespace stickslip;
  BladeScene s;
  s.parameters = p;
  auto& f = s.frame;
  const BladeFrame b = add_blade_frame(f, p);
  s.platform_member = b.platform_member;
  s.tip_node = b.tip_node;
  s.blade_member = b.blade_member;

  ModalOptions<double> mo;
  mo.num_modes = p.modes;
  s.basis = compute_modes(f.assemble(), mo);
  if (p.damping_ratio > 0)
    s.basis = s.basis.with_modal_damping(
        Eigen::VectorXd::Constant(s.basis.size(), p.damping_ratio));

  s.system = std::make_unique<BladeScene::System>(make_blade_system(s, p));
  s.tip_shape = s.system->point_shape(s.blade_member, p.L1, LoadDirection::GlobalX);
  return s;
}

}  // namespace blade

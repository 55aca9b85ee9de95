#pragma once
/// \file disk_scene.hpp
/// \brief The bladed disk of the example (docs/disks.md, "The example"): N copies of the paper's
/// blade + platform (examples/blade_damper's frame, add_blade_frame) side by side, neighbouring
/// platforms coupled by springs between their wing ends and by a friction damper (a joint
/// under the damper's preload, neighbour_joints) between platform k's right wing and platform
/// k + 1's left wing, every blade forced at engine order EO. Shared by the example and the disk
/// benchmarks.

#include "../blade_damper/blade_scene.hpp"

#include <stickslip/disk.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Core>

#include <cmath>
#include <numeric>
#include <vector>

namespace bladed_disk {

using Index = Eigen::Index;
using System = stickslip::ContactSystem<double>;
using Disk = stickslip::BladedDisk<double>;

/// Parameters of the disk scene. The blade and its material are the blade example's
/// (BladeParameters: E, rho, A, I, L1, L2, mu_s, mu_k, force, y0); the rest is the disk's.
struct DiskParameters {
  blade::BladeParameters blade;    ///< the blade example's defaults (20 blade, 8 platform elements)
  Index sectors = 24;              ///< N blades
  Index engine_order = 3;          ///< EO
  double pitch = 0.05;             ///< distance between neighbouring blade roots [m] (> L2)
  double spring_x = 1.0e3;         ///< coupling springs between neighbouring wing ends [N/m]
  double spring_y = 1.0e3;         ///< [N/m]
  double spring_rz = 1.0;          ///< [N m/rad]
  double damper_angle = 0.6;       ///< sliding direction of the dampers' faces from the platform [rad]
  double damping_ratio = 0.005;    ///< modal damping ratio of every retained mode
  /// Lowest modes kept per nodal diameter, every family (modes_per_family N annulus modes).
  /// Every family needs at least one: the N stuck dampers' rows span the N families, and a
  /// basis without one of them makes the stuck set dependent.
  Index modes_per_family = 2;
};

/// The disk, its modes and the pieces of its ContactSystem.
struct DiskScene {
  DiskParameters parameters;
  Disk disk;
  blade::BladeFrame sector;                 ///< ids in the reference sector
  stickslip::CyclicModes<double> cyclic;    ///< all families (modes_per_family each)
  stickslip::ModalBasis<double> basis;      ///< the retained annulus modes, damped
  Eigen::MatrixXd tip_rows;                 ///< row k: blade k's tip X displacement over the modes
  Index load_node = 0;                      ///< the blade node at y0, where the load acts (sector numbering)

  explicit DiskScene(const DiskParameters& p)
      : DiskScene(p, {}) {}
  /// The disk with blade-to-blade scatter delta_k (empty: tuned; cyclic modes only when tuned).
  DiskScene(const DiskParameters& p, std::vector<double> mistuning)
      : parameters(p),
        disk(p.sectors, p.pitch, builder(p),
             stickslip::SectorCoupling<double>::springs(p.spring_x, p.spring_y, p.spring_rz), std::move(mistuning)) {
    stickslip::FrameModel<double> probe;
    sector = blade::add_blade_frame(probe, p.blade);
    load_node = probe.member(sector.blade_member).nodes[static_cast<std::size_t>(
        std::lround(p.blade.y0 / p.blade.L1 * double(p.blade.blade_elements)))];
    if (!disk.is_tuned()) {
      stickslip::ModalOptions<double> mo;
      mo.num_modes = p.modes_per_family * p.sectors;
      basis = damped(stickslip::compute_modes(disk.assemble(), mo));
      tip_rows = rows(basis, sector.tip_node);
      return;
    }
    stickslip::CyclicModalOptions<double> co;
    co.num_modes = p.modes_per_family;
    cyclic = stickslip::compute_cyclic_modes(disk, co);
    basis = damped(stickslip::annulus_basis(disk, cyclic));
    tip_rows = rows(basis, sector.tip_node);
  }

  /// `b` with the modal damping ratio of the parameters.
  stickslip::ModalBasis<double> damped(const stickslip::ModalBasis<double>& b) const {
    if (!(parameters.damping_ratio > 0)) return b;
    return b.with_modal_damping(Eigen::VectorXd::Constant(b.size(), parameters.damping_ratio));
  }
  /// Row k: the X displacement of sector node `sector_node` of blade k over the modes of `b`.
  Eigen::MatrixXd rows(const stickslip::ModalBasis<double>& b, Index sector_node) const {
    Eigen::MatrixXd r(parameters.sectors, b.size());
    for (Index k = 0; k < parameters.sectors; ++k) r.row(k) = b.nodal(disk.node(k, sector_node), stickslip::Dof::X);
    return r;
  }

  /// The sector builder: the blade example's frame at the placement, E scaled by its factor.
  static Disk::SectorBuilder builder(const DiskParameters& p) {
    return [bp = p.blade](stickslip::FrameModel<double>& f, const stickslip::SectorPlacement<double>& at) {
      const blade::BladeFrame b = blade::add_blade_frame(f, bp, at.origin, at.stiffness_factor);
      return stickslip::SectorAttachments{b.left, b.right};
    };
  }

  stickslip::StructurePoint<double> right_wing() const { return {sector.platform_member, parameters.blade.L2}; }
  stickslip::StructurePoint<double> left_wing() const { return {sector.platform_member, 0.0}; }
  stickslip::PlaneDirection<double> damper_direction() const {
    return stickslip::PlaneDirection<double>::at_angle(parameters.damper_angle);
  }

  /// The dampers at preload N0 (Coulomb, the blade example's mu_s, mu_k).
  std::vector<stickslip::PointContact<double>> dampers(double preload) const {
    return stickslip::neighbour_joints(disk, right_wing(), left_wing(), damper_direction(),
                                       stickslip::CoulombLaw<double>(parameters.blade.mu_s, parameters.blade.mu_k),
                                       preload);
  }
  /// F_k = F cos(Omega t + 2 pi EO k / N) at y0 (a node of the blade's mesh) on every blade, along X.
  std::vector<stickslip::PointLoad<double>> loads(double omega) const {
    return stickslip::engine_order_loads(disk, sector.blade_member, parameters.blade.y0,
                                         stickslip::LoadDirection::GlobalX, parameters.blade.force, omega,
                                         parameters.engine_order);
  }
  /// The annulus' ContactSystem forced at Omega with dampers at preload N0.
  System system(double omega, double preload) const {
    return System(disk.frame(), basis, dampers(preload), loads(omega));
  }
  /// Tip X displacement of every blade for the state x.
  Eigen::VectorXd tips(const System::State& x) const { return tip_rows * x.head(basis.size()); }
  /// Frequency of the lowest mode of nodal diameter EO (folded) [rad/s].
  double engine_order_frequency() const {
    const Index h = stickslip::engine_order_nodal_diameter(parameters.engine_order, parameters.sectors);
    return cyclic.families[static_cast<std::size_t>(h)].omega(0);
  }
};

}  // namespace bladed_disk

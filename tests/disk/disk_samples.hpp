#pragma once
// Shared by the disk tests: the paper's blade + platform as a sector of a BladedDisk.

#include <stickslip/disk.hpp>
#include <stickslip/stickslip.hpp>

#include <Eigen/Core>

namespace disk_samples {

using namespace stickslip;
using Vector2 = Eigen::Vector2d;
using Disk = BladedDisk<double>;

constexpr double kPi = 3.14159265358979323846;
// A stocky steel section: (A L^2 / I) moderate, so that lambda_max / lambda_1 of the sector stays
// near 1e5 and the dense standard-form eigenvalues carry ~eps * 1e5 ~ 2e-11 relative error.
const SectionProperties<double> kSection{2.0e11, 7800, 1e-4, 1e-9};
constexpr double kBlade = 0.2, kPlatform = 0.04, kPitch = 0.05;

/// The paper's blade + platform as a sector: platform from (-L2/2, L1) to (L2/2, L1) in two
/// elements, the blade from the clamped root (0, 0) to the platform's middle in four. Sector
/// numbering: node 0 left wing, 1 right wing, 2 platform middle (the blade tip), 3 root; member
/// 0 platform, member 1 blade.
inline SectorAttachments build_sector(FrameModel<double>& f, const Vector2& o, double stiffness_factor = 1.0) {
  SectionProperties<double> section = kSection;
  section.E *= stiffness_factor;
  const NodeId left = f.add_node(o.x() - kPlatform / 2, o.y() + kBlade);
  const NodeId right = f.add_node(o.x() + kPlatform / 2, o.y() + kBlade);
  const MemberId platform = f.add_member(left, right, section, 2);
  const NodeId mid = f.member(platform).nodes[1];
  const NodeId root = f.add_node(o.x(), o.y());
  f.add_member(root, mid, section, 4);
  f.clamp(root);
  return {left, right};
}
constexpr NodeId kTip = 2;
constexpr MemberId kPlatformMember = 0, kBladeMember = 1;

inline Disk::SectorBuilder builder() {
  return [](FrameModel<double>& f, const SectorPlacement<double>& p) {
    return build_sector(f, p.origin, p.stiffness_factor);
  };
}

}  // namespace disk_samples

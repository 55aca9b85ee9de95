#pragma once
/// \file neighbour_joints.hpp
/// \brief Friction joints between neighbouring blades of a bladed disk: platform k's right wing
/// rubs on platform k + 1's left wing (wrap-around at N) under a held normal force, a
/// simplified under-platform damper (no damper body: its mass and rotation are neglected).

#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/model/damper_states.hpp"
#include "stickslip/model/point_contact.hpp"
#include "stickslip/model/structure_point.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace stickslip {

/// N PointContact joints for ContactSystem over disk.frame(): contact k has side a at
/// `right_wing` of sector k and side b at `left_wing` of sector k + 1 mod N (both points in the
/// reference sector's numbering), relative sliding (u_a - u_b) . direction, law `law`, held
/// normal force `normal` [N]. Contact k's force acts on the two platforms equal and opposite, so
/// the joints transmit no net force to the disk as a whole. With `direction` along the platforms
/// (global X) and every joint stuck, the rows sum to the platforms' axial stretch, which few
/// retained modes lack: the stuck set is then dependent (docs/disks.md); incline the direction.
/// \throws std::invalid_argument naming the parameter: more than DamperStates::max_dampers
///         sectors (num_sectors), a point off its sector's members (right_wing.member,
///         left_wing.member), or normal not finite and > 0. The remaining checks (coordinates on
///         the member, direction, law) are ContactSystem's, naming the contact.
template <class Scalar>
std::vector<PointContact<Scalar>> neighbour_joints(const BladedDisk<Scalar>& disk,
                                                   const StructurePoint<Scalar>& right_wing,
                                                   const StructurePoint<Scalar>& left_wing,
                                                   const PlaneDirection<Scalar>& direction,
                                                   const typename PointContact<Scalar>::Law& law, Scalar normal) {
  static const char* where = "neighbour_joints";
  using Index = Eigen::Index;
  const Index N = disk.num_sectors();
  if (N > DamperStates::max_dampers)
    detail::throw_invalid(where, "num_sectors must be <= DamperStates::max_dampers = " +
                                     std::to_string(DamperStates::max_dampers) + " (one contact per sector)",
                          N);
  if (right_wing.member < 0 || right_wing.member >= disk.members_per_sector())
    detail::throw_invalid(where, "right_wing.member must be a member of the sector", Index(right_wing.member));
  if (left_wing.member < 0 || left_wing.member >= disk.members_per_sector())
    detail::throw_invalid(where, "left_wing.member must be a member of the sector", Index(left_wing.member));
  detail::require_positive(where, "normal", normal);
  std::vector<PointContact<Scalar>> contacts;
  contacts.reserve(static_cast<std::size_t>(N));
  for (Index k = 0; k < N; ++k)
    contacts.push_back(PointContact<Scalar>::joint(disk.point(k, right_wing), disk.point((k + 1) % N, left_wing),
                                                   direction, law, normal));
  return contacts;
}

}  // namespace stickslip

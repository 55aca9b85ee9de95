#pragma once
/// \file neighbour_dampers.hpp
/// \brief Rigid wedge dampers between neighbouring platforms of a bladed disk: damper k rests on
/// platform k's right wing and platform k + 1's left wing (wrap-around at N), one rigid body with
/// its own mass, rotation, centrifugal load and two faces with unilateral friction contacts
/// (model/wedge_damper.hpp), for ContactSystem<Scalar, BodyContact<Scalar>> (docs/disks.md).

#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/model/body_contact.hpp"
#include "stickslip/model/damper_states.hpp"
#include "stickslip/model/rigid_body.hpp"
#include "stickslip/model/structure_point.hpp"
#include "stickslip/model/wedge_damper.hpp"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// One damper of the disk, given once for every pair of neighbours: its inertia, its load, its
/// two faces in body coordinates (from its centre of mass), the friction law of both faces.
/// The faces' platform points are filled in by neighbour_wedge_dampers.
template <class Scalar>
struct NeighbourDamperSpec {
  Scalar mass = Scalar(0);      ///< m [kg]
  Scalar inertia = Scalar(0);   ///< J about the centre of mass [kg m^2]
  Scalar preload = Scalar(0);   ///< centrifugal load P = m r Omega^2 along `radial` [N]
  /// Left face (on the lower-numbered blade's right wing): its point, angle and half width
  /// (WedgeFace; `platform` is ignored).
  WedgeFace<Scalar> left;
  /// Right face (on the next blade's left wing), as `left`.
  WedgeFace<Scalar> right;
  FrictionLawVariant<Scalar> law = CoulombLaw<Scalar>(Scalar(0.3), Scalar(0.3));  ///< both faces
  PlaneDirection<Scalar> radial = PlaneDirection<Scalar>::global_y();  ///< load direction
  Scalar restitution = Scalar(0);  ///< e of a landing, both faces
};

/// The bodies and contacts of a disk's dampers, in the order ContactSystem takes them: body k is
/// damper k; its contacts are 2k, 2k + 1 (left face, right face) with one point per face, or
/// 4k ... 4k + 3 with two (contacts_per_damper()).
template <class Scalar>
struct NeighbourDampers {
  std::vector<RigidBody<Scalar>> bodies;       ///< damper k = body k
  std::vector<BodyContact<Scalar>> contacts;   ///< damper k's contacts, left face first
  Eigen::Index contacts_per_damper = 0;        ///< 2 or 4
};

/// N wedge dampers for ContactSystem<Scalar, BodyContact<Scalar>> over disk.frame(): damper k's
/// left face touches `right_wing` of sector k, its right face `left_wing` of sector k + 1 mod N
/// (both points in the reference sector's numbering, mapped by BladedDisk::point). Every damper is
/// the same body (spec), so a tuned disk with its dampers keeps the cyclic symmetry: shifting the
/// blades by one shifts body k to k + 1 and its contacts by contacts_per_damper.
/// \throws std::invalid_argument naming the parameter: right_wing.member or left_wing.member not
///         a member of the sector, more contacts than DamperStates::max_dampers (num_sectors),
///         and wedge_damper's checks of the faces, preload and radial direction (spec.left.angle,
///         ...). Mass, inertia and the contacts' coordinates are ContactSystem's checks.
template <class Scalar>
NeighbourDampers<Scalar> neighbour_wedge_dampers(const BladedDisk<Scalar>& disk,
                                                 const StructurePoint<Scalar>& right_wing,
                                                 const StructurePoint<Scalar>& left_wing,
                                                 const NeighbourDamperSpec<Scalar>& spec) {
  static const char* where = "neighbour_wedge_dampers";
  using Index = Eigen::Index;
  if (right_wing.member < 0 || right_wing.member >= disk.members_per_sector())
    detail::throw_invalid(where, "right_wing.member must be a member of the sector", Index(right_wing.member));
  if (left_wing.member < 0 || left_wing.member >= disk.members_per_sector())
    detail::throw_invalid(where, "left_wing.member must be a member of the sector", Index(left_wing.member));
  const Index N = disk.num_sectors();
  const Index per = (spec.left.half_width > Scalar(0) ? 2 : 1) + (spec.right.half_width > Scalar(0) ? 2 : 1);
  if (N * per > DamperStates::max_dampers)
    detail::throw_invalid(where, "num_sectors times the contacts per damper (" + std::to_string(per) +
                                     ") must be <= DamperStates::max_dampers = " +
                                     std::to_string(DamperStates::max_dampers) + "; num_sectors",
                          N);
  NeighbourDampers<Scalar> out;
  out.contacts_per_damper = per;
  out.bodies.reserve(static_cast<std::size_t>(N));
  out.contacts.reserve(static_cast<std::size_t>(N * per));
  for (Index k = 0; k < N; ++k) {
    WedgeFace<Scalar> left = spec.left, right = spec.right;
    left.platform = {disk.point(k, right_wing)};
    right.platform = {disk.point((k + 1) % N, left_wing)};
    WedgeDamper<Scalar> w = wedge_damper<Scalar>(k, spec.mass, spec.inertia, spec.preload, left, right, spec.law,
                                                 spec.radial, spec.restitution);
    out.bodies.push_back(std::move(w.body));
    for (auto& c : w.contacts) out.contacts.push_back(std::move(c));
  }
  return out;
}

}  // namespace stickslip

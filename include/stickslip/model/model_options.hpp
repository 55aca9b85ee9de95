#pragma once
/// \file model_options.hpp
/// \brief What a friction-damped scene models. Each switch costs nothing when off.

#include "stickslip/model/normal_load.hpp"
#include "stickslip/moving_load.hpp"

namespace stickslip {

/// Modelling switches of FrictionDampedSystem.
template <class Scalar>
struct ModelOptions {
  /// Normal-load variation from the damper's vertical inertia (paper eqs 23-24) or constant N0.
  NormalLoad normal_load = NormalLoad::Inertial;
  /// The contact points move along the member with the relative slip (moving load, paper eq 10),
  /// as far as each damper's PointDamper::contact_point allows (Moving by default), or all stay at
  /// their initial coordinates (false overrides every damper). The state holds the contact
  /// coordinates when at least one damper's contact moves; FrictionDampedSystem::options() then
  /// reports moving_contact = true, else false.
  bool moving_contact = true;
  /// With a moving contact: keep the convective terms of the damper's vertical acceleration
  /// (2 q'^T psi_w' X' + q^T psi_w'' X'^2 + q^T psi_w' X'', paper eq 19).
  bool convective_terms = true;
  /// Watch the normal force and stop with a lift-off status when it reaches zero.
  bool watch_lift_off = true;
  /// Integrate the work and dissipation terms alongside the state for an energy audit.
  bool energy_audit = true;
  /// What happens when a contact point reaches a member end (component 3's policy): Throw stops
  /// the run with a "left member" status; Extrapolate/Clamp continue with that approximation.
  /// A damper's PointDamper::start_end / finish_end override it per end (MemberEnd: Stop,
  /// Extend, Wall; Default follows this option).
  EndPolicy end_policy = EndPolicy::Throw;
  /// When the acceleration solve's matrix changed since its last factorisation but has the same
  /// unknowns (slipping contacts that moved, new slopes), and the system is larger than the
  /// fixed-size 8 x 8 ones: solve by iterative refinement from the old factorisation (a few
  /// products with F and L) while it converges, instead of forming and factorising the new
  /// matrix. Results agree with the direct solve to round-off (relative 16 eps per correction
  /// criterion) but depend, at that level, on which matrix was factorised last (the call
  /// history). Off: every changed matrix is refactorised and the result is a function of the
  /// state alone, bitwise.
  bool refine_stale_factorisation = true;
};

}  // namespace stickslip

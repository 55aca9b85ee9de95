#pragma once
/// \file point_damper.hpp
/// \brief A point-contact friction damper pressed against a member of a frame.

#include "stickslip/beam/ids.hpp"
#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/contact_point.hpp"
#include "stickslip/model/detail/enum_checks.hpp"
#include "stickslip/model/normal_load.hpp"
#include "stickslip/model/member_end.hpp"
#include "stickslip/model/separation.hpp"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <variant>

namespace stickslip {

/// Any of the library's friction laws, chosen per damper at run time.
template <class Scalar>
using FrictionLawVariant = std::variant<CoulombLaw<Scalar>, StribeckLaw<Scalar>, RegularisedLaw<Scalar>>;

/// A damper in point contact with a member (the paper's under-platform damper, Figs 3-4).
///
/// It slides along the member's local axis u, follows the member's transverse motion w, is held
/// by a spring k to its own support along u, and is pressed against the member by the preload
/// N0 (paper: N0 = F/2 = m r Omega^2 / 2, the centrifugal force shared by two blades). The share
/// factor s scales the damper's inertia and spring in this structure's equations: effective mass
/// s m, effective spring s k. It defaults to 1 (the damper acts on this structure alone); the
/// paper's blade scene passes s = 1/2 (eqs 11-14, "a damper shared by two blades").
template <class Scalar, class Law = FrictionLawVariant<Scalar>>
struct PointDamper {
  /// Damper on `member` at contact coordinate X0 with mass m, spring k, preload N0 and `law`.
  PointDamper(MemberId member_, Scalar contact_coordinate_, Scalar mass_, Scalar stiffness_,
              Scalar preload_, Law law_, Scalar share_ = Scalar(1))
      : member(member_), contact_coordinate(contact_coordinate_), mass(mass_),
        stiffness(stiffness_), preload(preload_), share(share_), law(std::move(law_)) {}

  MemberId member = 0;           ///< member the damper touches
  Scalar contact_coordinate{};   ///< initial contact coordinate X0 along the member [m]
  Scalar mass{};                 ///< damper mass m [kg] (> 0)
  Scalar stiffness{};            ///< spring k to the damper's support along u [N/m] (>= 0)
  Scalar preload{};              ///< N0, this blade's share of the normal load [N] (>= 0)
  Scalar share = Scalar(1);      ///< share factor s in (0, 1] (1/2 in the paper's blade scene)
  Law law;                       ///< friction law
  ContactState initial_state = ContactState::Stick;  ///< state requested at t0
  /// +1: the damper presses the member along its local +w axis (90 degrees counter-clockwise
  /// from u); -1: along -w (a damper on the other face).
  Scalar side = Scalar(1);
  /// This damper's normal force: Inertial (N = N0 - s m y'', paper eqs 23-24) or Constant
  /// (N = N0). ModelOptions::normal_load = Constant overrides it for every damper.
  NormalLoad normal_load = NormalLoad::Inertial;
  /// This damper's contact point: Moving (X' = V, paper eq 10) or Fixed (X = X0).
  /// ModelOptions::moving_contact = false overrides it for every damper.
  ContactPoint contact_point = ContactPoint::Moving;
  /// What happens when this damper's normal force reaches zero: Stop the run (default) or
  /// Separate (free flight, then an impact; docs/model_separation.md "Separation"). Separate needs an
  /// inertial normal load and ModelOptions::watch_lift_off (else N never reaches zero).
  Separation separation = Separation::Stop;
  /// Newton's coefficient of restitution e in [0, 1] of this damper's impacts (Separate only).
  Scalar restitution = Scalar(0);
  /// Impacts approaching at or below this relative normal speed land (persistent contact, the
  /// rule that ends a Zeno sequence of bounces; NewtonImpact) [m/s], >= 0 (Separate); a
  /// contact arriving at a MemberEnd::Wall at or below it comes to rest against the wall
  /// (docs/model_separation.md "Resting at a wall").
  Scalar landing_speed = Scalar(1e-4);
  /// What the moving contact does at X = 0 of the member (docs/model_separation.md, "Member ends").
  MemberEnd start_end = MemberEnd::Default;
  /// What the moving contact does at X = L of the member.
  MemberEnd finish_end = MemberEnd::Default;
  /// Coefficient of restitution e in [0, 1] of a MemberEnd::Wall: V -> -e V (e = 0, or an arrival
  /// at or below landing_speed: the damper rests against the wall).
  Scalar wall_restitution = Scalar(1);

  /// Effective mass s m in this blade's equations (paper eqs 11-14).
  Scalar effective_mass() const { return share * mass; }
  /// Effective spring s k (paper eqs 11-12).
  Scalar effective_stiffness() const { return share * stiffness; }

  /// Damper whose preload comes from the centrifugal force: N0 = s m r Omega^2 (paper section 2).
  static PointDamper centrifugal(MemberId member, Scalar contact_coordinate, Scalar mass,
                                 Scalar stiffness, Scalar radius, Scalar spin, Law law,
                                 Scalar share = Scalar(1)) {
    detail::require_non_negative("PointDamper::centrifugal", "radius", radius);
    detail::require_finite("PointDamper::centrifugal", "spin", spin);
    return PointDamper(member, contact_coordinate, mass, stiffness,
                       share * mass * radius * spin * spin, std::move(law), share);
  }

  /// Throws std::invalid_argument naming the damper and the parameter (also for an enum field
  /// holding a value that is not one of its enumerators).
  void validate(Eigen::Index index) const {
    const std::string where = "PointDamper[" + std::to_string(index) + "]";
    detail::require_finite(where, "contact_coordinate", contact_coordinate);
    detail::require_positive(where, "mass", mass);
    detail::require_non_negative(where, "stiffness", stiffness);
    detail::require_non_negative(where, "preload", preload);
    detail::require_positive(where, "share", share);
    if (share > Scalar(1)) detail::throw_invalid(where, "share must be <= 1", share);
    if (!(side == Scalar(1) || side == Scalar(-1))) detail::throw_invalid(where, "side must be +1 or -1", side);
    detail::require_non_negative(where, "restitution", restitution);
    if (!(restitution <= Scalar(1))) detail::throw_invalid(where, "restitution must be in [0, 1]", restitution);
    detail::require_non_negative(where, "landing_speed", landing_speed);
    detail::require_non_negative(where, "wall_restitution", wall_restitution);
    if (!(wall_restitution <= Scalar(1)))
      detail::throw_invalid(where, "wall_restitution must be in [0, 1]", wall_restitution);
    detail::require_enumerator(where, "initial_state", "ContactState", initial_state, ContactState::Separated);
    detail::require_enumerator(where, "normal_load", "NormalLoad", normal_load, NormalLoad::Inertial);
    detail::require_enumerator(where, "contact_point", "ContactPoint", contact_point, ContactPoint::Moving);
    detail::require_enumerator(where, "separation", "Separation", separation, Separation::Separate);
    detail::require_enumerator(where, "start_end", "MemberEnd", start_end, MemberEnd::Wall);
    detail::require_enumerator(where, "finish_end", "MemberEnd", finish_end, MemberEnd::Wall);
    if (initial_state == ContactState::LiftOff)
      detail::throw_invalid(where, "initial_state cannot be lift-off", "lift_off");
    if (initial_state == ContactState::Separated)  // a run starts in contact; lift-off separates
      detail::throw_invalid(where, "initial_state cannot be separated", "separated");
  }
};

}  // namespace stickslip

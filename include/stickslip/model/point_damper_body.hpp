#pragma once
/// \file point_damper_body.hpp
/// \brief The paper's damper (PointDamper) as a ContactSystem scene part: a rigid body on its
/// spring, pressed by its preload, and a BodyContact whose side b moves along the member
/// (docs/contacts.md, "The paper's damper as a body").
///
/// With the member's axes u (along) and w (90 degrees counter-clockwise), a damper pressing the
/// member along side * w (PointDamper::side) becomes
///   - a body of mass s m (the effective mass; paper eqs 11-14) with a spring s k to ground along
///     u at its centre of mass, and the load N0 along side * w (towards the member);
///   - a contact of the body's centre of mass on the member point under it, normal
///     n = -side * w (from the member to the damper), tangent t = (n_y, -n_x) = -side * u, the
///     damper's friction law, side b moving with the sliding (X' = V, paper eq. 10) or fixed at X0.
/// Closed, the contact holds the body's motion along w on the member's, y_b = psi_w(X) . q, so the
/// body's equation along w is the paper's inertial normal N = N0 - s m y'' (eqs 23-24); along u it
/// is s m x'' + s k x = f (eqs 11-12). All forces act at the centre of mass: the rotation is
/// unloaded (theta'' = 0), its inertia a placeholder. The normal is unilateral (where N reaches
/// zero the contact opens and lands again, or the run stops), or held at N0 under a constant
/// normal load (point_damper_body's choices below).

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/model/body_contact.hpp>
#include <stickslip/model/model_options.hpp>
#include <stickslip/model/point_damper.hpp>
#include <stickslip/model/rigid_body.hpp>

#include <Eigen/Core>

#include <string>

namespace stickslip {

namespace detail {
/// SlipPositive <-> SlipNegative; other states unchanged.
inline ContactState mirrored_slip(ContactState s) noexcept {
  return s == ContactState::SlipPositive ? ContactState::SlipNegative
         : s == ContactState::SlipNegative ? ContactState::SlipPositive
                                            : s;
}
}  // namespace detail

/// The body and the contact of one PointDamper (point_damper_body).
template <class Scalar>
struct PointDamperBody {
  RigidBody<Scalar> body;       ///< mass s m, spring s k along u, load N0 along side * w
  BodyContact<Scalar> contact;  ///< its centre of mass on the member, unilateral normal
};

/// `damper` on `frame` as body number `body` of a ContactSystem scene and its contact, with the
/// choices FrictionDampedSystem would take from `options` (ModelOptions):
///   - a constant normal load (damper.normal_load or options.normal_load = Constant) holds the
///     contact's normal at N = N0 (ContactNormal::Held): the body is not coupled to the member
///     along w, its preload and the contact's N cancel on it, the member carries N0 at the contact;
///   - Separation::Stop stops the run where N reaches zero (at_lift_off = Stop), Separate opens
///     the contact and lands it with restitution e (its landing rule is the system's velocity
///     tolerance, not damper.landing_speed);
///   - options.moving_contact = false fixes the contact point at X0;
///   - a member end Default follows options.end_policy (Throw: Stop, Extrapolate: Extend), Stop
///     and Extend are kept.
/// \throws std::invalid_argument naming the parameter: a member not in the frame, the damper's
///         own checks (PointDamper::validate), a damper's preload of 0 under a constant normal
///         load, a member end that is a Wall or that extends under EndPolicy::Clamp,
///         options.convective_terms = false with a moving contact point, or
///         options.watch_lift_off = false under an inertial normal load (a body contact is
///         unilateral: its N never goes negative).
template <class Scalar, class Law>
PointDamperBody<Scalar> point_damper_body(const FrameModel<Scalar>& frame, Eigen::Index body,
                                          const PointDamper<Scalar, Law>& damper,
                                          const ModelOptions<Scalar>& options = {}) {
  static const std::string where = "point_damper_body";
  if (damper.member < 0 || damper.member >= frame.num_members())
    detail::throw_invalid(where, "damper.member must name a member of the frame", damper.member);
  damper.validate(0);
  const bool held = damper.normal_load == NormalLoad::Constant || options.normal_load == NormalLoad::Constant;
  const bool moving = damper.contact_point == ContactPoint::Moving && options.moving_contact;
  if (!held && !options.watch_lift_off)
    detail::throw_invalid(where, "options.watch_lift_off must be true under an inertial normal load (a body "
                                 "contact opens where N reaches zero)", 0);
  if (moving && !options.convective_terms)
    detail::throw_invalid(where, "options.convective_terms must be true with a moving contact point", 0);
  auto end = [&](MemberEnd e, const char* name) {
    if (e == MemberEnd::Default)
      e = options.end_policy == EndPolicy::Throw ? MemberEnd::Stop : MemberEnd::Extend;
    if (e == MemberEnd::Wall)
      detail::throw_invalid(where, std::string("damper.") + name + " = Wall is not available on a body contact",
                            static_cast<int>(e));
    if (e == MemberEnd::Extend && options.end_policy == EndPolicy::Clamp)
      detail::throw_invalid(where, std::string("damper.") + name +
                                       " extends under options.end_policy = Clamp (a body contact extrapolates)",
                            static_cast<int>(e));
    return e;
  };
  const MemberEnd start_end = end(damper.start_end, "start_end"), finish_end = end(damper.finish_end, "finish_end");
  if (held) detail::require_positive(where, "damper.preload (a constant normal load)", damper.preload);
  const auto& member = frame.member(damper.member);
  const Scalar ux = member.cos, uy = member.sin, sd = damper.side;
  PointDamperBody<Scalar> out;
  RigidBody<Scalar>& b = out.body;
  b.mass = damper.effective_mass();
  b.inertia = damper.effective_mass() * Scalar(1e-4);  // (1 cm)^2: any positive value, theta is unloaded
  b.springs.push_back(BodySpring<Scalar>{Eigen::Matrix<Scalar, 2, 1>::Zero(), {ux, uy}, damper.effective_stiffness(),
                                         Scalar(0)});
  b.loads.push_back(BodyLoad<Scalar>{{-sd * uy, sd * ux}, damper.preload, {}});
  const PlaneDirection<Scalar> n{sd * uy, -sd * ux};  // -side * w
  out.contact = BodyContact<Scalar>::on_structure({body, Eigen::Matrix<Scalar, 2, 1>::Zero()},
                                                  StructurePoint<Scalar>{damper.member, damper.contact_coordinate}, n,
                                                  FrictionLawVariant<Scalar>(damper.law), damper.restitution);
  out.contact.contact_point = moving ? ContactPoint::Moving : ContactPoint::Fixed;
  // t = -side u: a slip state of the damper (sign of V along u) is the body's mirrored for side +1.
  out.contact.initial_state = sd > 0 ? detail::mirrored_slip(damper.initial_state) : damper.initial_state;
  out.contact.at_lift_off = damper.separation;
  out.contact.start_end = start_end;
  out.contact.finish_end = finish_end;
  if (held) {
    out.contact.normal_behaviour = ContactNormal::Held;
    out.contact.held_normal_force = damper.preload;
  }
  return out;
}

}  // namespace stickslip

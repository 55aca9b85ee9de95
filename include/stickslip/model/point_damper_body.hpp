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
/// unloaded (theta'' = 0), its inertia a placeholder. The normal is unilateral: where N reaches
/// zero the contact opens and lands again (PointDamper's Separation::Separate with restitution e).

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/model/body_contact.hpp>
#include <stickslip/model/point_damper.hpp>
#include <stickslip/model/rigid_body.hpp>

#include <Eigen/Core>

#include <string>

namespace stickslip {

/// The body and the contact of one PointDamper (point_damper_body).
template <class Scalar>
struct PointDamperBody {
  RigidBody<Scalar> body;       ///< mass s m, spring s k along u, load N0 along side * w
  BodyContact<Scalar> contact;  ///< its centre of mass on the member, unilateral normal
};

/// `damper` on `frame` as body number `body` of a ContactSystem scene and its contact.
/// \throws std::invalid_argument naming the parameter: a member not in the frame, the damper's
///         own checks (PointDamper::validate), a constant normal load (the body's normal force is
///         the contact's unknown, always inertial), a member end other than Default (a moving
///         contact point stops the run at a member end) or walls.
template <class Scalar, class Law>
PointDamperBody<Scalar> point_damper_body(const FrameModel<Scalar>& frame, Eigen::Index body,
                                          const PointDamper<Scalar, Law>& damper) {
  static const std::string where = "point_damper_body";
  if (damper.member < 0 || damper.member >= frame.num_members())
    detail::throw_invalid(where, "damper.member must name a member of the frame", damper.member);
  damper.validate(0);
  if (damper.normal_load != NormalLoad::Inertial)
    detail::throw_invalid(where, "damper.normal_load must be Inertial (a body's normal force is inertial)",
                          static_cast<int>(damper.normal_load));
  if (damper.start_end != MemberEnd::Default || damper.finish_end != MemberEnd::Default)
    detail::throw_invalid(where, "damper.start_end and finish_end must be Default (the run stops at a member end)",
                          static_cast<int>(damper.start_end != MemberEnd::Default ? damper.start_end : damper.finish_end));
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
  out.contact.contact_point = damper.contact_point;
  out.contact.initial_state = damper.initial_state;
  return out;
}

}  // namespace stickslip

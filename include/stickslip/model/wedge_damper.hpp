#pragma once
/// \file wedge_damper.hpp
/// \brief A rigid wedge damper between two platforms: one body with two flat faces at given
/// angles, pressed by its centrifugal load, each face touching a platform point (or ground) at
/// one or two contact points (docs/contacts.md, "The wedge damper").
///
/// With the load along the radial unit direction e (the body's load P e at its centre of mass),
/// the outward normal of the left face is e turned counter-clockwise by its angle a_l, that of
/// the right face e turned clockwise by a_r: for e = +Y, (-sin a_l, cos a_l) and (sin a_r, cos a_r).
/// Each contact's normal n (from the platform into the damper) is minus the face's outward
/// normal, its tangent t = (n_y, -n_x) runs along the face. A face with half_width w > 0 touches
/// at the two points p -+ w t (it can rock onto either), with w = 0 at p alone.

#include <stickslip/model/body_contact.hpp>
#include <stickslip/model/rigid_body.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace stickslip {

/// One flat face of a wedge damper.
template <class Scalar>
struct WedgeFace {
  /// The platform's material points it touches: none, ground; one, every contact point of the
  /// face on it; two, the points under p - w t and p + w t (two contact points of one face stuck
  /// on one material point constrain the body's rotation twice: their rows are dependent).
  std::vector<StructurePoint<Scalar>> platform;
  Eigen::Matrix<Scalar, 2, 1> point = Eigen::Matrix<Scalar, 2, 1>::Zero();  ///< p on the face, body coordinates [m]
  Scalar angle = Scalar(0);       ///< face angle from the plane normal to the load [rad], in (-pi/2, pi/2)
  Scalar half_width = Scalar(0);  ///< w >= 0: 0 one contact point, > 0 two at p +- w t [m]
};

/// The body and the contacts of a wedge damper, to pass to ContactSystem.
template <class Scalar>
struct WedgeDamper {
  RigidBody<Scalar> body;                      ///< the damper (its centrifugal load included)
  std::vector<BodyContact<Scalar>> contacts;   ///< left face's contacts first, then the right face's
};

/// A wedge damper: body `body` of the scene (its index, used by the contacts) with mass m,
/// rotary inertia J and the load `preload` [N] (m r Omega^2) along `radial`, faces `left` and
/// `right`, friction law `law` and restitution e on every contact.
/// \throws std::invalid_argument naming the parameter: a face angle outside (-pi/2, pi/2), a
///         negative or non-finite half width or preload, more than two platform points, two with
///         a zero half width, a radial direction that is not a unit vector (mass, inertia and the
///         contacts are checked by ContactSystem).
template <class Scalar>
WedgeDamper<Scalar> wedge_damper(Eigen::Index body, Scalar mass, Scalar inertia, Scalar preload,
                                 const WedgeFace<Scalar>& left, const WedgeFace<Scalar>& right,
                                 FrictionLawVariant<Scalar> law,
                                 PlaneDirection<Scalar> radial = PlaneDirection<Scalar>::global_y(),
                                 Scalar restitution = Scalar(0)) {
  static const std::string where = "wedge_damper";
  using std::atan2;
  radial.validate(where, "radial");
  detail::require_non_negative(where, "preload", preload);
  WedgeDamper<Scalar> w;
  w.body.mass = mass;
  w.body.inertia = inertia;
  w.body.loads.push_back(BodyLoad<Scalar>{radial, preload, {}});
  const Scalar half_pi = Scalar(std::acos(-1.0) / 2), radial_angle = atan2(radial.y, radial.x);
  auto add_face = [&](const WedgeFace<Scalar>& face, const char* name, Scalar turn) {
    const std::string w_name = std::string(name);
    detail::require_finite(where, (w_name + ".angle").c_str(), face.angle);
    if (!(std::abs(face.angle) < half_pi))
      detail::throw_invalid(where, w_name + ".angle must lie in (-pi/2, pi/2)", face.angle);
    detail::require_non_negative(where, (w_name + ".half_width").c_str(), face.half_width);
    const PlaneDirection<Scalar> outward = PlaneDirection<Scalar>::at_angle(radial_angle + turn * face.angle);
    const PlaneDirection<Scalar> n{-outward.x, -outward.y};
    const Eigen::Matrix<Scalar, 2, 1> t(n.y, -n.x);
    if (face.platform.size() > 2)
      detail::throw_invalid(where, w_name + ".platform must hold at most two points", face.platform.size());
    if (face.platform.size() == 2 && !(face.half_width > Scalar(0)))
      detail::throw_invalid(where, w_name + ".half_width must be > 0 with two platform points", face.half_width);
    auto contact_at = [&](const Eigen::Matrix<Scalar, 2, 1>& p, std::size_t k) {
      const BodyPoint<Scalar> at{body, p};
      if (face.platform.empty())
        w.contacts.push_back(BodyContact<Scalar>::on_ground(at, n, law, restitution));
      else
        w.contacts.push_back(BodyContact<Scalar>::on_structure(
            at, face.platform[std::min(k, face.platform.size() - 1)], n, law, restitution));
    };
    if (face.half_width > Scalar(0)) {
      contact_at(face.point - face.half_width * t, 0);
      contact_at(face.point + face.half_width * t, 1);
    } else {
      contact_at(face.point, 0);
    }
  };
  add_face(left, "left", Scalar(1));
  add_face(right, "right", Scalar(-1));
  return w;
}

}  // namespace stickslip

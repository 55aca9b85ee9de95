#pragma once
/// \file newton_impact.hpp
/// \brief Impact of a contact that closes again (ContactState::Separated, gap = 0): Newton's
/// restitution on the relative normal velocity with the impulse through the coupled system, the
/// rule that ends a sequence of accumulating bounces, and the tangential impulse by Coulomb's law
/// for impulses, alone (decoupled directions) or with the normal and tangential directions coupled
/// through the inverse effective mass (frictional_impact). docs/contact.md, "Separation and
/// impact".

#include <stickslip/contact/contact_state.hpp>
#include <stickslip/contact/friction_law.hpp>
#include <stickslip/detail/validate.hpp>

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <string>
#include <type_traits>

namespace stickslip {

/// Outcome of NewtonImpact::impact: the normal impulse and what it does.
template <class Scalar>
struct NormalImpact {
  /// Normal impulse on the body, >= 0 (force x time; the surface receives -impulse).
  Scalar impulse = Scalar(0);
  /// Relative normal velocity after the impact: -e v_n (bounce), max(v_n, 0) (landing).
  Scalar velocity_after = Scalar(0);
  /// Kinetic energy of the relative motion lost in the impact, (v_n^2 - velocity_after^2)/(2 W).
  Scalar energy_loss = Scalar(0);
  /// True: the contact closes for good (persistent contact); false: the body bounces off.
  bool lands = false;
};

/// Newton's impact law with a landing rule, for a contact whose relative normal velocity is
/// v_n = (velocity of the body - velocity of the surface) . normal (< 0 approaching) and whose
/// inverse effective mass is W = G M^-1 G^T > 0 (G: the contact's row of the constraint Jacobian,
/// M: the mass matrix; a point mass m on a surface of prescribed motion: W = 1/m; a damper of mass
/// m_d on a modal member: W = 1/m_d + psi_w^T psi_w). The impulse L obeys
///
///   W L = v_after - v_n,   v_after = -e v_n   (bounce, v_n < -landing_speed and e > 0),
///   v_after = max(v_n, 0)                      (landing: e = 0 or v_n >= -landing_speed).
///
/// The landing rule ends the Zeno sequence of bounces of e < 1: the impact velocities of a body
/// pressed onto a surface fall geometrically (e^k v_1), so the sequence reaches landing_speed after
/// finitely many bounces, and the remaining, infinitely many bounces (total duration
/// 2 landing_speed e / (a (1 - e)) under a constant pressing acceleration a) are replaced by a
/// plastic landing. With e = 0 every impact lands; with e = 1 and landing_speed = 0 every impact
/// bounces and conserves the energy of the relative motion.
template <class Scalar_>
class NewtonImpact {
 public:
  /// Floating-point type.
  using Scalar = Scalar_;

  /// \param restitution Newton's coefficient e in [0, 1]: v_after = -e v_n
  /// \param landing_speed an impact with |v_n| <= landing_speed lands (persistent contact), in
  ///        the model's velocity unit; >= 0. Choose it well below the impact speeds of interest
  ///        and large enough that the last flight, 2 e landing_speed / a, spans several event time
  ///        tolerances (a: the acceleration pressing the body onto the surface).
  /// \throws std::invalid_argument if restitution is outside [0, 1] or landing_speed is negative
  ///         or non-finite.
  NewtonImpact(Scalar restitution, Scalar landing_speed)
      : restitution_(restitution), landing_speed_(landing_speed) {
    detail::require_non_negative("NewtonImpact", "restitution", restitution);
    if (!(restitution <= Scalar(1)))
      detail::throw_invalid("NewtonImpact", "restitution must be in [0, 1]", restitution);
    detail::require_non_negative("NewtonImpact", "landing_speed", landing_speed);
  }

  /// Newton's coefficient of restitution e.
  Scalar restitution() const noexcept { return restitution_; }
  /// Impacts at or below this approach speed land.
  Scalar landing_speed() const noexcept { return landing_speed_; }

  /// True when an impact at relative normal velocity v_n lands: e = 0 or v_n >= -landing_speed.
  bool lands(Scalar v_n) const noexcept {
    return restitution_ == Scalar(0) || v_n >= -landing_speed_;
  }

  /// The impact at relative normal velocity v_n through inverse effective mass W (see the class).
  /// \param v_n relative normal velocity before the impact (< 0: approaching)
  /// \param inverse_mass W = G M^-1 G^T > 0
  /// \throws std::invalid_argument if v_n is non-finite or inverse_mass is not finite and > 0.
  NormalImpact<Scalar> impact(Scalar v_n, Scalar inverse_mass) const {
    using std::max;
    detail::require_finite("NewtonImpact::impact", "v_n", v_n);
    detail::require_positive("NewtonImpact::impact", "inverse_mass", inverse_mass);
    NormalImpact<Scalar> r;
    r.lands = lands(v_n);
    r.velocity_after = r.lands ? max(v_n, Scalar(0)) : -restitution_ * v_n;
    r.impulse = (r.velocity_after - v_n) / inverse_mass;
    r.energy_loss = impact_energy_loss(v_n, r.velocity_after, inverse_mass);
    return r;
  }

  /// Kinetic energy lost by an impulse that changes a contact velocity from v_before to v_after
  /// through inverse effective mass W: (v_before^2 - v_after^2) / (2 W), i.e. minus the work
  /// L (v_before + v_after) / 2 of the impulse L = (v_after - v_before) / W on the relative
  /// motion (the change of q'^T M q' / 2 when the surface is at rest; relative to a surface of
  /// prescribed velocity v_s the body's kinetic energy changes by L v_s more, the surface's work).
  static Scalar impact_energy_loss(Scalar v_before, Scalar v_after, Scalar inverse_mass) {
    return (v_before * v_before - v_after * v_after) / (Scalar(2) * inverse_mass);
  }

 private:
  Scalar restitution_;
  Scalar landing_speed_;
};

/// Outcome of coulomb_impulse: the tangential impulse of an impact and what it does.
template <class Scalar>
struct TangentialImpact {
  /// Tangential impulse on the body along the slip axis.
  Scalar impulse = Scalar(0);
  /// Sliding velocity after the impact: 0 (stick) or v_t + W_t impulse (slip, same sign as v_t).
  Scalar velocity_after = Scalar(0);
  /// Kinetic energy lost to friction in the impact, (v_t^2 - velocity_after^2) / (2 W_t).
  Scalar energy_loss = Scalar(0);
  /// Stick when the impulse stopped the sliding, else the slip state of sgn(v_t).
  ContactState state = ContactState::Stick;
};

/// Tangential impulse of an impact with normal impulse L_n >= 0, by Coulomb's law for impulses
/// (the impulse form of eq. 1; Pfeiffer & Glocker, Multibody Dynamics with Unilateral Contacts,
/// Wiley 1996; Brogliato, Nonsmooth Mechanics, Springer 2016):
///
///   L_stick = -v_t / W_t;  |L_stick| <= mu_s L_n  ->  L_t = L_stick, v_t after = 0 (stick)
///                          otherwise              ->  L_t = -mu_k(|v_t|) L_n sgn(v_t) (slip)
///
/// v_t is the sliding velocity before the impact and W_t > 0 the tangential inverse effective
/// mass. The law assumes the normal and tangential directions decoupled (W_nt = 0: the tangential
/// impulse does not change the normal velocity), as for a point mass on a flat surface. A sliding
/// impulse does not reverse the slip (mu_k <= mu_s), so the energy loss is >= 0. Exact laws only.
/// \param law the friction law (has_stick_state)
/// \param v_t sliding velocity of the body relative to the surface before the impact
/// \param inverse_mass_t tangential inverse effective mass W_t > 0
/// \param normal_impulse the impact's normal impulse L_n >= 0 (NormalImpact::impulse)
/// \throws std::invalid_argument if v_t is non-finite, inverse_mass_t is not finite and > 0, or
///         normal_impulse is negative or non-finite.
template <class Law, std::enable_if_t<is_friction_law_v<Law> && Law::has_stick_state, int> = 0>
TangentialImpact<typename Law::Scalar> coulomb_impulse(const Law& law, typename Law::Scalar v_t,
                                                       typename Law::Scalar inverse_mass_t,
                                                       typename Law::Scalar normal_impulse) {
  using Scalar = typename Law::Scalar;
  using std::abs;
  detail::require_finite("coulomb_impulse", "v_t", v_t);
  detail::require_positive("coulomb_impulse", "inverse_mass_t", inverse_mass_t);
  detail::require_non_negative("coulomb_impulse", "normal_impulse", normal_impulse);
  TangentialImpact<Scalar> r;
  const Scalar stick_impulse = -v_t / inverse_mass_t;
  if (abs(stick_impulse) <= law.static_coefficient() * normal_impulse) {
    r.impulse = stick_impulse;
    r.velocity_after = Scalar(0);
    r.state = ContactState::Stick;
  } else {
    r.state = slip_state(v_t);
    r.impulse = -Scalar(slip_sign(r.state)) * law.kinetic_coefficient(abs(v_t)) * normal_impulse;
    r.velocity_after = v_t + inverse_mass_t * r.impulse;
  }
  r.energy_loss = NewtonImpact<Scalar>::impact_energy_loss(v_t, r.velocity_after, inverse_mass_t);
  return r;
}

/// Outcome of frictional_impact: normal and tangential impulses of one impact with the directions
/// coupled.
template <class Scalar>
struct FrictionalImpact {
  /// (normal, tangential) impulse on the body; normal >= 0.
  Eigen::Matrix<Scalar, 2, 1> impulse = Eigen::Matrix<Scalar, 2, 1>::Zero();
  /// (normal, tangential) relative velocity after the impact.
  Eigen::Matrix<Scalar, 2, 1> velocity_after = Eigen::Matrix<Scalar, 2, 1>::Zero();
  /// Kinetic energy lost, -impulse . (v_before + velocity_after) / 2.
  Scalar energy_loss = Scalar(0);
  /// True: persistent contact follows (NewtonImpact's landing rule).
  bool lands = false;
  /// Stick when the tangential impulse stopped the sliding, else the slip state after.
  ContactState state = ContactState::Stick;
  /// False when neither stick nor a slip direction satisfies Newton's and Coulomb's laws
  /// together (then impulse is zero); not met in 200 000 random positive definite W, v, e, mu
  /// (a sampling, not a proof), kept so that a model can report it rather than go on.
  bool resolved = true;
};

/// One impact with friction when the tangential impulse also changes the normal velocity (and the
/// normal impulse the sliding velocity): the relative velocities v = (v_n, v_t) change by
/// W L with the symmetric positive definite 2 x 2 inverse effective mass W = G M^-1 G^T of the
/// contact's normal and tangential rows G (a damper of mass m on a modal member:
/// W = I/m + [psi_w psi_u]^T [psi_w psi_u], psi in mass-normalised modes). Newton's law on the
/// normal velocity (v_n after = -e v_n, or the landing rule of NewtonImpact) and Coulomb's law for
/// impulses (the rule of coulomb_impulse) are solved together:
///
///   stick:  W L = (v_n^+ - v_n, -v_t),   accepted if L_n >= 0 and |L_t| <= mu_s L_n;
///   slip s: L_t = -s mu_k(|v_t|) L_n,  (W_nn - s mu_k W_nt) L_n = v_n^+ - v_n,
///           accepted if W_nn - s mu_k W_nt > 0 and s v_t^+ >= 0 (the slip does not reverse),
///
/// trying s = sgn v_t first (sgn of the stick impulse's opposite when v_t = 0), then -s. With
/// W_nt = 0 this is NewtonImpact::impact followed by coulomb_impulse. When v_n >= 0 (no approach)
/// no impulse acts. Newton's kinematic restitution with coupled friction may create energy
/// (Stronge, Impact Mechanics, Cambridge 2000, ch. 4): energy_loss is then negative and reported
/// as such.
/// \param newton Newton's law and landing rule for the normal direction
/// \param law the friction law (has_stick_state)
/// \param W inverse effective mass, rows/columns (normal, tangential): symmetric, positive definite
/// \param v relative velocity before the impact: (v_n, v_t), v_n < 0 approaching
/// \throws std::invalid_argument if v or W is non-finite, W is not symmetric or not positive
///         definite.
template <class Law, std::enable_if_t<is_friction_law_v<Law> && Law::has_stick_state, int> = 0>
FrictionalImpact<typename Law::Scalar> frictional_impact(
    const NewtonImpact<typename Law::Scalar>& newton, const Law& law,
    const Eigen::Matrix<typename Law::Scalar, 2, 2>& W,
    const Eigen::Matrix<typename Law::Scalar, 2, 1>& v) {
  using Scalar = typename Law::Scalar;
  using Vec2 = Eigen::Matrix<Scalar, 2, 1>;
  using std::abs;
  static const std::string where = "frictional_impact";
  detail::require_finite(where, "v_n", v[0]);
  detail::require_finite(where, "v_t", v[1]);
  if (!detail::all_finite(W)) detail::throw_invalid(where, "W must be finite", W.sum());
  if (!(W(0, 1) == W(1, 0)))
    detail::throw_invalid(where, "W must be symmetric: W(0,1) = W(1,0)", W(0, 1) - W(1, 0));
  if (!(W(0, 0) > Scalar(0) && W.determinant() > Scalar(0)))
    detail::throw_invalid(where, "W must be positive definite (W(0,0) > 0, det W > 0)",
                          W.determinant());
  FrictionalImpact<Scalar> r;
  r.lands = newton.lands(v[0]);
  if (!(v[0] < Scalar(0))) {  // not approaching: no impulse
    r.velocity_after = v;
    r.state = v[1] != Scalar(0) ? slip_state(v[1]) : ContactState::Stick;
    return r;
  }
  const Scalar v_n_after = r.lands ? Scalar(0) : -newton.restitution() * v[0];
  const Scalar dv_n = v_n_after - v[0];
  auto finish = [&](const Vec2& L, ContactState state) {
    r.impulse = L;
    r.velocity_after = v + W * L;
    r.velocity_after[0] = v_n_after;  // exact by construction; avoids round-off of W L
    if (state == ContactState::Stick) r.velocity_after[1] = Scalar(0);
    r.energy_loss = -L.dot(v + r.velocity_after) / Scalar(2);
    r.state = state;
    return r;
  };
  const Vec2 stick = W.inverse() * Vec2(dv_n, -v[1]);
  if (stick[0] >= Scalar(0) && abs(stick[1]) <= law.static_coefficient() * stick[0])
    return finish(stick, ContactState::Stick);
  const Scalar mu = law.kinetic_coefficient(abs(v[1]));
  const Scalar first = v[1] != Scalar(0) ? (v[1] > 0 ? Scalar(1) : Scalar(-1))
                                         : (stick[1] > 0 ? Scalar(-1) : Scalar(1));
  for (Scalar s : {first, -first}) {
    const Scalar d = W(0, 0) - s * mu * W(0, 1);
    if (!(d > Scalar(0))) continue;
    const Scalar L_n = dv_n / d;
    const Vec2 L(L_n, -s * mu * L_n);
    const Scalar v_t_after = v[1] + W(1, 0) * L[0] + W(1, 1) * L[1];
    if (s * v_t_after >= Scalar(0)) return finish(L, slip_state(s));
  }
  r.resolved = false;
  r.velocity_after = v;
  return r;
}

}  // namespace stickslip

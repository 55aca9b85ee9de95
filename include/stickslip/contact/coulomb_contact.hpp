#pragma once
/// \file coulomb_contact.hpp
/// \brief The Coulomb contact state machine: friction force, guards, crossing directions and
/// transition decision of one friction contact, for any friction law (paper eq. 1, with the
/// time-varying normal force of eqs. 13-14 / 23-24 passed in by the model).
///
/// Conventions (docs/contact.md): v is the sliding velocity of the BODY relative to the
/// SURFACE; f is the force the surface exerts on the body along the slip axis; N is the normal
/// force (> 0 in contact); f_required is the force that would keep v' = 0 (the stick constraint
/// force), computed by the model. The state is held by the model and passed in.

#include <stickslip/contact/contact_state.hpp>
#include <stickslip/contact/friction_law.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/hybrid_system.hpp>

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

namespace stickslip {

/// State machine of one friction contact governed by `Law` (CoulombLaw, StribeckLaw,
/// RegularisedLaw or a user law satisfying is_friction_law_v). Stateless apart from the law and
/// a velocity tolerance, so one object serves every step and every contact with the same law.
template <class Law>
class CoulombContact {
  static_assert(is_friction_law_v<Law>,
                "CoulombContact<Law>: Law needs `using Scalar`, `static constexpr bool "
                "has_stick_state`, and either static_coefficient() + kinetic_coefficient(speed) "
                "(has_stick_state = true) or coefficient(v) + coefficient_derivative(v) "
                "(has_stick_state = false); see stickslip/contact/friction_law.hpp");

 public:
  /// The friction law (template parameter).
  using law_type = Law;
  /// Floating-point type of the law.
  using Scalar = typename Law::Scalar;
  /// True for exact laws (stick state, set-valued friction); false for regularised laws.
  static constexpr bool has_stick_state = Law::has_stick_state;
  /// Largest num_guards over all states (stick with lift-off watched).
  static constexpr Eigen::Index max_guards = 3;

  /// Default velocity tolerance sqrt(machine epsilon) (1.5e-8 for double), in the model's
  /// velocity unit: |v| at or below it counts as v = 0 in decide().
  static Scalar default_velocity_tolerance() {
    using std::sqrt;
    return sqrt(std::numeric_limits<Scalar>::epsilon());
  }

  /// \param velocity_tolerance |v| <= velocity_tolerance is "v = 0" in decide(); choose it above
  ///        the velocity overshoot of event location (|v'| times the event time tolerance) and
  ///        below any sliding speed that matters. It is not read when the contact's own velocity
  ///        guard fired: decide_at_rest() / velocity_guard_fired() take v = 0 as located.
  /// \param law the friction law: exact (stick state) or regularised
  /// \throws std::invalid_argument if velocity_tolerance is negative or non-finite.
  explicit CoulombContact(Law law, Scalar velocity_tolerance = default_velocity_tolerance())
      : law_(std::move(law)), velocity_tolerance_(velocity_tolerance) {
    detail::require_non_negative("CoulombContact", "velocity_tolerance", velocity_tolerance);
  }

  /// The friction law.
  const Law& law() const noexcept { return law_; }
  /// |v| at or below this counts as v = 0 in decide() (constructor argument).
  Scalar velocity_tolerance() const noexcept { return velocity_tolerance_; }

  /// Stick capacity mu_s N (force units); exact laws only.
  template <class L = Law, std::enable_if_t<L::has_stick_state, int> = 0>
  Scalar stick_capacity(Scalar N) const {
    return law_.static_coefficient() * N;
  }

  /// Friction force on the body (eq. 1): slip -mu_k(|v|) N sgn(state); stick f_required;
  /// lift-off and separated 0. Regularised laws: -coefficient(v) N in every contact state.
  /// No checks (hot path): non-finite inputs propagate to the state for the stepper to report.
  Scalar friction_force(ContactState s, Scalar v, Scalar N, Scalar f_required) const {
    if (!is_in_contact(s)) return Scalar(0);
    if constexpr (has_stick_state) {
      using std::abs;
      if (s == ContactState::Stick) return f_required;
      const Scalar magnitude = law_.kinetic_coefficient(abs(v)) * N;
      return s == ContactState::SlipPositive ? -magnitude : magnitude;
    } else {
      return -law_.coefficient(v) * N;
    }
  }

  /// Number of guards in state s: stick 2, slip 1 (regularised laws 0), plus 1 for N when
  /// watch_lift_off; lift-off 1 (N, re-contact); separated 1 (the gap, impact).
  static Eigen::Index num_guards(ContactState s, bool watch_lift_off) noexcept {
    if (!is_in_contact(s)) return 1;
    return num_friction_guards(s) + (watch_lift_off ? 1 : 0);
  }

  /// Guard values g[0 .. num_guards(s, watch_lift_off)): stick g0 = mu_s N - f_required,
  /// g1 = mu_s N + f_required; slip g0 = v; then N when lift-off is watched; lift-off state
  /// g0 = N. Directions in guard_direction(). Not for Separated: its guard is the model's gap,
  /// written by gap_guard().
  void guards(ContactState s, Scalar v, Scalar N, Scalar f_required, bool watch_lift_off,
              Scalar* g) const {
    guards(s, v, N, [f_required] { return f_required; }, watch_lift_off, g);
  }

  /// As above, with the stick force required given by a callable `Scalar f_required()`, called
  /// in Stick only (slip and lift-off guards do not depend on it): for a caller whose f_required
  /// costs an evaluation of its own (an excitation, a constraint solve).
  template <class RequiredForce,
            std::enable_if_t<std::is_invocable_r_v<Scalar, RequiredForce&>, int> = 0>
  void guards(ContactState s, Scalar v, Scalar N, RequiredForce&& f_required,
              bool watch_lift_off, Scalar* g) const {
    STICKSLIP_ASSERT(s != ContactState::Separated &&
                     "CoulombContact::guards: a separated contact's guard is its gap (gap_guard)");
    if (s == ContactState::LiftOff) {
      g[0] = N;
      return;
    }
    const Eigen::Index n = num_friction_guards(s);
    if constexpr (has_stick_state) {
      if (s == ContactState::Stick) {
        const Scalar capacity = stick_capacity(N);
        const Scalar f = f_required();
        g[0] = capacity - f;
        g[1] = capacity + f;
      } else {
        g[0] = v;
      }
    }
    if (watch_lift_off) g[n] = N;
  }

  /// Guard of the Separated state: g0 = gap = y_body - y_surface (>= 0 while separated, in
  /// the model's length unit), Falling: the body reaches the surface (impact, NewtonImpact).
  static void gap_guard(Scalar gap, Scalar* g) noexcept { g[0] = gap; }

  /// True when the sliding-velocity guard of state s (slip: the contact's guard 0, at index
  /// `first` of the system's guard vector) is among the guards `which` that fired together. The
  /// stepper then hands over a state on v = 0 (to |v'| times its event time tolerance): the
  /// contact is at rest, and decide_at_rest() applies.
  static bool velocity_guard_fired(ContactState s, const TriggeredGuards& which,
                                   Eigen::Index first = 0) noexcept {
    if (!has_stick_state || !is_slipping(s)) return false;
    for (Eigen::Index i : which)
      if (i == first) return true;
    return false;
  }

  /// Crossing direction of guard i in state s: stick g0, g1 Falling (capacity exceeded; g0 leads
  /// to slip negative, g1 to slip positive); SlipPositive g0 Falling, SlipNegative g0 Rising;
  /// N Falling (lift-off); in the lift-off state N Rising (re-contact); in the separated state
  /// the gap Falling (impact).
  static CrossingDirection guard_direction(ContactState s, Eigen::Index i,
                                           bool watch_lift_off) noexcept {
    STICKSLIP_ASSERT(i >= 0 && i < num_guards(s, watch_lift_off));
    static_cast<void>(watch_lift_off);
    if (s == ContactState::LiftOff) return CrossingDirection::Rising;
    if (s == ContactState::Separated) return CrossingDirection::Falling;
    if (i == num_friction_guards(s)) return CrossingDirection::Falling;  // N, lift-off
    return s == ContactState::SlipNegative ? CrossingDirection::Rising : CrossingDirection::Falling;
  }

  /// Transition decision at an event (docs/contact.md, "Decision rules"), first match wins:
  ///  1. N <= 0                                  -> LiftOff (a model that lets the contact
  ///                                                open maps it to Separated)
  ///  2. |v| > velocity_tolerance                -> slip in sgn(v)
  ///  3. exact law, |f_stick_required| <= mu_s N -> Stick; regularised law -> Stick (label)
  ///  4. exact law                               -> slip in -sgn(f_stick_required)
  /// The rules are those of eq. 1 and depend on `from` through nothing else: a slip state
  /// reaching v = 0 sticks or reverses by rule 3/4, a stick state whose force leaves the
  /// capacity slips by rule 4, a lift-off state with N > 0 re-enters contact by rules 2-4.
  /// \throws std::invalid_argument if v, N or f_stick_required is non-finite.
  ContactState decide(ContactState from, Scalar v, Scalar N, Scalar f_stick_required) const {
    static_cast<void>(from);
    using std::abs;
    using std::isfinite;
    if (!(isfinite(v) && isfinite(N) && isfinite(f_stick_required))) {  // messages off the hot path
      detail::require_finite("CoulombContact::decide", "v", v);
      detail::require_finite("CoulombContact::decide", "N", N);
      detail::require_finite("CoulombContact::decide", "f_stick_required", f_stick_required);
    }
    if (!(N > Scalar(0))) return ContactState::LiftOff;
    if (abs(v) > velocity_tolerance_) return slip_state(v);
    return decide_at_rest(N, f_stick_required);
  }

  /// Decision for a contact at rest (v = 0 by construction: stuck, or a slip state whose
  /// velocity guard fired, see velocity_guard_fired): rules 1, 3, 4 of decide(); the leftover
  /// sliding velocity of event location is not read, so no velocity tolerance is involved.
  /// \throws std::invalid_argument if N or f_stick_required is non-finite.
  ContactState decide_at_rest(Scalar N, Scalar f_stick_required) const {
    using std::abs;
    using std::isfinite;
    if (!(isfinite(N) && isfinite(f_stick_required))) {
      detail::require_finite("CoulombContact::decide_at_rest", "N", N);
      detail::require_finite("CoulombContact::decide_at_rest", "f_stick_required",
                             f_stick_required);
    }
    if (!(N > Scalar(0))) return ContactState::LiftOff;
    if constexpr (has_stick_state) {
      if (abs(f_stick_required) <= stick_capacity(N)) return ContactState::Stick;
      return slip_state(-f_stick_required);
    } else {
      return ContactState::Stick;
    }
  }

 private:
  static Eigen::Index num_friction_guards(ContactState s) noexcept {
    if constexpr (!has_stick_state) {
      static_cast<void>(s);
      return 0;
    } else {
      return s == ContactState::Stick ? 2 : (is_slipping(s) ? 1 : 0);
    }
  }

  Law law_;
  Scalar velocity_tolerance_;
};

}  // namespace stickslip

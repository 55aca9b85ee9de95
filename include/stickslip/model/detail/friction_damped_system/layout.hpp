#pragma once
/// \file layout.hpp
/// \brief FrictionDampedSystem, the state layout: where each quantity lives in the state vector
/// (q | q' | x | x' | X | y_d, y_d' | audit integrals), the rest state, the checks of a state and a
/// mode, and the right-hand side dx/dt assembled in that layout from one Evaluation.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::initial_state() const -> State {
  State x = State::Zero(state_size());
  if (options_.moving_contact)
    for (Index i = 0; i < D_; ++i)
      x[contact_offset() + i] = dampers_[static_cast<std::size_t>(i)].contact_coordinate;
  return x;
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::requested_mode() const -> Mode {
  Mode m(D_);
  for (Index i = 0; i < D_; ++i) {
    const bool stick = has_stick_[static_cast<std::size_t>(i)];
    m[i] = stick ? dampers_[static_cast<std::size_t>(i)].initial_state : ContactState::SlipPositive;
  }
  return m;
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::validate_state(
    const Mode& mode, const State& x, const char* where) const {
  if (x.size() != state_size())
    throw std::invalid_argument(std::string(where) + ": state x has size " + std::to_string(x.size()) +
                                ", expected state_size() = " + std::to_string(state_size()));
  if (mode.size() != D_)
    throw std::invalid_argument(std::string(where) + ": mode (DamperStates) has " +
                                std::to_string(mode.size()) + " states, expected num_dampers() = " +
                                std::to_string(D_));
  for (Index i = 0; i < D_; ++i) {  // only a damper with Separation::Separate has a flight state
    if (!detail::is_enumerator(mode[i], ContactState::Separated))
      detail::require_enumerator(where, "mode[" + std::to_string(i) + "]", "ContactState", mode[i],
                                 ContactState::Separated);
    if (mode[i] == ContactState::LiftOff)  // the model stops there, or separates (Separated)
      throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) +
                                  "] is lift_off, which the model never runs in (a damper is in contact "
                                  "- stick, slip - or Separated)");
    if (mode[i] == ContactState::Separated && flight_slot_[static_cast<std::size_t>(i)] < 0)
      throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) +
                                  "] is separated, but damper " + std::to_string(i) +
                                  " cannot separate (PointDamper::separation = Stop, or a "
                                  "constant normal load, or lift-off not watched)");
  }
  if (has_walls_) validate_walls(mode, where);
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::validate_start(
    const Mode& mode, Scalar t0, const State& x0, const char* where, const char* t_name, const char* x_name) const {
  detail::require_finite(where, t_name, t0);
  validate_state(mode, x0, where);
  using std::isfinite;
  for (Index k = 0; k < x0.size(); ++k)
    if (!isfinite(x0[k]))
      detail::throw_invalid(where, std::string(x_name) + "[" + std::to_string(k) + "] must be finite", x0[k]);
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::rhs(const Mode& mode, Scalar t, const State& x, State& dxdt) {
  const Evaluation& e = evaluate(mode, t, x);
  dxdt.resize(x.size());
  linear_derivative(e, x, dxdt);
  if (options_.energy_audit) audit_rates(e, t, x, dxdt);
  if (!e.finite) dxdt.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
}

/// Derivative of the state's first linear_size() components from an evaluation:
/// (q', q'', x_d', x_d'', X') - the X rows only when a contact moves: X' = V for a moving
/// contact, 0 for a fixed one.
template <class Scalar_, class Law_, int Modes>
template <class Out>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::linear_derivative(
    const Evaluation& e, const State& x, Out& d) const {
  d.template segment<Modes>(0, n_) = x.template segment<Modes>(n_, n_);
  d.template segment<Modes>(n_, n_) = modal(e.qdd);
  d.segment(x_offset(), D_) = x.segment(xd_offset(), D_);
  d.segment(xd_offset(), D_) = e.xdd;
  if (options_.moving_contact)
    for (Index i = 0; i < D_; ++i)
      d[contact_offset() + i] = moving_[static_cast<std::size_t>(i)] ? e.V[i] : Scalar(0);
  flight_derivative(x, d);
}

/// The flight rows of the derivative: y_d' and y_d'' = N0 / m of a separated damper (its
/// preload pushes it towards the member, docs/model_separation.md "Separation"); 0 for a damper in
/// contact (its flight coordinates wait, unused, until a lift-off sets them). Uses flying_ of
/// the evaluation's solve.
template <class Scalar_, class Law_, int Modes>
template <class Out>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::flight_derivative(const State& x, Out& d) const {
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Index k = flight_slot_[iu];
    if (k < 0) continue;
    const Index y = flight_offset() + k, yd = y + num_separable_;
    d[y] = flying_[iu] ? x[yd] : Scalar(0);
    d[yd] = flying_[iu] ? dampers_[iu].preload / dampers_[iu].effective_mass() : Scalar(0);
  }
}

}  // namespace stickslip

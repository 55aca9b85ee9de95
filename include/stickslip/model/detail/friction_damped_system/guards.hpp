#pragma once
/// \file guards.hpp
/// \brief FrictionDampedSystem, guards: per damper its contact guards (stick: mu_s N -+ f,
/// slip: V, lift-off: N, flight: the gap) from the contact component, then the member-end guards
/// X and L - X; their count, values and crossing directions in the order the stepper sees them.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::num_guards(const Mode& mode) const -> Index {
  Index count = 0;
  for (Index i = 0; i < D_; ++i) count += guards_of(mode, i);
  return count;
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::guards(const Mode& mode, Scalar t, const State& x,
                                                               GuardVector& g) {
  const Evaluation& e = evaluate(mode, t, x);
  g.resize(num_guards(mode));
  fill_guards(mode, e, g.data());
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::guard_direction(
    const Mode& mode, Index idx) const -> CrossingDirection {
  for (Index i = 0; i < D_; ++i) {
    const Index nc = contact_guards_of(mode, i);
    if (idx < nc) {
      return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
        return CoulombContact<std::decay_t<decltype(law)>>::guard_direction(mode[i], idx,
                                                                            watch_lift_off(i));
      });
    }
    idx -= nc;
    if (end_guards_of(mode, i)) {
      if (idx < 2) return CrossingDirection::Falling;
      idx -= 2;
    }
  }
  STICKSLIP_ASSERT(false && "guard index out of range");
  return CrossingDirection::Either;
}

// Number of guards of damper i in mode: contact guards (from the contact component, incl.
// the lift-off guard when watched) followed by two member-end guards when they apply.
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::contact_guards_of(const Mode& mode, Index i) const -> Index {
  return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
    using L = std::decay_t<decltype(law)>;
    return CoulombContact<L>::num_guards(mode[i], watch_lift_off(i));
  });
}

/// Lift-off is watched for dampers whose normal force varies.
template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::watch_lift_off(Index i) const {
  return options_.watch_lift_off && inertial_[static_cast<std::size_t>(i)];
}

template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::end_guards_of(const Mode& mode, Index i) const {
  const std::size_t iu = static_cast<std::size_t>(i);
  if (!moving_[iu] || (end_kind_[iu][0] == MemberEnd::Extend && end_kind_[iu][1] == MemberEnd::Extend)) return false;
  return !has_stick_[static_cast<std::size_t>(i)] || detail::is_slipping(mode[i]) ||
         mode[i] == ContactState::Separated;
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::guards_of(const Mode& mode, Index i) const -> Index {
  return contact_guards_of(mode, i) + (end_guards_of(mode, i) ? 2 : 0);
}

/// The guards of `mode` from an evaluation, into g[0 .. num_guards(mode)): per damper its
/// contact guards (CoulombContact::guards), then X and L - X when end_guards_of.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::fill_guards(const Mode& mode, const Evaluation& e,
                                                                    Scalar* g) const {
  Index k = 0;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Index nc = contact_guards_of(mode, i);
    if (mode[i] == ContactState::Separated)
      CoulombContact<CoulombLaw<Scalar>>::gap_guard(e.gap[i], g + k);
    else if (nc > 0)
      detail::with_law(dampers_[iu].law, [&](const auto& law) {
        CoulombContact<std::decay_t<decltype(law)>> contact(law);
        contact.guards(mode[i], e.V[i], e.N[i], e.f[i] + e.wall_force[i], watch_lift_off(i), g + k);
      });
    if (has_walls_ && mode[i] == ContactState::Stick && mode.wall(i) != WallRest::None)
      rest_guard(mode.wall(i), e.N[i], g + k);
    k += nc;
    if (end_guards_of(mode, i)) {
      const Scalar L = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
      // (an end that extends keeps a constant guard, so that the guard count stays two)
      g[k++] = end_kind_[iu][0] != MemberEnd::Extend ? e.X[i] : Scalar(1);
      g[k++] = end_kind_[iu][1] != MemberEnd::Extend ? L - e.X[i] : Scalar(1);
      if (has_walls_ && mode[i] == ContactState::Separated) hold_guard(
          mode.wall(i), e.f[i] + e.wall_force[i], g + k - 2);
    }
  }
}

}  // namespace stickslip

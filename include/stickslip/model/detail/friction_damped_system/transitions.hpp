#pragma once
/// \file transitions.hpp
/// \brief FrictionDampedSystem, transitions: what an event does to the mode and the state.
/// transition() sorts the triggered guards (member ends, impacts, lift-offs, stick/slip switches),
/// hands impacts and separations to the separation and wall rooms, then resolve() picks a
/// consistent stick/slip state for all dampers together; make_consistent() does the same at t0.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::transition(Mode& mode, const TriggeredGuards& triggered,
                                                            Scalar t, State& x) -> TransitionAction {
  std::vector<Index>& involved = involved_;
  involved.clear();
  lifting_.clear();
  impacting_.clear();
  wall_hits_.clear();
  for (Index idx : triggered) {
    Index i = 0, local = idx;
    for (; i < D_; ++i) {
      const Index nc = guards_of(mode, i);
      if (local < nc) break;
      local -= nc;
    }
    STICKSLIP_ASSERT(i < D_);
    const Index nc = contact_guards_of(mode, i);
    if (local >= nc) {  // a member end: a wall reflects, else the run stops
      const int end = static_cast<int>(local - nc);
      if (mode[i] == ContactState::Separated && mode.wall(i) == (end == 0 ? WallRest::Start : WallRest::Finish)) {
        mode.set_wall(i, WallRest::None);  // held in flight: the wall's reaction reached zero, it leaves
        cache_valid_ = false;
        continue;
      }
      if (end_kind_[static_cast<std::size_t>(i)][static_cast<std::size_t>(end)] != MemberEnd::Wall)
        return stop(StopReason::LeftMember, i, t, x, mode);
      wall_hits_.emplace_back(i, end);
      continue;
    }
    if (mode[i] == ContactState::Separated) {  // the gap closed: an impact
      impacting_.push_back(i);
      continue;
    }
    const bool lift = watch_lift_off(i) && local == nc - 1;
    if (lift && flight_slot_[static_cast<std::size_t>(i)] < 0) return stop(StopReason::LiftOff, i, t, x, mode);
    if (lift) {
      lifting_.push_back(i);
      continue;
    }
    if (std::find(involved.begin(), involved.end(), i) == involved.end()) involved.push_back(i);
  }
  if (!separation_transition(mode, t, x))
    return stop(StopReason::NoConsistentState, impacting_.front(), t, x, mode);
  // The new states leave no damper in contact with N <= 0 (one switch changes the accelerations
  // and so the normal forces of the others): a damper that may separate leaves the member, one
  // that may not stops the run at its lift-off.
  const bool consistent = resolve(mode, involved, t, x) && separate_unpressed(mode, t, x);
  if (has_walls_) release_pulled_holds(mode, t, x);
  forget_left_walls(mode);
  if (!consistent)
    return stop(StopReason::NoConsistentState, involved.empty() ? 0 : involved.front(), t, x, mode);
  const Index lifted = unpressed_contact(mode, t, x);
  return lifted < 0 ? TransitionAction::proceed() : stop(StopReason::LiftOff, lifted, t, x, mode);
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::make_consistent(Mode& mode, Scalar t, State& x) -> bool {
  validate_start(mode, t, x, "FrictionDampedSystem::make_consistent", "t", "x");
  std::vector<Index>& involved = involved_;
  involved.clear();
  for (Index i = 0; i < D_; ++i)
    if (mode[i] == ContactState::Stick) involved.push_back(i);
  const long load_faults = load_fault_.count;
  const bool resolved = resolve(mode, involved, t, x);
  if (load_fault_.count != load_faults && load_fault_.t == t) {  // F_l(t0) is not finite: no start
    stop(StopReason::NonFiniteLoad, load_fault_.load, t, x, mode);
    return false;
  }
  if (!resolved) return false;
  {
    const Evaluation& e = evaluate(mode, t, x);
    for (Index i = 0; i < D_; ++i) {
      // A constant normal load N0 = 0 never presses an exact-law damper: no contact, ever.
      const std::size_t iu = static_cast<std::size_t>(i);
      const bool unpressed = !inertial_[iu] && has_stick_[iu];
      if (mode[i] == ContactState::Separated || flight_slot_[iu] >= 0) continue;  // below
      if ((watch_lift_off(i) || unpressed) && !(e.N[i] > Scalar(0))) {
        stop(StopReason::LiftOff, i, t, x, mode);
        return false;
      }
    }
  }
  // Dampers that may separate: those without a positive normal force leave the member at t0.
  const bool consistent = separate_unpressed(mode, t, x);
  if (has_walls_) release_pulled_holds(mode, t, x);
  forget_left_walls(mode);
  return consistent;
}

/// Picks consistent states for the dampers in `involved` (and any stuck damper whose capacity
/// the new states exceed): each is tried stuck first; those whose required stick force exceeds
/// mu_s N slip in the direction of the excess force. Bounded fixed-point iteration.
template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::resolve(Mode& mode, std::vector<Index>& involved, Scalar t,
                                                                State& x) {
  const Mode before = mode;
  for (Index i : involved)
    if (has_stick_[static_cast<std::size_t>(i)]) mode[i] = ContactState::Stick;
  bool consistent = false;
  for (int iter = 0; iter < 4 * static_cast<int>(D_) + 4 && !consistent; ++iter) {
    set_stuck_velocities(mode, x);
    cache_valid_ = false;
    const Evaluation& e = evaluate(mode, t, x);
    if (!e.finite) {  // a blown-up state: no states to choose; the stepper's finiteness check
      mode = before;  // after the transition reports it (Status::NonFiniteState)
      consistent = true;
      break;
    }
    consistent = true;
    for (Index i = 0; i < D_; ++i) {
      if (!has_stick_[static_cast<std::size_t>(i)] || mode[i] != ContactState::Stick) continue;
      const ContactState next = detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) {
        CoulombContact<std::decay_t<decltype(law)>> contact(law);
        return contact.decide(ContactState::Stick, Scalar(0), e.N[i], e.f[i]);
      });
      if (next == ContactState::LiftOff) continue;  // reported by the lift-off guard / check
      if (next != ContactState::Stick && has_walls_ && rest_at_wall(mode, i, next, x)) {
        consistent = false;
        break;  // re-solve with the wall holding it
      }
      if (next != ContactState::Stick) {
        mode[i] = next;
        consistent = false;
        if (std::find(involved.begin(), involved.end(), i) == involved.end()) involved.push_back(i);
        break;  // re-solve: one switch can relieve the others
      }
    }
  }
  cache_valid_ = false;
  for (Index i = 0; i < D_; ++i)
    if (before[i] != mode[i]) events_.push_back(ContactEvent{t, i, before[i], mode[i]});
  return consistent;
}

/// Enforce V_i = 0 exactly for stuck dampers: x_i' = q'^T psi_u(X_i). Only the stuck dampers'
/// shapes are evaluated (and then kept for the solve that follows: X is unchanged); slipping
/// ones are formed in element space by the solve.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::set_stuck_velocities(const Mode& mode, State& x) {
  const auto qd = x.segment(n_, n_);
  for (Index i = 0; i < D_; ++i) {
    if (!has_stick_[static_cast<std::size_t>(i)] || mode[i] != ContactState::Stick) continue;
    if (moving_[static_cast<std::size_t>(i)]) evaluate_shapes(i, x[contact_offset() + i]);
    x[xd_offset() + i] = qd.dot(C_.col(D_ + i));
  }
}

/// The first damper in contact whose lift-off is watched and that may not separate, with
/// N <= 0 at (mode, t, x); -1 when there is none.
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::unpressed_contact(
    const Mode& mode, Scalar t, const State& x) -> Index {
  const Evaluation& e = evaluate(mode, t, x);
  for (Index i = 0; i < D_; ++i)
    if (watch_lift_off(i) && flight_slot_[static_cast<std::size_t>(i)] < 0 && mode[i] != ContactState::Separated &&
        e.finite && !(e.N[i] > Scalar(0)))
      return i;
  return -1;
}

template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::stop(StopReason why, Index i, Scalar t, const State& x,
                                                             const Mode& mode) -> TransitionAction {
  stop_reason_ = why;
  stop_damper_ = i;
  const std::string at = " at t = " + detail::format_value(t);
  const std::string who = "damper " + std::to_string(i);
  switch (why) {
    case StopReason::LiftOff: {
      const Evaluation& e = evaluate(mode, t, x);
      return TransitionAction::halt("lift-off: the normal force of " + who + " reached zero" + at +
                                    " (N = " + detail::format_value(e.N[i]) +
                                    "); the model assumes permanent contact");
    }
    case StopReason::LeftMember: {
      const std::size_t iu = static_cast<std::size_t>(i);
      const Scalar X = moving_[iu] ? x[contact_offset() + i] : dampers_[iu].contact_coordinate;
      return TransitionAction::halt(
          "left member: the contact point of " + who + " reached the end of member " +
          std::to_string(dampers_[iu].member) + at + " (X = " + detail::format_value(X) +
          ", valid range [0, " + detail::format_value(shapes_[static_cast<std::size_t>(damper_shape_[iu])].length()) + "])");
    }
    case StopReason::NoConsistentState:
      return TransitionAction::halt("no consistent stick/slip state found for " + who + at);
    case StopReason::NonFiniteLoad:
      return TransitionAction::halt("PointLoad[" + std::to_string(i) + "] is not finite" + at + " (F = " +
                                    detail::format_value(load_fault_.value) + ")");
    case StopReason::None: break;
  }
  return TransitionAction::halt("stopped" + at);
}

}  // namespace stickslip

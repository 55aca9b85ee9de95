#pragma once
/// \file contact_system_events.hpp
/// \brief ContactSystem's guards and transitions (contact_system.hpp): component 4's state
/// machine per contact, a unilateral contact's lift-off (N = 0) and landing (gap = 0, an impact
/// of restitution e), and the consistent set of states after every switch.

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::requested_mode() const -> Mode {
  Mode mode(D_);
  for (Index i = 0; i < D_; ++i) mode[i] = contacts_[static_cast<std::size_t>(i)].start_state();
  return mode;
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::contact_guards(const Mode& mode) const -> Index {
  Index k = 0;
  for (Index i = 0; i < D_; ++i) k += guards_of(mode, i);
  return k;
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::num_guards(const Mode& mode) const -> Index {
  return contact_guards(mode) + 2 * num_moving();  // each moving side b: X and L - X
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::guards(const Mode& mode, Scalar t, const State& x, GuardVector& g) {
  solve(mode, t, x);
  g.resize(num_guards(mode));
  Index k = 0;
  for (Index i = 0; i < D_; ++i) {
    detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
      if (is_in_contact(mode[i]))
        m.guards(mode[i], e_.v[i], e_.N[i], e_.f[i], unilateral(i), g.data() + k);
      else
        m.gap_guard(e_.gap[i], g.data() + k);
    });
    k += guards_of(mode, i);
  }
  for (Index p = 0; p < num_moving(); ++p) {  // an end the side b continues past never fires
    const std::size_t pu = static_cast<std::size_t>(p);
    const Scalar X = x[contact_offset() + p];
    g[k++] = extends_[2 * pu] ? Scalar(1) : X;
    g[k++] = extends_[2 * pu + 1] ? Scalar(1) : moving_[pu].shapes.length() - X;
  }
}

template <class Scalar_, class Contact_>
CrossingDirection ContactSystem<Scalar_, Contact_>::guard_direction(const Mode& mode, Index idx) const {
  for (Index i = 0; i < D_; ++i) {
    const Index gi = guards_of(mode, i);
    if (idx < gi)
      return detail::with_law(machines_[static_cast<std::size_t>(i)],
                              [&](const auto& m) { return m.guard_direction(mode[i], idx, unilateral(i)); });
    idx -= gi;
  }
  if (idx < 2 * num_moving()) return CrossingDirection::Falling;  // a moving side b reaching a member end
  STICKSLIP_ASSERT(false && "ContactSystem::guard_direction: index beyond num_guards");
  return CrossingDirection::Either;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::make_consistent(Mode& mode, Scalar t, State& x) {
  validate_start(mode, t, x, "ContactSystem::make_consistent");
  const Mode before = mode;
  lifted_ = -1;
  solve(mode, t, x);
  for (Index i = 0; i < D_; ++i) {  // component 4's rule 2: sliding where |v| > tolerance
    if (!has_stick_state(i) || !is_in_contact(mode[i])) continue;  // an open contact stays open
    const Scalar v = e_.v[i];
    if (std::abs(v) <= options_.velocity_tolerance) mode[i] = ContactState::Stick;  // decided at rest below
    else mode[i] = v > 0 ? ContactState::SlipPositive : ContactState::SlipNegative;
  }
  bool consistent = resolve(mode, t, x);
  if (consistent) consistent = impulse(mode, t, x);
  for (Index i = 0; i < D_; ++i)
    if (mode[i] != before[i]) events_.push_back({t, i, before[i], mode[i]});
  return consistent;
}

template <class Scalar_, class Contact_>
TransitionAction ContactSystem<Scalar_, Contact_>::transition(Mode& mode, const TriggeredGuards& which, Scalar t,
                                                              State& x) {
  const Mode before = mode;
  lifted_ = -1;
  const Index end_guards = contact_guards(before);
  for (Index idx : which) {  // a moving side b at a member end: its shapes end there
    if (idx < end_guards) continue;
    const auto& side = moving_[static_cast<std::size_t>((idx - end_guards) / 2)];
    return TransitionAction::halt("contact " + std::to_string(side.contact) + " left member " +
                                  std::to_string(side.shapes.member()) + " at X = " +
                                  detail::format_value(x[contact_offset() + (idx - end_guards) / 2]) +
                                  " at t = " + detail::format_value(t));
  }
  solve(mode, t, x);
  bool landing = false;
  for (Index idx : which) {
    Index i = 0, k = idx;
    for (; i < D_ && k >= guards_of(before, i); ++i) k -= guards_of(before, i);
    if (i >= D_) continue;
    if (!is_in_contact(before[i])) {  // the gap closed: an impact
      landing_[static_cast<std::size_t>(i)] = 1;
      landing_restitution(i, x);
      landing = true;
    } else if (unilateral(i) && k == guards_of(before, i) - 1) {  // the normal force reached zero
      if (stop_at_lift_off_[static_cast<std::size_t>(i)])
        return TransitionAction::halt("contact " + std::to_string(i) + " lifted off (N = 0) at t = " +
                                      detail::format_value(t));
      mode[i] = ContactState::Separated;
    } else if (before[i] == ContactState::Stick) {
      // A stick guard: component 4's rule 4 (slip against the required force).
      mode[i] = detail::with_law(machines_[static_cast<std::size_t>(i)],
                                 [&](const auto& m) { return m.decide_at_rest(e_.N[i], e_.f[i]); });
      if (mode[i] == ContactState::LiftOff && unilateral(i)) mode[i] = ContactState::Separated;
    } else if (is_slipping(before[i])) {
      // A slip state's velocity guard: at rest, tried stuck and decided by resolve() with the set.
      mode[i] = ContactState::Stick;
    }
  }
  bool consistent = true;
  if (landing) {
    // The impact (contact_impulse.hpp): landing normal velocities to -e v_n (e = 0 when the
    // rebound would rise less than the landing height; 0 below the velocity tolerance) with
    // Coulomb's law on the impulse and the other constraints held. A contact that does not
    // bounce closes, stuck when its sliding velocity after the impact is at rest, else slipping
    // along it.
    consistent = impact(mode, t, x);
    const auto zd = x.segment(m_, m_);
    for (Index i = 0; i < D_; ++i) {
      const std::size_t iu = static_cast<std::size_t>(i);
      if (!landing_[iu]) continue;
      landing_[iu] = 0;
      const bool bounces = consistent && gap_rate_row(i).dot(zd) > options_.velocity_tolerance;
      const Scalar v = G_.row(i).dot(zd);
      mode[i] = bounces ? ContactState::Separated
                : (!has_stick_state(i) || std::abs(v) <= options_.velocity_tolerance)
                    ? ContactState::Stick
                    : (v > 0 ? ContactState::SlipPositive : ContactState::SlipNegative);
      if (bounces) events_.push_back({t, i, ContactState::Separated, ContactState::Separated});
    }
  }
  if (consistent) consistent = resolve(mode, t, x);
  if (consistent) consistent = impulse(mode, t, x);
  if (!consistent) {
    mode = before;
    if (lifted_ >= 0)
      return TransitionAction::halt("contact " + std::to_string(lifted_) + " lifted off (N < 0) at t = " +
                                    detail::format_value(t));
    return TransitionAction::halt("no consistent set of contact states at t = " + detail::format_value(t) +
                                  " (dependent constrained contacts, or no set within mu_s N and N >= 0)");
  }
  for (Index i = 0; i < D_; ++i)
    if (mode[i] != before[i]) events_.push_back({t, i, before[i], mode[i]});
  return TransitionAction::proceed();
}

}  // namespace stickslip

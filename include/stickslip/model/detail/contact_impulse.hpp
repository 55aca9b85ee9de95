#pragma once
/// \file contact_impulse.hpp
/// \brief ContactSystem's impulses (contact_system.hpp; docs/contacts.md, "Impacts"): the
/// impulse that sets the constrained velocities (stuck projections, landings), the impact of
/// landing contacts with Newton's restitution and Coulomb's law on the impulse (all landing
/// contacts of one instant together, by enumeration of their stick / slip cases), the plastic
/// landing of a rebound lower than the landing height, and the complementarity choice of the
/// touching contacts that open.

#include <stickslip/model/contact_system.hpp>

namespace stickslip {

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::init_impulse(const FrameModel<Scalar>& frame) {
  detail::require_finite("ContactSystem", "options.landing_height", options_.landing_height);
  const std::size_t D = contacts_.size();
  impact_choice_.assign(D, impact_frictionless);
  impact_row_.assign(D, 0);
  impact_list_.assign(D, 0);
  impact_e_ = restitution_;
  impact_mu_.setZero(D_);
  impact_s_.setZero(D_);
  vt_.setZero(D_);
  zsave_.setZero(m_);
  landing_height_ = options_.landing_height;
  if (landing_height_ < Scalar(0)) {  // 1e-8 of the frame's size
    Vector2 low = Vector2::Constant(std::numeric_limits<Scalar>::max()), high = -low;
    for (Index k = 0; k < frame.num_nodes(); ++k) {
      const Vector2 p = frame.node_position(NodeId(k));
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    const Scalar size = frame.num_nodes() > 0 ? (high - low).norm() : Scalar(0);
    landing_height_ = size > Scalar(0) ? Scalar(1e-8) * size : Scalar(1e-9);
  }
}

template <class Scalar_, class Contact_>
void ContactSystem<Scalar_, Contact_>::landing_restitution(Index i, const State& x) {
  // Reads the solve of the mode before the impact (contact i open): the pressing acceleration
  // a = -g''. A rebound of apex (e v_n)^2 / (2 a) at or below the landing height lands plastically.
  const Scalar vn = gap_rate_row(i).dot(x.segment(m_, m_));
  const Scalar a = -(gap_rate_row(i).dot(e_.qdd) + hdot_[i]);
  const Scalar e = restitution_[i], rebound = e * vn;
  impact_e_[i] = (a > Scalar(0) && vn < Scalar(0) && rebound * rebound <= Scalar(2) * a * landing_height_) ? Scalar(0) : e;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::impulse(const Mode& mode, Scalar t, State& x) {
  // The constrained velocities (stuck sliding velocities, closed normal velocities: target 0;
  // landing normal velocities: target -e v_n, or 0 when that is below the velocity tolerance)
  // are set by the impulse along the rows that changes z' least in kinetic energy:
  //   z' <- z' + M^-1 cols^T Lambda,   (rows M^-1 cols^T) Lambda = target - rows z',
  // cols = rows (a normal impulse along the normal row, a stuck one along the sliding row)
  // except under a moving side b, whose gap-rate row adds the slope's share of the sliding row,
  // and at a landing contact that slips through the impact, whose normal impulse P_n carries
  // the tangential impulse mu P_n (column h + mu g, mu = -s mu_k); a landing contact that sticks
  // through the impact adds its sliding row with target 0. The kinetic energy it removes is
  // booked as friction dissipation.
  solve(mode, t, x);
  if (!e_.finite) return false;
  auto zd = x.segment(m_, m_);
  b_.setZero();
  Index U = 0;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    if (landing_[iu]) {
      impact_row_[iu] = U;
      const signed char choice = impact_choice_[iu];
      rows_.row(U) = gap_rate_row(i);
      if (choice == impact_slip) cols_.row(U) = H_.row(i) + impact_mu_[i] * G_.row(i);
      else cols_.row(U) = H_.row(i);
      const Scalar bounce = -impact_e_[i] * rows_.row(U).dot(zd);
      b_[U++] = bounce > options_.velocity_tolerance ? bounce : Scalar(0);
      if (choice == impact_stick) {
        rows_.row(U) = G_.row(i);
        cols_.row(U) = G_.row(i);
        b_[U++] = 0;
      }
      continue;
    }
    if (unilateral(i) && is_in_contact(mode[i])) {
      rows_.row(U) = gap_rate_row(i);
      cols_.row(U) = H_.row(i);
      b_[U++] = 0;
    }
    if (mode[i] == ContactState::Stick && has_stick_state(i)) {
      rows_.row(U) = G_.row(i);
      cols_.row(U) = G_.row(i);
      b_[U++] = 0;
    }
  }
  if (U == 0) return true;
  C_.setZero();
  Scalar scale = 0;
  for (Index a = 0; a < U; ++a) {  // C = rows M^-1 cols^T: symmetric unless a side b moves or a landing slips
    b_[a] -= rows_.row(a).dot(zd);
    for (Index c = 0; c < U; ++c) C_(a, c) = rows_.row(a).dot(cols_.row(c).cwiseProduct(minv_.transpose()));
    scale = std::max(scale, std::abs(C_(a, a)));
  }
  for (Index a = U; a < 2 * D_; ++a) C_(a, a) = scale > 0 ? scale : Scalar(1);
  lu_.compute(C_);
  if (lu_.rank() < 2 * D_) return false;
  lambda_ = lu_.solve(b_);
  const Scalar before = Scalar(0.5) * zd.dot(zd.cwiseQuotient(minv_));
  for (Index a = 0; a < U; ++a) zd += lambda_[a] * minv_.cwiseProduct(cols_.row(a).transpose());
  if (options_.energy_audit) x[audit_offset() + 2] += before - Scalar(0.5) * zd.dot(zd.cwiseQuotient(minv_));
  return true;
}

template <class Scalar_, class Contact_>
auto ContactSystem<Scalar_, Contact_>::impulse_friction(Index i) const -> Scalar {
  return detail::with_law(machines_[static_cast<std::size_t>(i)], [](const auto& m) {
    using M = std::decay_t<decltype(m)>;
    if constexpr (M::has_stick_state) return m.law().static_coefficient();
    else return Scalar(0);
  });
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::impact(const Mode& mode, Scalar t, State& x) {
  // Newton's restitution on each landing contact's normal velocity (v_n+ = -impact_e v_n) and
  // Coulomb's law on its impulse, for all landing contacts at once: each one with friction
  // (a law with a stick state and mu_s > 0) sticks through the impact (v_t+ = 0, accepted if
  // |P_t| <= mu_s P_n) or slips in s (P_t = -s mu_k(|v_t-|) P_n, accepted if s v_t+ >= 0), and
  // P_n >= 0. The cases are tried in the order stick, slip along sgn v_t-, slip against it, the
  // first landing contact's choice varying fastest; the first case that satisfies every
  // landing contact's conditions is the impact. Frictionless landings take their normal
  // impulse alone (exactly the frictionless impact).
  solve(mode, t, x);
  if (!e_.finite) return false;
  Index F = 0;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    impact_choice_[iu] = impact_frictionless;
    if (landing_[iu] && impulse_friction(i) > Scalar(0)) impact_list_[static_cast<std::size_t>(F++)] = i;
  }
  if (F == 0 || F > max_friction_landings) return impulse(mode, t, x);
  zsave_ = x.segment(m_, m_);
  const Scalar audit0 = options_.energy_audit ? x[audit_offset() + 2] : Scalar(0);
  for (Index f = 0; f < F; ++f) {
    const Index i = impact_list_[static_cast<std::size_t>(f)];
    vt_[i] = G_.row(i).dot(zsave_);
  }
  Index cases = 1;
  for (Index f = 0; f < F; ++f) cases *= 3;
  const Scalar eps = std::sqrt(std::numeric_limits<Scalar>::epsilon());
  for (Index k = 0; k < cases; ++k) {
    Index digits = k;
    for (Index f = 0; f < F; ++f) {
      const Index i = impact_list_[static_cast<std::size_t>(f)];
      const Index d = digits % 3;
      digits /= 3;
      const Scalar s0 = vt_[i] < Scalar(0) ? Scalar(-1) : Scalar(1);
      const Scalar s = d == 2 ? -s0 : s0;
      impact_s_[i] = s;
      impact_choice_[static_cast<std::size_t>(i)] = d == 0 ? impact_stick : impact_slip;
      impact_mu_[i] = -s * detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (M::has_stick_state) return m.law().kinetic_coefficient(std::abs(vt_[i]));
        else return Scalar(0);
      });
    }
    bool accepted = impulse(mode, t, x);
    if (accepted) {
      Scalar largest = 0;  // impulses within round-off of the largest count as their bound
      for (Index f = 0; f < F; ++f) {
        const Index a = impact_row_[static_cast<std::size_t>(impact_list_[static_cast<std::size_t>(f)])];
        largest = std::max(largest, std::abs(lambda_[a]));
      }
      const Scalar slack = eps * largest;
      const auto zd = x.segment(m_, m_);
      for (Index f = 0; f < F && accepted; ++f) {
        const Index i = impact_list_[static_cast<std::size_t>(f)];
        const std::size_t iu = static_cast<std::size_t>(i);
        const Index a = impact_row_[iu];
        const Scalar Pn = lambda_[a];
        if (impact_choice_[iu] == impact_stick)
          accepted = Pn >= -slack && std::abs(lambda_[a + 1]) <= impulse_friction(i) * Pn + slack;
        else  // slipping in s: the sliding velocity after does not reverse
          accepted = Pn >= -slack && impact_s_[i] * G_.row(i).dot(zd) >= -options_.velocity_tolerance;
      }
    }
    if (accepted) return true;
    x.segment(m_, m_) = zsave_;
    if (options_.energy_audit) x[audit_offset() + 2] = audit0;
  }
  // No case satisfies Newton's and Coulomb's laws together (kinematic restitution with coupled
  // directions admits such impacts): the landing contacts take frictionless impulses.
  for (Index f = 0; f < F; ++f)
    impact_choice_[static_cast<std::size_t>(impact_list_[static_cast<std::size_t>(f)])] = impact_frictionless;
  ++frictionless_impacts_;
  return impulse(mode, t, x);
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::separating(const Mode& entry, const Mode& mode) const {
  // Each contact closed in `entry` and open in `mode` must not approach: its gap's acceleration
  // with it open, g'' = (gap-rate row) . z'' + (row rate) z', >= 0 to round-off. Reads the last
  // solve (of `mode`).
  const Scalar eps = std::sqrt(std::numeric_limits<Scalar>::epsilon());
  for (Index i = 0; i < D_; ++i) {
    if (!unilateral(i) || !is_in_contact(entry[i]) || is_in_contact(mode[i])) continue;
    const Scalar gdd = gap_rate_row(i).dot(e_.qdd) + hdot_[i];
    const Scalar size = gap_rate_row(i).cwiseAbs().dot(e_.qdd.cwiseAbs()) + std::abs(hdot_[i]);
    if (gdd < -eps * size) return false;
  }
  return true;
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::resolve(Mode& mode, Scalar t, State& x) {
  // The greedy rule first (open the most tensile closed contact, release the stuck contact most
  // over its capacity, one at a time). When it opens a contact whose gap would then close
  // (g'' < 0: it pulls when closed and approaches when open), the touching contacts' normal
  // complementarity (N >= 0 closed, g'' >= 0 open) is solved by enumeration: the subsets of the
  // contacts closed on entry are opened, fewest first, each followed by the greedy release of the
  // stuck contacts without further openings, until one satisfies it.
  const Mode entry = mode;
  const bool greedy = resolve_greedy(mode, t, x, true);
  if (!greedy || separating(entry, mode)) return greedy;
  Index K = 0;
  for (Index i = 0; i < D_; ++i)
    if (unilateral(i) && is_in_contact(entry[i]) && K < max_touching) impact_list_[static_cast<std::size_t>(K++)] = i;
  for (Index count = 1; count <= K; ++count) {
    for (unsigned subset = 1; subset < (1u << K); ++subset) {
      Index bits = 0;
      for (Index k = 0; k < K; ++k) bits += (subset >> k) & 1u;
      if (bits != count) continue;
      bool stops = false;  // a contact that stops the run at lift-off is never opened
      for (Index k = 0; k < K; ++k)
        stops = stops || (((subset >> k) & 1u) && stop_at_lift_off_[static_cast<std::size_t>(impact_list_[static_cast<std::size_t>(k)])]);
      if (stops) continue;
      Mode trial = entry;
      for (Index k = 0; k < K; ++k)
        if ((subset >> k) & 1u) trial[impact_list_[static_cast<std::size_t>(k)]] = ContactState::Separated;
      if (resolve_greedy(trial, t, x, false) && separating(entry, trial)) {
        mode = trial;
        return true;
      }
    }
  }
  // No subset satisfies the complementarity: the greedy rule's states.
  mode = entry;
  return resolve_greedy(mode, t, x, true);
}

template <class Scalar_, class Contact_>
bool ContactSystem<Scalar_, Contact_>::resolve_greedy(Mode& mode, Scalar t, State& x, bool may_open) {
  // A closed unilateral contact under tension opens (the most tensile first; with may_open
  // false the set fails instead); otherwise the stuck contact whose required force exceeds its
  // capacity most is released; one at a time, until every normal force is compressive and every
  // stuck force lies within mu_s N. Ends with a solve of the final mode.
  for (Index iter = 0; iter <= 6 * D_ + 4; ++iter) {
    solve(mode, t, x);
    if (!e_.finite) return false;
    Index worst = -1;
    Scalar worst_excess = 0;
    for (Index i = 0; i < D_; ++i)
      if (unilateral(i) && is_in_contact(mode[i]) && -e_.N[i] > worst_excess) {
        worst_excess = -e_.N[i];
        worst = i;
      }
    if (worst >= 0) {
      if (stop_at_lift_off_[static_cast<std::size_t>(worst)]) {  // the run stops there (lifted_)
        lifted_ = worst;
        return false;
      }
      if (!may_open) return false;
      mode[worst] = ContactState::Separated;
      continue;
    }
    for (Index i = 0; i < D_; ++i) {
      if (mode[i] != ContactState::Stick || !has_stick_state(i)) continue;
      const Scalar excess = detail::with_law(machines_[static_cast<std::size_t>(i)], [&](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        if constexpr (M::has_stick_state)
          return std::abs(e_.f[i]) - m.stick_capacity(e_.N[i]);
        else
          return Scalar(0);
      });
      if (excess > worst_excess) {
        worst_excess = excess;
        worst = i;
      }
    }
    if (worst < 0) return true;
    mode[worst] = detail::with_law(machines_[static_cast<std::size_t>(worst)],
                                   [&](const auto& m) { return m.decide_at_rest(e_.N[worst], e_.f[worst]); });
    if (mode[worst] == ContactState::LiftOff && unilateral(worst)) mode[worst] = ContactState::Separated;
  }
  return false;
}

}  // namespace stickslip

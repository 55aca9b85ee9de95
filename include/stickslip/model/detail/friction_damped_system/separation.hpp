#pragma once
/// \file separation.hpp
/// \brief FrictionDampedSystem, separation (docs/model_separation.md "Separation"): a damper whose normal
/// force reaches zero leaves the member into flight (y_d, y_d'), its gap closing is an impact
/// solved through the member's impulse response W = G M_eff^-1 G^T (frictional_impact: Newton's
/// restitution, Coulomb on the impulse), and a rebound inside the landing band lands.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

/// The impacts of impacting_, then the lift-offs of lifting_ (into flight); false when an
/// impact has no solution (frictional_impact not resolved).
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::separation_transition(Mode& mode, Scalar t, State& x) {
  for (Index i : impacting_)
    if (!impact(mode, i, t, x)) return false;
  for (const auto& hit : wall_hits_) wall_impact(mode, hit.first, hit.second, t, x);
  for (Index i : lifting_) separate(mode, i, t, x);
  involved_.erase(std::remove_if(involved_.begin(), involved_.end(),
                                 [&](Index i) { return mode[i] == ContactState::Separated; }),
                  involved_.end());
  return true;
}

/// Damper i leaves the member: flight coordinates y_d, y_d' := the member's y, y' under it.
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::separate(Mode& mode, Index i, Scalar t, State& x) {
  const MemberContact c = member_contact(i, x);
  const Index y = flight_offset() + flight_slot_[static_cast<std::size_t>(i)];
  x[y] = c.y;
  x[y + num_separable_] = c.yd;
  events_.push_back(ContactEvent{t, i, mode[i], ContactState::Separated});
  mode[i] = ContactState::Separated;
  cache_valid_ = false;
}

/// land_or_separate over every damper in contact that may separate: no such damper is left
/// pressed by N <= 0, where its N guard would start on its triggering side and not fire.
template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::separate_unpressed(Mode& mode, Scalar t, State& x) {
  lifting_.clear();
  for (Index i = 0; i < D_; ++i)
    if (flight_slot_[static_cast<std::size_t>(i)] >= 0 && mode[i] != ContactState::Separated) lifting_.push_back(i);
  return land_or_separate(mode, lifting_, t, x);
}

/// Candidates (dampers that may separate, in contact) whose normal force is not positive leave
/// the member; the other dampers' states are then resolved again. False when resolve fails.
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::land_or_separate(Mode& mode, const std::vector<Index>& candidates,
                                                                  Scalar t, State& x) {
  for (Index pass = 0; pass <= D_; ++pass) {
    bool changed = false;
    for (Index i : candidates) {
      if (flight_slot_[static_cast<std::size_t>(i)] < 0 || mode[i] == ContactState::Separated) continue;
      const Evaluation& e = evaluate(mode, t, x);
      if (!e.finite) return true;  // reported by the stepper's finiteness check
      if (e.N[i] > Scalar(0)) continue;
      separate(mode, i, t, x);
      changed = true;
    }
    if (!changed) return true;
    involved_.clear();
    if (!resolve(mode, involved_, t, x)) return false;
  }
  return true;
}

/// response_ = the member's modal velocity jumps, response_x_ the dampers' x' jumps, for unit
/// modal impulses impulse_dir_ (two columns), through the other dampers' contact rows.
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::impulse_response(const Mode& mode, const State& x) {
  // The frozen solve (solve_forces<true>) is the impulse problem when r0 is the impulse and the
  // state, preloads and slip coefficients are zero: q'' -> the jump of q', N and f -> the other
  // dampers' impulses, x'' -> the jumps of their x'. The other contacts act through their rows:
  // a stuck damper's tangential and (inertial) normal constraint, a slipping one's normal
  // constraint without its friction impulse (mu = 0: a symmetric W, no work of the constraints).
  lp_.xs.setZero();
  if (options_.moving_contact) lp_.xs.segment(contact_offset(), D_) = x.segment(contact_offset(), D_);
  lp_.mu.setZero();
  for (Index j = 0; j < D_; ++j) std::swap(lp_.preload[static_cast<std::size_t>(j)],
                                           dampers_[static_cast<std::size_t>(j)].preload);
  const bool refine = options_.refine_stale_factorisation;
  options_.refine_stale_factorisation = false;
  factor_unknowns_ = -1;
  for (Index c = 0; c < 2; ++c) {
    modal(r0_) = modal(impulse_dir_.col(c));
    solve_forces<true>(mode, lp_.xs);
    response_.col(c) = eval_.qdd;
    response_x_.col(c) = eval_.xdd;
  }
  for (Index j = 0; j < D_; ++j) std::swap(lp_.preload[static_cast<std::size_t>(j)],
                                           dampers_[static_cast<std::size_t>(j)].preload);
  options_.refine_stale_factorisation = refine;
  factor_unknowns_ = -1;
  cache_valid_ = false;
}

/// W = G M_eff^-1 G^T of a damper of mass m at slope s: the member's part impulse_dir_^T
/// response_ (after impulse_response) plus the damper's [[(1 + s^2)/m, s/m], [s/m, 1/m]],
/// symmetric (the member's part is, up to round-off).
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::inverse_effective_mass(
    Scalar s, Scalar m) const -> Eigen::Matrix<Scalar, 2, 2> {
  Eigen::Matrix<Scalar, 2, 2> W = impulse_dir_.transpose() * response_;
  W(0, 0) += (Scalar(1) + s * s) / m;
  W(1, 1) += Scalar(1) / m;
  W(0, 1) = W(1, 0) = (W(0, 1) + W(1, 0)) / Scalar(2) + s / m;
  return W;
}

/// The impact of separated damper i (gap = 0): frictional_impact with W from the member's
/// impulse response; velocities updated, the loss booked; bounce or landing.
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::impact(Mode& mode, Index i, Scalar t, State& x) {
  using Mat2 = Eigen::Matrix<Scalar, 2, 2>;
  using Vec2 = Eigen::Matrix<Scalar, 2, 1>;
  const std::size_t iu = static_cast<std::size_t>(i);
  const Damper& d = dampers_[iu];
  const Scalar m = d.effective_mass();
  // A damper held at a wall in flight lands (or bounces) with its own rows out of the member's
  // response, as any flying damper; the wall holds it again afterwards if nothing moves it away.
  const WallRest held = mode.wall(i);
  mode.set_wall(i, WallRest::None);
  const MemberContact c = member_contact(i, x);  // i's shapes now in C_
  const Scalar s = c.slope;
  // Rows of the gap rate g' = (a - s b)^T q' + s x' - y_d' and of V = x' - b^T q' in the
  // velocities (q', x', y_d'); the impulse L = (L_n, L_t) acts on them through these rows.
  impulse_dir_.col(0) = C_.col(i) - s * C_.col(D_ + i);
  impulse_dir_.col(1) = -C_.col(D_ + i);
  const Index y = flight_offset() + flight_slot_[iu], yd = y + num_separable_;
  const Vec2 v(c.yd - x[yd], c.V);
  impulse_response(mode, x);
  const Mat2 W = inverse_effective_mass(s, m);
  auto solve_impact = [&](const NewtonImpact<Scalar>& newton) {
    return detail::with_law(d.law, [&](const auto& law) {
      using L = std::decay_t<decltype(law)>;
      if constexpr (L::has_stick_state) {
        return frictional_impact(newton, law, W, v);
      } else {  // a bounded friction force has no impulse: Newton's law alone, through W_nn
        FrictionalImpact<Scalar> r;
        const NormalImpact<Scalar> normal = newton.impact(v[0], W(0, 0));
        r.impulse = Vec2(normal.impulse, Scalar(0));
        r.velocity_after = v + W.col(0) * normal.impulse;
        r.velocity_after[0] = normal.velocity_after;
        r.energy_loss = normal.energy_loss;
        r.lands = normal.lands;
        r.state = slip_state(r.velocity_after[1]);
        return r;
      }
    });
  };
  // The velocity jumps of an impulse L on the damper (and -L through the rows on the member).
  auto apply = [&](const Vec2& L) {
    x.segment(n_, n_) += response_ * L;
    for (Index j = 0; j < D_; ++j)
      if (j != i) x[xd_offset() + j] += response_x_(j, 0) * L[0] + response_x_(j, 1) * L[1];
    x[xd_offset() + i] += (s * L[0] + L[1]) / m;
    x[yd] -= L[0] / m;
  };
  FrictionalImpact<Scalar> hit = solve_impact(NewtonImpact<Scalar>(d.restitution, d.landing_speed));
  if (!hit.resolved) return false;
  apply(hit.impulse);
  if (!hit.lands && rebound_within_band(mode, i, t, x, hit.velocity_after[0])) {
    // A rebound too low to leave the landing band is a landing (docs/model_separation.md "Separation"):
    // the plastic impact (e = 0) in its place, i.e. the difference of the two impulses added.
    const FrictionalImpact<Scalar> landing = solve_impact(NewtonImpact<Scalar>(Scalar(0), d.landing_speed));
    if (!landing.resolved) return false;
    apply(landing.impulse - hit.impulse);
    hit = landing;
  }
  const Vec2& L = hit.impulse;
  if (audit_size() > 4) x[energy_offset() + 4] += hit.energy_loss;
  const ContactState to = hit.lands ? hit.state : ContactState::Separated;
  if (held != WallRest::None) {  // back at the wall: held (V = 0 in flight), or an impact on it
    const Scalar V_after = hit.velocity_after[1];
    const bool into = held == WallRest::Start ? V_after < Scalar(0) : V_after > Scalar(0);
    if (into) wall_hits_.emplace_back(i, held == WallRest::Start ? 0 : 1);
    else if (to == ContactState::Separated && V_after == Scalar(0)) mode.set_wall(i, held);
  }
  impacts_.push_back(ImpactEvent{t, i, L[0], L[1], v[0], hit.velocity_after[0], v[1], hit.velocity_after[1],
                                 hit.energy_loss, to});
  events_.push_back(ContactEvent{t, i, ContactState::Separated, to});
  mode[i] = to;
  if (to == ContactState::Stick) involved_.push_back(i);  // resolve() decides stick or slip
  cache_valid_ = false;
  return true;
}

/// Whether the rebound of separated damper i at gap rate v_after > 0 (state x just after the
/// bounce) stays inside the landing band: g'' < 0 and v_after^2 <= 2 |g''| kLandingBand L, i.e.
/// the flight's apex below kLandingBand L (docs/model_separation.md "Separation", "The landing band").
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::rebound_within_band(const Mode& mode, Index i, Scalar t,
                                                                     const State& x, Scalar v_after) {
  const Scalar a = flight_gap_acceleration(mode, i, t, x);
  const Scalar band = Scalar(kLandingBand) * shapes_[static_cast<std::size_t>(damper_shape_[static_cast<std::size_t>(i)])].length();
  return a < Scalar(0) && v_after * v_after <= Scalar(-2) * a * band;
}

}  // namespace stickslip

#pragma once
/// \file walls.hpp
/// \brief FrictionDampedSystem, member ends and walls (docs/model_separation.md "Member ends", "Resting at
/// a wall"): the tangential impact of a moving contact on a MemberEnd::Wall (V -> -e V), a damper
/// resting against a wall (the wall takes the force beyond mu_s N) or held at it in flight, and
/// their guards and checks.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

/// Damper i's contact point reached the wall at end `end` (0: X = 0, 1: X = L): the sliding
/// velocity V -> -e V by a tangential impulse through W_t = 1/m + b^T R b (with the normal
/// impulse that keeps an inertial contact closed on a sloped member); the loss booked.
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::wall_impact(Mode& mode, Index i, int end, Scalar t, State& x) {
  const std::size_t iu = static_cast<std::size_t>(i);
  const Damper& d = dampers_[iu];
  const Scalar m = d.effective_mass();
  const MemberContact c = member_contact(i, x);  // i's shapes now in C_
  const Scalar V = c.V;
  if (!(end == 0 ? V < Scalar(0) : V > Scalar(0))) return;  // not moving into the wall
  // V = x' - b^T q': the impulse L_t on the damper along u acts on the member as -b L_t. A
  // damper in contact with an inertial normal load keeps its contact through the impact: with
  // a slope s, V's jump moves it along the normal by s dV, which takes a normal impulse L_n
  // with gap' = (a - s b)^T q' + s x' - y_d' held at 0 (the rows of impact(); its own contact
  // rows are taken out of the member's response for this, and its friction impulse left out).
  const bool normal = inertial_[iu] && mode[i] != ContactState::Separated;
  const Scalar s = normal ? c.slope : Scalar(0);
  impulse_dir_.col(0) = C_.col(i) - s * C_.col(D_ + i);
  impulse_dir_.col(1) = -C_.col(D_ + i);
  const char inertial = inertial_[iu];
  inertial_[iu] = 0;  // (no preload in the probe: no rows of its own)
  impulse_response(mode, x);
  inertial_[iu] = inertial;
  // Resting contact (docs/model_separation.md "Resting at a wall"): a damper in contact with a stick state
  // that arrives at or below its landing speed, or at a plastic wall, stops against it.
  using std::abs;
  const bool rests = has_stick_[iu] && mode[i] != ContactState::Separated &&
                     (d.wall_restitution == Scalar(0) || abs(V) <= d.landing_speed);
  // Held in flight (docs/model_separation.md "Held at a wall in flight"): a separated damper that arrives at
  // or below its landing speed, at a plastic wall, or whose rebound would turn within the wall
  // band (V^2 e^2 <= 2 |V'| kWallBand L with V' pushing it into the wall: no velocity guard in
  // flight would see that turning point) stays at the wall.
  const bool holds = mode[i] == ContactState::Separated && [&] {
    if (d.wall_restitution == Scalar(0) || abs(V) <= d.landing_speed) return true;
    const Scalar push = (end == 0 ? Scalar(-1) : Scalar(1)) * flight_sliding_acceleration(mode, i, t, x);
    const Scalar Lm = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
    const Scalar rebound = d.wall_restitution * V;
    return push > Scalar(0) && rebound * rebound <= Scalar(2) * push * Scalar(kWallBand) * Lm;
  }();
  const Scalar V_after = rests || holds ? Scalar(0) : -d.wall_restitution * V;
  Eigen::Matrix<Scalar, 2, 1> L(Scalar(0), Scalar(0));
  if (normal) {
    L = inverse_effective_mass(s, m).inverse() * Eigen::Matrix<Scalar, 2, 1>(Scalar(0), V_after - V);
  } else {
    L[1] = (V_after - V) / (Scalar(1) / m + impulse_dir_.col(1).dot(response_.col(1)));
  }
  x.segment(n_, n_) += response_ * L;
  for (Index j = 0; j < D_; ++j)
    if (j != i) x[xd_offset() + j] += response_x_(j, 0) * L[0] + response_x_(j, 1) * L[1];
  x[xd_offset() + i] += (s * L[0] + L[1]) / m;
  const Scalar loss = -L[1] * (V + V_after) / Scalar(2);
  if (audit_size() > 4) x[energy_offset() + 4] += loss;
  ContactState to = mode[i];
  if (mode[i] != ContactState::Separated) {
    if (rests) {  // at the end (it was within |V| times the event time tolerance of it)
      to = ContactState::Stick;
      mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
      x[contact_offset() + i] = end == 0 ? Scalar(0) : shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
      involved_.push_back(i);  // resolve() keeps it (the wall takes the push) or lets it slip away
    } else {
      to = slip_state(V_after);
    }
  } else if (holds) {
    mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
    x[contact_offset() + i] = end == 0 ? Scalar(0) : shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
  }
  impacts_.push_back(ImpactEvent{t, i, L[0], L[1], Scalar(0), Scalar(0), V, V_after, loss, to, true});
  events_.push_back(ContactEvent{t, i, mode[i], to});
  mode[i] = to;
  cache_valid_ = false;
}

/// A damper at rest that would slip into a wall it lies at (X within kWallBand L of the end, or
/// beyond it) rests against that wall instead: marked, X set to the end. True when it did.
/// (Its turning point after a rebound slower than the stepper's guard_zero_tolerance can
/// resolve lies there: the end guard would start "at zero" and miss the crossing.)
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::rest_at_wall(Mode& mode, Index i, ContactState next, State& x) {
  const std::size_t iu = static_cast<std::size_t>(i);
  if (!moving_[iu] || mode.wall(i) != WallRest::None) return false;
  const int end = next == ContactState::SlipNegative ? 0 : 1;  // the end it would slip towards
  if (end_kind_[iu][static_cast<std::size_t>(end)] != MemberEnd::Wall) return false;
  const Scalar L = shapes_[static_cast<std::size_t>(damper_shape_[iu])].length();
  const Scalar X = x[contact_offset() + i], band = Scalar(kWallBand) * L;
  if (end == 0 ? X > band : X < L - band) return false;
  mode.set_wall(i, end == 0 ? WallRest::Start : WallRest::Finish);
  x[contact_offset() + i] = end == 0 ? Scalar(0) : L;
  return true;
}

/// A stuck damper resting at a wall: the tangential force f solved for splits into friction
/// (up to mu_s N towards the wall) and the wall's reaction (the excess, into eval_.wall_force).
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::split_wall_reaction(const Mode& mode) const {
  Evaluation& e = eval_;
  for (Index i = 0; i < D_; ++i) {
    e.wall_force[i] = Scalar(0);
    const WallRest wall = mode.wall(i);
    if (wall == WallRest::None) continue;
    const Scalar mu_s = detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [](const auto& law) -> Scalar {
      if constexpr (std::decay_t<decltype(law)>::has_stick_state)
        return law.static_coefficient();
      else
        return Scalar(0);  // (never resting: validate_walls)
    });
    // Start wall (X = 0): it pushes the damper along +u, R >= 0, and takes f - mu_s N when the
    // force f needed to hold the damper exceeds the friction bound mu_s N; finish wall: R <= 0.
    const Scalar capacity = mu_s * e.N[i];
    const Scalar excess = wall == WallRest::Start ? e.f[i] - capacity : e.f[i] + capacity;
    if (wall == WallRest::Start ? excess > Scalar(0) : excess < Scalar(0)) {
      e.wall_force[i] = excess;
      e.f[i] = wall == WallRest::Start ? capacity : -capacity;  // exactly the bound (not f - excess)
    }
  }
}

/// The stick guard of a resting damper that would let it slip into its wall (start: mu_s N - f,
/// finish: mu_s N + f) is replaced by N, positive in contact (affine in the state like the
/// others; it falls to 0 with the lift-off guard).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::rest_guard(WallRest wall, Scalar N, Scalar* g) noexcept {
  g[wall == WallRest::Start ? 0 : 1] = N;
}

/// A separated damper held at a wall (docs/model_separation.md "Held at a wall in flight"): the guard of
/// its wall end (end_g[0]: X, end_g[1]: L - X) becomes the wall's reaction, which can only push:
/// F at the start wall, -F at the finish wall (F = f + wall_force, the force along u holding it).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::hold_guard(WallRest wall, Scalar F, Scalar* end_g) noexcept {
  if (wall == WallRest::Start) end_g[0] = F;
  if (wall == WallRest::Finish) end_g[1] = -F;
}

/// The tangential row of separated damper i held at a wall: V = 0, i.e. x'' = b^T q'', with the
/// force F along u as an unknown, F - m b^T q'' = k x (the stick row without a normal row).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::hold_rows(Index i, const State& x) const {
  const Damper& dmp = dampers_[static_cast<std::size_t>(i)];
  const auto b = C_.col(D_ + i);
  const Index j = add_unknown(i, Scalar(1), dmp.effective_stiffness() * x[x_offset() + i], Scalar(0), Scalar(0),
                              D_ + i);
  modal(F_.col(j)) = -b;
  modal(L_.col(j)) = -dmp.effective_mass() * b;
  eval_.V[i] = Scalar(0);
}

/// Separated dampers held at a wall whose holding force pulls away from it (F < 0 at the
/// start, F > 0 at the finish) leave the wall (the mark cleared), until none does.
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::release_pulled_holds(Mode& mode, Scalar t, const State& x) {
  for (Index pass = 0; pass <= D_; ++pass) {
    const Evaluation& e = evaluate(mode, t, x);
    if (!e.finite) return;
    bool changed = false;
    for (Index i = 0; i < D_; ++i) {
      const WallRest w = mode.wall(i);
      if (mode[i] != ContactState::Separated || w == WallRest::None) continue;
      const Scalar F = e.f[i] + e.wall_force[i];
      if (w == WallRest::Start ? F < Scalar(0) : F > Scalar(0)) {
        mode.set_wall(i, WallRest::None);
        changed = true;
      }
    }
    if (!changed) return;
  }
}

/// Clears the wall marks of dampers that are no longer stuck (so that a later stick away from
/// the wall is an ordinary one).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::forget_left_walls(Mode& mode) {
  for (Index i = 0; i < mode.size(); ++i)
    if (mode[i] != ContactState::Stick && mode[i] != ContactState::Separated) mode.set_wall(i, WallRest::None);
}

/// Throws std::invalid_argument when a damper is marked as resting at an end that is not a wall.
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::validate_walls(const Mode& mode, const char* where) const {
  for (Index i = 0; i < D_; ++i) {
    const WallRest wall = mode.wall(i);
    if (wall == WallRest::None) continue;
    const std::size_t iu = static_cast<std::size_t>(i);
    const bool needs_stick = mode[i] != ContactState::Separated;  // (held in flight: no friction)
    if (!moving_[iu] || (needs_stick && !has_stick_[iu]) || end_kind_[iu][wall == WallRest::Start ? 0 : 1] != MemberEnd::Wall)
      throw std::invalid_argument(std::string(where) + ": mode[" + std::to_string(i) + "] rests at the " +
                                  (wall == WallRest::Start ? "start" : "finish") + " wall, but damper " +
                                  std::to_string(i) + " has no wall there (a moving contact, a law with a "
                                  "stick state and MemberEnd::Wall at that end are needed)");
  }
}

}  // namespace stickslip

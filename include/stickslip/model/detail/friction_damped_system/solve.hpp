#pragma once
/// \file solve.hpp
/// \brief FrictionDampedSystem, the coupled acceleration solve: evaluate() with its cache, the
/// structural right side r0 = -omega^2 q - c q' + sum_l F_l(t) psi_l, and the rows of every damper
/// (stick: N + m a^T q'' = N0, f - m b^T q'' = k x; slip: f = -mu N) reduced to the unknowns u with
/// A u + L^T q'' = c, q'' = r0 + F u (docs/model_solve.md, "acceleration solve").

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::evaluate(const Mode& mode, Scalar t, const State& x)
    -> const Evaluation& {
  if (!(cache_valid_ && t == cache_t_ && mode == cache_mode_ && x.size() == cache_x_.size() &&
        x == cache_x_)) {
    validate_state(mode, x, "FrictionDampedSystem::evaluate");
    solve(mode, t, x);
    cache_valid_ = true;
    cache_t_ = t;
    cache_mode_ = mode;
    cache_x_ = x;
  }
  return eval_;
}

/// The coupled solve for (q'', N, f, x'') in mode `mode` (docs/model_solve.md, "acceleration solve").
/// Known forces (constant N, f = -mu N of a slipping damper) are eliminated first; the U <= 2D
/// remaining unknowns u satisfy  A u + L^T q'' = c  with  q'' = r0 + F u  (A diagonal, F and L
/// n x U). Solved in the smaller of two equivalent forms: the capacitance (Woodbury) system
/// (A + L^T F) u = c - L^T r0, or the mode-space system (I + F A^-1 L^T) q'' = r0 + F A^-1 c,
/// used with A = I (rows with |A_jj| >= 1/2 are divided by A_jj as they are assembled).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve(const Mode& mode, Scalar t, const State& x) const {
  structural_r0(x);
  using std::isfinite;
  for (Index l = 0; l < load_psi_.cols(); ++l) {
    const Scalar F = loads_[static_cast<std::size_t>(l)].value(t);
    if (!isfinite(F)) load_fault_ = LoadFault{l, t, F, load_fault_.count + 1};
    r0_.noalias() += F * load_psi_.col(l);
  }
  solve_forces<false>(mode, x);
}

/// r0_ = -omega^2 q - c q' with the basis' modal damping coefficients c (2 zeta omega, or
/// alpha + beta omega^2 for Rayleigh damping; r0 of docs/model_solve.md without the loads).
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::structural_r0(const State& x) const {
  const auto q = x.template segment<Modes>(0, n_);
  const auto qd = x.template segment<Modes>(n_, n_);
  modal(r0_).noalias() = -modal(omega2_).cwiseProduct(q) - modal(modal_damping_).cwiseProduct(qd);
}

/// The solve after r0_ = r0 (docs/model_solve.md) is formed. Frozen (linear_part): every damper's
/// rows as at a fixed contact at the state's X (a slipping damper's too: no convective terms,
/// no slope coupling) with the slip coefficient lp_.mu instead of the law's.
template <class Scalar_, class Law_, int Modes>
template <bool Frozen>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve_forces(const Mode& mode, const State& x) const {
  const Index n = n_, D = D_;
  const auto q = x.template segment<Modes>(0, n);
  const auto qd = x.template segment<Modes>(n, n);
  Evaluation& e = eval_;
  num_unknowns_ = 0;
  for (Index i = 0; i < D; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Damper& dmp = dampers_[iu];
    const bool moving = moving_[iu];
    if (moving) {
      const Scalar X = x[contact_offset() + i];
      e.X[i] = X;
      using std::isfinite;
      if (!isfinite(X)) {  // a blown-up trial state: report it as non-finite (no shapes at NaN)
        for (Vector* v : {&e.qdd, &e.N, &e.f, &e.V, &e.Vdot, &e.xdd, &e.slope, &e.y, &e.gap})
          v->setConstant(std::numeric_limits<Scalar>::quiet_NaN());
        e.finite = false;
        return;
      }
    } else {
      e.X[i] = dmp.contact_coordinate;
    }
    const ContactState s = mode[i];
    flying_[iu] = s == ContactState::Separated;
    e.gap[i] = Scalar(0);
    if (flying_[iu]) {
      flight_rows(i, x);
      if (has_walls_ && mode.wall(i) != WallRest::None) hold_rows(i, x);
      continue;
    }
    const bool stuck = has_stick_[iu] && s == ContactState::Stick;
    if (!Frozen && moving && !stuck) {  // the contact moves at every call: element-space products
      moving_damper(i, mode, x);
      continue;
    }
    if (moving) evaluate_shapes(i, e.X[i]);  // kept over a stick phase (X constant)
    const auto a = C_.col(i), b = C_.col(D + i);
    const Scalar m = dmp.effective_mass(), k = dmp.effective_stiffness();
    const Scalar xi = x[x_offset() + i];
    const Scalar V = stuck ? Scalar(0) : x[xd_offset() + i] - qd.dot(b);
    e.V[i] = V;
    // Only stuck dampers and slipping dampers at a fixed contact come here (moving ones went to
    // moving_damper): no convective terms (V = 0, or convective_terms off without a moving
    // contact), and the slope enters only the outputs and the audit.
    e.slope[i] = moving ? q.dot(dpsi_w_.col(i)) : Scalar(0);
    e.y[i] = q.dot(a);
    d_[i] = 0;
    const bool inertial = inertial_[iu];
    if (stuck) {  // stick rows (eq 11 with x'' = b^T q''): N_i + m a^T q'' = N0, f_i - m b^T q'' = k x
      if (inertial) {
        const Index j = add_unknown(i, Scalar(1), dmp.preload, Scalar(0), Scalar(0));
        modal(F_.col(j)) = a;
        modal(L_.col(j)) = m * a;
      } else {
        e.N[i] = dmp.preload;
        r0_.noalias() += dmp.preload * a;
      }
      const Index j = add_unknown(i, Scalar(1), k * xi, Scalar(0), Scalar(0), D + i);
      modal(F_.col(j)) = -b;
      modal(L_.col(j)) = -m * b;
    } else {  // slip rows (15-16 with 19 and 22): f_i = -mu_i N_i
      const Scalar mu = Frozen ? lp_.mu[i] : slip_coefficient(i, s, V);
      mu_[i] = mu;
      if (inertial) {
        const Index j = add_unknown(i, Scalar(1), dmp.preload, mu, Scalar(0));
        modal(F_.col(j)) = a + mu * b;
        modal(L_.col(j)) = m * a;
      } else {
        e.N[i] = dmp.preload;
        e.f[i] = -mu * dmp.preload;
        r0_.noalias() += dmp.preload * (a + mu * b);
      }
    }
  }

  const Index U = num_unknowns_;
  solve_info_ = SolveInfo{};
  if (U > 0) solve_unknowns(U);
  else e.qdd = r0_;  // every force known (all dampers slipping under constant normal load)
  for (Index j = 0; j < U; ++j) {
    const Index col = unknown_of_[static_cast<std::size_t>(j)];
    (col < D ? e.N[col] : e.f[col - D]) = u_[j];
  }
  for (Index i = 0; i < D; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const Damper& dmp = dampers_[iu];
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    const bool held = flying_[iu] && mode.wall(i) != WallRest::None;  // in flight, held by a wall
    Scalar bq;
    if (!Frozen && moving_[iu] && !stuck && !flying_[iu]) {  // b from moving_damper
      bq = modal(slip_b_.col(i)).dot(modal(e.qdd));
    } else {
      bq = C_.col(D + i).dot(e.qdd);
    }
    if (stuck || held) {
      e.xdd[i] = bq;
      e.Vdot[i] = 0;
    } else {
      if (inertial_[iu]) e.f[i] = -mu_[i] * e.N[i];  // N_i was an unknown
      e.xdd[i] = (e.f[i] - dmp.effective_stiffness() * x[x_offset() + i]) / dmp.effective_mass();
      e.Vdot[i] = e.xdd[i] - bq - d_[i];
    }
  }
  if (has_walls_) split_wall_reaction(mode);
  e.finite = detail::all_finite(e.qdd) && detail::all_finite(e.N) && detail::all_finite(e.f);
}

/// Appends an unknown (column of z = [N; f], A entry, right side) of damper i; its key
/// (column, X_i, mu_i, slope_i) fixes its column, A entry and row for the factorisation reuse.
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::add_unknown(Index i, Scalar diag, Scalar rhs, Scalar mu,
                                                                    Scalar sc, Index column) const -> Index {
  const Index U = num_unknowns_;
  if (column < 0) column = i;
  unknown_of_[static_cast<std::size_t>(U)] = column;
  A_[U] = diag;
  c_[U] = rhs;
  Scalar* key = key_.data() + 4 * U;
  key[0] = Scalar(column);
  key[1] = eval_.X[i];
  key[2] = mu;
  key[3] = sc;
  return num_unknowns_++;
}

/// Signed slip coefficient mu_i with f_i = -mu_i N_i for a slipping (or regularised) damper.
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::slip_coefficient(
    Index i, ContactState s, Scalar V) const -> Scalar {
  using std::isnan;
  const Scalar constant = kinetic_constant_[static_cast<std::size_t>(i)];
  if (!isnan(constant)) return Scalar(detail::slip_sign(s)) * constant;
  return detail::with_law(dampers_[static_cast<std::size_t>(i)].law, [&](const auto& law) -> Scalar {
    using L = std::decay_t<decltype(law)>;
    using std::abs;
    if constexpr (L::has_stick_state)
      return Scalar(detail::slip_sign(s)) * law.kinetic_coefficient(abs(V));
    else
      return law.coefficient(V);
  });
}

}  // namespace stickslip

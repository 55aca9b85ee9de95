#pragma once
/// \file linear_part.hpp
/// \brief FrictionDampedSystem, the linear part per discrete mode x_L' = A_m x_L + b_m(t) + r_m
/// (stickslip/ode/linear_part.hpp) for the exponential method: A_m, b_m and the affine guards by
/// probing the solve with the contact coordinates and slip coefficients frozen, exact where the
/// mode is linear, with b0 corrected so that r_m(t, x) = 0 elsewhere.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::every_mode_exact() const {
  using std::isnan;  // (the exact test of linear_part below, for every mode at once)
  for (std::size_t i = 0; i < moving_.size(); ++i)
    if (moving_[i] || isnan(kinetic_constant_[i])) return false;
  for (const Load& l : loads_)
    if (l.time_function) return false;
  return true;
}

template <class Scalar_, class Law_, int Modes>
auto FrictionDampedSystem<Scalar_, Law_, Modes>::linear_part(const Mode& mode, Scalar t, const State& x,
                                                             LinearPart<Scalar>& lp) -> bool {
  if (x.size() != state_size())
    detail::throw_invalid("FrictionDampedSystem::linear_part", "x must have state_size() entries, size", x.size());
  if (mode.size() != D_)
    detail::throw_invalid("FrictionDampedSystem::linear_part", "mode must hold one state per damper, size",
                          mode.size());
  const Evaluation& e = evaluate(mode, t, x);
  if (!e.finite) return false;
  if (lp_.xs.size() != state_size()) allocate_linear_part_workspace();
  using std::isnan;
  bool exact = true, moving_slip = false;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    const bool stuck = has_stick_[iu] && mode[i] == ContactState::Stick;
    lp_.X[i] = e.X[i];
    if (mode[i] == ContactState::Separated) {  // free flight: linear (y'' = N0/m), f = 0
      lp_.mu[i] = Scalar(0);
      moving_slip = moving_slip || moving_[iu];
      exact = exact && !moving_[iu];
      continue;
    }
    lp_.mu[i] = stuck ? Scalar(0) : slip_coefficient(i, mode[i], e.V[i]);
    if (stuck) continue;
    moving_slip = moving_slip || moving_[iu];
    exact = exact && !moving_[iu] && !isnan(kinetic_constant_[iu]);
  }
  for (const Load& l : loads_) exact = exact && !l.time_function;

  const bool same = lp_.key_valid && mode == lp_.mode && lp_.X == lp_.key_X && lp_.mu == lp_.key_mu;
  if (!same) {
    ++lp_.version;
    lp_.mode = mode;
    lp_.key_X = lp_.X;
    lp_.key_mu = lp_.mu;
    lp_.key_valid = true;
    lp_.cached = false;
  }
  if (lp_.cached) {  // an exact mode depends on its key only
    lp = lp_.cache;
    return true;
  }
  const bool frozen_guards = !exact && lp.want_inexact_guards;
  linear_part_by_probes(mode, exact, moving_slip, frozen_guards, lp);
  if (frozen_guards) frozen_guard_rows(mode, t, x, lp);
  lp.exact = exact;
  lp.version = lp_.version;
  if (exact) {
    lp_.cache = lp;
    lp_.cached = true;
    return true;
  }
  // r_m(t, x) = f(t, x) - A x_L - b(t) into b0, so that the remainder vanishes at x.
  const Evaluation& ex = evaluate(mode, t, x);
  linear_derivative(ex, x, lp_.f);
  lp.load(t, lp_.b);
  lp_.f -= lp_.b;
  lp_.f.noalias() -= lp.A * x.head(linear_size());
  lp.b0 += lp_.f;
  return true;
}

/// True when linear_part's A_m is exact in `mode` (r_m = 0 with X frozen), as linear_part decides.
template <class Scalar_, class Law_, int Modes>
bool FrictionDampedSystem<Scalar_, Law_, Modes>::exact_mode(const Mode& mode) const {
  using std::isnan;
  for (Index i = 0; i < D_; ++i) {
    const std::size_t iu = static_cast<std::size_t>(i);
    if (has_stick_[iu] && mode[i] == ContactState::Stick) continue;
    if (moving_[iu]) return false;
    if (mode[i] != ContactState::Separated && isnan(kinetic_constant_[iu])) return false;
  }
  return std::none_of(loads_.begin(), loads_.end(), [](const Load& l) { return bool(l.time_function); });
}

template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::allocate_linear_part_workspace() {
  lp_.xs.setZero(state_size());
  for (Vector* v : {&lp_.f, &lp_.b}) v->setZero(linear_size());
  for (Vector* v : {&lp_.X, &lp_.mu, &lp_.key_X, &lp_.key_mu}) v->setZero(D_);
  lp_.g.setZero(D_ * (CoulombContact<CoulombLaw<Scalar>>::max_guards + 2));
  lp_.preload.assign(static_cast<std::size_t>(D_), Scalar(0));
}

/// A_m, b_m and (exact modes without end guards; inexact ones with frozen_guards, completed by
/// frozen_guard_rows) the affine guards of `mode` by probing the
/// frozen solve (solve_forces<true>: X = lp_.X, mu = lp_.mu), which is affine in x_L, N0 and the
/// load values: b0 at x_L = 0; with the preloads set to zero, column j of A_m at x_L = e_j
/// and load l's response at unit load (no differences, so nothing cancels). Each probe reuses
/// the factorisation of the frozen matrix, which is refactorised at the first probe when a
/// slipping contact moves (its rows are otherwise formed in element space) and after the last.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::linear_part_by_probes(
    const Mode& mode, bool exact, bool moving_slip, bool frozen_guards, LinearPart<Scalar>& lp) {
  using std::cos;
  using std::sin;
  using std::abs;
  const Index P = linear_size(), probed = 2 * n_ + 2 * D_;  // X columns: zero (X frozen)
  bool end_guards = false;
  for (Index i = 0; i < D_; ++i) end_guards = end_guards || end_guards_of(mode, i);
  const Index G = (exact && !end_guards) || (!exact && frozen_guards) ? num_guards(mode) : 0;
  lp.omega.clear();
  detail::add_load_frequencies(loads_, lp.omega);
  const Index K = static_cast<Index>(lp.omega.size());
  // The audit's rates as quadratic forms in z = (x_L, 1, cos w_k t, sin w_k t) (exact modes):
  // the friction forces f and slip velocities V are affine in z, recorded at every probe.
  const bool forms = exact && options_.energy_audit;
  const Index nz = P + 1 + 2 * K;
  if (forms) {
    lp_.fz.setZero(D_, nz);
    lp_.vz.setZero(D_, nz);
  }
  auto record = [&](Index col, Scalar scale) {
    if (!forms) return;
    lp_.fz.col(col) += scale * eval_.f;
    lp_.vz.col(col) += scale * eval_.V;
  };
  lp.A.setZero(P, P);
  lp.bc.setZero(P, K);
  lp.bs.setZero(P, K);
  lp.Gx.setZero(G, G > 0 ? P : 0);
  lp.gc.setZero(G, K);
  lp.gs.setZero(G, K);

  const bool refine = options_.refine_stale_factorisation;
  options_.refine_stale_factorisation = false;  // a direct solve of the frozen matrix at every probe
  if (moving_slip) factor_unknowns_ = -1;
  lp_.xs.setZero();
  if (options_.moving_contact) lp_.xs.segment(contact_offset(), D_) = lp_.X;
  frozen_probe(mode, -1, G);
  record(P, Scalar(1));
  lp.b0 = lp_.f;
  lp.g0 = lp_.g.head(G);
  for (Index i = 0; i < D_; ++i) std::swap(lp_.preload[static_cast<std::size_t>(i)],
                                           dampers_[static_cast<std::size_t>(i)].preload);
  const Index flight = 2 * num_separable_;  // the flight columns y_d, y_d' follow X
  for (Index jj = 0; jj < probed + flight; ++jj) {
    const Index j = jj < probed ? jj : flight_offset() + (jj - probed);
    lp_.xs[j] = Scalar(1);
    frozen_probe(mode, -1, G);
    lp_.xs[j] = Scalar(0);
    record(j, Scalar(1));
    lp.A.col(j) = lp_.f;
    if (G > 0) lp.Gx.col(j) = lp_.g.head(G);
  }
  for (Index l = 0; l < static_cast<Index>(loads_.size()); ++l) {
    const Load& load = loads_[static_cast<std::size_t>(l)];
    if (load.time_function) continue;  // left to the remainder
    frozen_probe(mode, l, G);
    // F = a sin(w t + phi) + offset = a sin(phi) cos(w t) + a cos(phi) sin(w t) + offset
    const Scalar cosine = load.amplitude * sin(load.phase), sine = load.amplitude * cos(load.phase);
    if (load.omega == Scalar(0)) {
      record(P, load.offset + cosine);
      lp.b0 += (load.offset + cosine) * lp_.f;
      lp.g0 += (load.offset + cosine) * lp_.g.head(G);
      continue;
    }
    lp.b0 += load.offset * lp_.f;
    lp.g0 += load.offset * lp_.g.head(G);
    const Index k = static_cast<Index>(std::find(lp.omega.begin(), lp.omega.end(), abs(load.omega)) - lp.omega.begin());
    const Scalar s = load.omega < 0 ? -sine : sine;  // sin(-w t + phi) = sin(phi) cos(w t) - cos(phi) sin(w t)
    record(P, load.offset);
    record(P + 1 + 2 * k, cosine);
    record(P + 2 + 2 * k, s);
    lp.bc.col(k) += cosine * lp_.f;
    lp.bs.col(k) += s * lp_.f;
    lp.gc.col(k) += cosine * lp_.g.head(G);
    lp.gs.col(k) += s * lp_.g.head(G);
  }
  for (Index i = 0; i < D_; ++i) std::swap(lp_.preload[static_cast<std::size_t>(i)],
                                           dampers_[static_cast<std::size_t>(i)].preload);
  options_.refine_stale_factorisation = refine;
  if (moving_slip) factor_unknowns_ = -1;  // rhs() forms these rows in element space
  cache_valid_ = false;
  if (forms) audit_forms(P, K, lp);
}

/// One probe: the frozen solve at the probe state lp_.xs with load `load` at unit value (none
/// for -1); the derivative of x_L into lp_.f and, for G > 0, the guards into lp_.g.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::frozen_probe(const Mode& mode, Index load, Index G) {
  structural_r0(lp_.xs);
  if (load >= 0) r0_ += load_psi_.col(load);
  solve_forces<true>(mode, lp_.xs);
  linear_derivative(eval_, lp_.xs, lp_.f);
  if (G > 0) fill_guards(mode, eval_, lp_.g.data());
}

/// Frozen affine guards of an inexact mode (long Lawson steps while slipping),
/// completed from the rows of guards() that linear_part_by_probes recorded under the frozen solve
/// (X = lp_.X, mu = lp_.mu): an end guard reads the frozen linear part's X (g = X, L - X), and
/// g0 is corrected so that the rows Gx x_L + g(t) equal guards() at (t, x).
template <class Scalar_, class Law_, int Modes>
void FrictionDampedSystem<Scalar_, Law_, Modes>::frozen_guard_rows(const Mode& mode, Scalar t, const State& x,
                                                                   LinearPart<Scalar>& lp) {
  using std::cos;
  using std::sin;
  const Index P = linear_size(), G = lp.Gx.rows(), K = static_cast<Index>(lp.omega.size());
  // End guards (X, L - X; a constant 1 at an end that extends): rows of the contact coordinate
  // (+1, -1; g0 below adds 0, L), which the probes hold at X* (their X columns are not probed).
  Index k = 0;
  for (Index i = 0; i < D_; ++i) {
    k += contact_guards_of(mode, i);
    if (!end_guards_of(mode, i)) continue;
    const std::size_t iu = static_cast<std::size_t>(i);
    for (Index e = 0; e < 2; ++e, ++k) {
      lp.Gx.row(k).setZero();
      if (K > 0) {  // G x 0 without harmonic loads: no row to clear (and no data to offset)
        lp.gc.row(k).setZero();
        lp.gs.row(k).setZero();
      }
      if (end_kind_[iu][static_cast<std::size_t>(e)] != MemberEnd::Extend)
        lp.Gx(k, contact_offset() + i) = e == 0 ? Scalar(1) : Scalar(-1);
    }
  }
  // g0 = g(t, x) - Gx x_L - sum_k (gc_k cos w_k t + gs_k sin w_k t): the rows equal guards() at
  // the refresh point.
  fill_guards(mode, evaluate(mode, t, x), lp_.g.data());
  lp_.g.head(G).noalias() -= lp.Gx * x.head(P);
  lp.g0 = lp_.g.head(G);
  for (Index kk = 0; kk < K; ++kk) {
    const Scalar w = lp.omega[static_cast<std::size_t>(kk)];
    lp.g0 -= cos(w * t) * lp.gc.col(kk) + sin(w * t) * lp.gs.col(kk);
  }
}

}  // namespace stickslip

#pragma once
/// \file factorisation.hpp
/// \brief FrictionDampedSystem, the factorisation of the reduced solve: the cheaper of the
/// capacitance form (A + L^T F) u = c - L^T r0 (U x U) and the mode-space form
/// (I + F L^T) q'' = r0 + F c (n x n), fixed-size padded LUs up to order 8, reuse of the
/// factorisation while its key is unchanged, and iterative refinement from a stale one.

#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {

/// Solves for the U unknowns and q'' (see solve()), in the cheaper of the two forms. A system
/// of order up to 8 (U unknowns, or n modes in the mode-space form) uses a fixed-size 2, 4, 6
/// or 8 LU padded with identity rows (padded_order); a larger capacitance system an exact-size
/// LU allocated by the first solve with that many unknowns (in a run: the transition into the
/// mode, which evaluates it; never inside a step). Every row is assembled with A_jj = 1 except
/// a slip row whose diagonal 1 - s_i mu_i is below 1/2 in magnitude (a row with |A_jj| >= 1/2 is
/// divided by it in moving_damper: one division and seven products instead of a pass over F). The
/// mode-space form needs A = I - no such row - else the capacitance form. The factorisation is
/// kept while its key (per unknown: column, X, mu, slope) is unchanged - while the unknowns
/// belong to stuck dampers (X constant) or to a fixed contact with a constant slip coefficient -
/// so that such calls cost O(n U + U^2). When only X, mu or the slope changed and the system is
/// larger than 8 x 8, refine() tries iterative refinement from the old factorisation first.
template <class Scalar_, class Law_, int Modes>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve_unknowns(Index U) const {
  const Index n = n_;
  Evaluation& e = eval_;
  const auto F = F_.topLeftCorner(n, U);
  const auto L = L_.topLeftCorner(n, U);
  const auto A = A_.head(U);
  const auto c = c_.head(U);
  auto u = u_.head(U);
  // (std::equal stops at the first difference: a slipping damper's key changes at every call)
  const bool reuse = factor_unknowns_ == U &&
                     std::equal(key_.data(), key_.data() + 4 * U, factor_key_.data());
  if (!reuse && options_.refine_stale_factorisation && factor_unknowns_ == U &&
      padded_order(factor_mode_space_ ? n : U) > 8 && same_columns(U) && refine(F, L, A, c, u)) {
    solve_info_.unknowns = U;
    solve_info_.mode_space = factor_mode_space_;
    solve_info_.system_size = factor_mode_space_ ? n : U;
    return;  // (the factorisation and its key stay those of the matrix factorised)
  }
  if (!reuse) {
    const double nd = static_cast<double>(n), ud = static_cast<double>(U);
    // Products + LU, the LU at the order actually factorised (padded_order: 2, 4, 6 or 8).
    const auto lu_cost = [](Index order) { const double o = static_cast<double>(order); return o * o * o / 3.0; };
    const double capacitance_cost = nd * ud * ud + lu_cost(padded_order(U));
    const double mode_space_cost = nd * nd * ud + lu_cost(padded_order(n));
    factor_mode_space_ = mode_space_cost < capacitance_cost && (A.array() == Scalar(1)).all();
    factor_unknowns_ = -1;  // valid again once the factorisation below is complete
  }
  const Index order = padded_order(factor_mode_space_ ? n : U);
  if (factor_mode_space_ && order <= 8) {
    // (a fixed Modes is at most the padded order; the other sizes are never reached)
    if constexpr (fits_order<2>()) if (order == 2) solve_mode_space_small<2>(U, reuse, lu2_);
    if constexpr (fits_order<4>()) if (order == 4) solve_mode_space_small<4>(U, reuse, lu4_);
    if constexpr (fits_order<6>()) if (order == 6) solve_mode_space_small<6>(U, reuse, lu6_);
    if constexpr (fits_order<8>()) if (order == 8) solve_mode_space_small<8>(U, reuse, lu8_);
  } else if (factor_mode_space_) {
    // (I + F L^T) q'' = r0 + F c, then u = c - L^T q'' (A = I).
    if (!reuse) {
      // (assigned, then 1 added to the diagonal: a setIdentity() first and an accumulating
      // product cost a third more, measured at n = 24, U = 32)
      Mn_.noalias() = F * L.transpose();
      Mn_.diagonal().array() += Scalar(1);
      lun_.compute(Mn_);
    }
    r0_.noalias() += F * c;
    e.qdd.noalias() = lun_.solve(r0_);
    u = c;
    u.noalias() -= L.transpose() * e.qdd;
  } else if (order == 2) {
    solve_small<2>(U, reuse, lu2_);
  } else if (order == 4) {
    solve_small<4>(U, reuse, lu4_);
  } else if (order == 6) {
    solve_small<6>(U, reuse, lu6_);
  } else if (order == 8) {
    solve_small<8>(U, reuse, lu8_);
  } else {
    Eigen::PartialPivLU<Matrix>& lu = sized_lu(U);
    if (!reuse) {
      S_.topLeftCorner(U, U).noalias() = L.transpose() * F;
      S_.diagonal().head(U) += A;
      lu.compute(S_.topLeftCorner(U, U));
    }
    rhs_.head(U) = c;
    rhs_.head(U).noalias() -= L.transpose() * r0_;
    u.noalias() = lu.solve(rhs_.head(U));
    e.qdd = r0_;
    e.qdd.noalias() += F * u;
  }
  if (!reuse) {
    factor_key_.head(4 * U) = key_.head(4 * U);
    factor_unknowns_ = U;
  }
  solve_info_.unknowns = U;
  solve_info_.mode_space = factor_mode_space_;
  solve_info_.system_size = order;
  solve_info_.reused = reuse;
}

/// True when the unknowns are the same forces as those of the stored factorisation (same
/// columns of z = [N; f], in the same order); X, mu and slope may differ.
template <class Scalar_, class Law_, int Modes>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::same_columns(Index U) const {
  for (Index j = 0; j < U; ++j)
    if (key_[4 * j] != factor_key_[4 * j]) return false;
  return true;
}

/// Iterative refinement with the stored factorisation of a matrix M0 of the same form and
/// columns (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., ch. 12: fixed
/// precision refinement): z <- z + M0^-1 (b - M z), with the residual of the current matrix M
/// formed from F and L (2 n U multiply-adds) in place of forming and factorising M
/// (n U min(n, U) + min(n, U)^3 / 3). Converges when the corrections contract, i.e. when M is
/// close to M0 - a slipping contact that moved by a stage's step. Accepted when a correction is
/// below kRefineTol relative to z (max norm); abandoned (false, the caller refactorises) when a
/// correction fails to halve or after kMaxRefinements, so a large change costs a few products.
/// F, L: the n x U directions, A, c: diagonal and right side, u: the unknowns (views of the
/// workspace, as in solve_unknowns).
template <class Scalar_, class Law_, int Modes>
template <class Directions, class Coefficients, class Unknowns>
inline bool FrictionDampedSystem<Scalar_, Law_, Modes>::refine(const Directions& F, const Directions& L,
                                                               const Coefficients& A, const Coefficients& c,
                                                               Unknowns u) const {
  const Index U = u.size();
  Evaluation& e = eval_;
  Scalar previous = std::numeric_limits<Scalar>::infinity();
  if (factor_mode_space_) {
    if (!(A.array() == Scalar(1)).all()) return false;  // the mode-space form needs A = I
    // (I + F L^T) q'' = b = r0 + F c
    auto t = rhs_.head(U);  // L^T q''
    b_n_ = r0_;
    b_n_.noalias() += F * c;
    e.qdd.noalias() = lun_.solve(b_n_);
    for (int k = 1; k <= kMaxRefinements; ++k) {
      t.noalias() = L.transpose() * e.qdd;
      res_n_ = b_n_ - e.qdd;
      res_n_.noalias() -= F * t;
      dz_n_.noalias() = lun_.solve(res_n_);
      e.qdd += dz_n_;
      const Scalar size = dz_n_.cwiseAbs().maxCoeff();
      if (size <= kRefineTol * e.qdd.cwiseAbs().maxCoeff()) {
        u = c;
        u.noalias() -= L.transpose() * e.qdd;
        solve_info_.refinements = k;
        return true;
      }
      if (!(size <= Scalar(0.5) * previous)) return false;
      previous = size;
    }
    return false;
  }
  // (A + L^T F) u = b = c - L^T r0
  Eigen::PartialPivLU<Matrix>& lu = sized_lu(U);
  auto b = b_u_.head(U);
  auto res = res_u_.head(U);
  auto dz = dz_u_.head(U);
  b = c;
  b.noalias() -= L.transpose() * r0_;
  u.noalias() = lu.solve(b);
  for (int k = 1; k <= kMaxRefinements; ++k) {
    res_n_.noalias() = F * u;
    res = b - A.cwiseProduct(u);
    res.noalias() -= L.transpose() * res_n_;
    dz.noalias() = lu.solve(res);
    u += dz;
    const Scalar size = dz.cwiseAbs().maxCoeff();
    if (size <= kRefineTol * u.cwiseAbs().maxCoeff()) {
      e.qdd = r0_;
      e.qdd.noalias() += F * u;
      solve_info_.refinements = k;
      return true;
    }
    if (!(size <= Scalar(0.5) * previous)) return false;
    previous = size;
  }
  return false;
}

/// The capacitance form for U <= K unknowns in a fixed K x K system padded with identity rows:
/// (A + L^T F) u = c - L^T r0, then q'' = r0 + F u. Coefficient-based products: for a K x K
/// result GEMM/GEMV packing costs more than it saves.
template <class Scalar_, class Law_, int Modes>
template <int K, class Factor>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve_small(Index U, bool reuse, Factor& lu) const {
  // No padding: products with K columns known at compile time. Only for K <= 4 (the blade's
  // 2 slipping and 4 stuck unknowns), to keep the instantiations per system type few.
  if constexpr (K <= 4) {
    if (U == K) return solve_small_products<K>(K, reuse, lu);
  }
  solve_small_products<Eigen::Dynamic, K>(U, reuse, lu);
}

/// solve_small with Cols (or, for Eigen::Dynamic, U) columns of F and L in a K x K system.
template <class Scalar_, class Law_, int Modes>
template <int Cols, int K, class Factor>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve_small_products(Index U, bool reuse, Factor& lu) const {
  const auto F = F_.template block<Modes, Cols>(0, 0, n_, U);
  const auto L = L_.template block<Modes, Cols>(0, 0, n_, U);
  const auto r0 = modal(r0_);
  if (!reuse) {
    Eigen::Matrix<Scalar, K, K> S = Eigen::Matrix<Scalar, K, K>::Identity();
    S.template topLeftCorner<Cols, Cols>(U, U).noalias() = L.transpose().lazyProduct(F);
    S.diagonal().template head<Cols>(U) += A_.template head<Cols>(U);
    lu.compute(S);
  }
  Eigen::Matrix<Scalar, K, 1> r = Eigen::Matrix<Scalar, K, 1>::Zero();
  auto rU = r.template head<Cols>(U);
  rU = c_.template head<Cols>(U);
  rU.noalias() -= L.transpose().lazyProduct(r0);
  const Eigen::Matrix<Scalar, K, 1> z = lu.solve(r);
  solve_info_.pivoted = lu.pivoting();
  auto u = u_.template head<Cols>(U);
  u = z.template head<Cols>(U);
  auto qdd = modal(eval_.qdd);
  qdd = r0;
  qdd.noalias() += F.lazyProduct(u);
}

/// The mode-space form for n <= K modes in a fixed K x K system padded with identity rows
/// (A = I, see solve_unknowns): (I + F L^T) q'' = r0 + F c, then u = c - L^T q''. F_ and L_
/// have K rows here, zero below row n, so the products run on K x U blocks with K fixed (a
/// zero row of F leaves an identity row of the matrix; a zero row of L an identity column).
template <class Scalar_, class Law_, int Modes>
template <int K, class Factor>
inline void FrictionDampedSystem<Scalar_, Law_, Modes>::solve_mode_space_small(Index U, bool reuse, Factor& lu) const {
  using Fixed = Eigen::Matrix<Scalar, K, Eigen::Dynamic>;
  const Eigen::Map<const Fixed> F(F_.data(), K, U), L(L_.data(), K, U);
  const auto c = c_.head(U);
  if (!reuse) {
    Eigen::Matrix<Scalar, K, K> M = Eigen::Matrix<Scalar, K, K>::Identity();
    M.noalias() += F.lazyProduct(L.transpose());
    lu.compute(M);
  }
  Eigen::Matrix<Scalar, K, 1> rhs = Eigen::Matrix<Scalar, K, 1>::Zero();
  rhs.template segment<Modes>(0, n_) = modal(r0_);
  rhs.noalias() += F.lazyProduct(c);
  const Eigen::Matrix<Scalar, K, 1> z = lu.solve(rhs);
  solve_info_.pivoted = lu.pivoting();
  modal(eval_.qdd) = z.template segment<Modes>(0, n_);
  auto u = u_.head(U);
  u = c;
  u.noalias() -= L.transpose().lazyProduct(z);
}

/// The exact-size LU for U > 8 unknowns (allocated on first use only).
template <class Scalar_, class Law_, int Modes>
inline auto FrictionDampedSystem<Scalar_, Law_, Modes>::sized_lu(Index U) const -> Eigen::PartialPivLU<Matrix>& {
  Eigen::PartialPivLU<Matrix>& lu = lu_sized_[static_cast<std::size_t>(U)];
  if (lu.rows() != U) lu = Eigen::PartialPivLU<Matrix>(U);
  return lu;
}

}  // namespace stickslip

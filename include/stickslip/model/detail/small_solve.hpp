#pragma once
/// \file small_solve.hpp
/// \brief Solvers for the small fixed-size systems of the acceleration solve (orders 2, 4, 6, 8;
/// see FrictionDampedSystem::solve_unknowns): closed-form inverses and a checked 2 x 2 block
/// elimination that replace a partially pivoted LU where that is safe.

#include <Eigen/Core>
#include <Eigen/LU>

#include <limits>

namespace stickslip {
namespace detail {

/// Order-2 systems: the closed-form inverse (Eigen's cofactor formula) in place of an LU; for
/// order 2 Cramer's rule is forward stable (Higham, Accuracy and Stability of Numerical
/// Algorithms, 2nd ed., sec. 1.10.1). A singular matrix gives non-finite values, reported as a
/// non-finite evaluation, as with an LU.
template <class Scalar>
struct Inverse2 {
  Eigen::Matrix<Scalar, 2, 2> inverse = Eigen::Matrix<Scalar, 2, 2>::Identity();
  void compute(const Eigen::Matrix<Scalar, 2, 2>& m) { inverse = m.inverse(); }
  Eigen::Matrix<Scalar, 2, 1> solve(const Eigen::Matrix<Scalar, 2, 1>& r) const { return inverse * r; }
  static constexpr bool pivoting() noexcept { return false; }
};

/// K x K systems (K = 4, 6, 8) by 2 x 2 block elimination with closed-form inverses of the
/// K/2 x K/2 blocks (Eigen's fixed-size inverse(), cofactors up to 4 x 4):
///     M = [A B; C D],  S = D - C A^-1 B,
///     z2 = S^-1 (r2 - C A^-1 r1),  z1 = A^-1 r1 - (A^-1 B) z2.
/// Two divisions and independent products instead of the K dependent pivot steps of an LU
/// (measured 70 vs 104 ns at K = 6 and 79 vs 174 ns at K = 8, with the check below).
///
/// Without pivoting this is not backward stable for every matrix (A may be singular or nearly
/// so while M is not), so every solve is checked: the normwise backward error
///     eta = ||r - M z||_inf / (||M||_inf ||z||_inf + ||r||_inf)
/// (Rigal and Gaches; Higham, sec. 7.1) must be at most 16 K u, u the unit round-off. The
/// residual itself is formed in floating point with an error of up to about K u of the same
/// denominator, so a tighter bound could not be checked; a stable factorisation of the
/// acceleration solve's matrices gives eta of about u. A solve that fails the check (or gives
/// non-finite values) is redone with Eigen's PartialPivLU of M (factorised at the first such
/// solve, kept for that M). Every solve tries the block form first, so z is a function of M and
/// r alone, never of which right sides were solved before: a caller that solves an extra
/// system (an observer reading the forces) leaves every later result bitwise unchanged. A
/// singular M gives non-finite values, as with an LU alone.
template <class Scalar, int K>
class CheckedBlockSolve {
  static_assert(K % 2 == 0 && K >= 2 && K <= 8, "CheckedBlockSolve: K must be 2, 4, 6 or 8");
  static constexpr int H = K / 2;

 public:
  using MatrixK = Eigen::Matrix<Scalar, K, K>;
  using VectorK = Eigen::Matrix<Scalar, K, 1>;

  /// Block factors of m (and ||m||_inf and a copy of m for the check).
  void compute(const MatrixK& m) {
    m_ = m;
    norm_m_ = m.cwiseAbs().rowwise().sum().maxCoeff();
    pivoting_ = false;
    lu_ready_ = false;
    const Half A = m.template topLeftCorner<H, H>();
    c_ = m.template bottomLeftCorner<H, H>();
    a_inv_ = A.inverse();
    e_.noalias() = a_inv_ * m.template topRightCorner<H, H>();
    Half S = m.template bottomRightCorner<H, H>();
    S.noalias() -= c_ * e_;
    s_inv_ = S.inverse();
  }

  /// z with M z = r (M of the last compute()).
  VectorK solve(const VectorK& r) {
    VectorK z;
    const HalfVector y1 = a_inv_ * r.template head<H>();
    HalfVector t = r.template tail<H>();
    t.noalias() -= c_ * y1;
    z.template tail<H>().noalias() = s_inv_ * t;
    z.template head<H>() = y1;
    z.template head<H>().noalias() -= e_ * z.template tail<H>();
    VectorK res = r;
    res.noalias() -= m_ * z;
    const Scalar bound = Scalar(16 * K) * std::numeric_limits<Scalar>::epsilon() *
                         (norm_m_ * z.cwiseAbs().maxCoeff() + r.cwiseAbs().maxCoeff());
    pivoting_ = !(res.cwiseAbs().maxCoeff() <= bound);  // (true for NaN: to the LU)
    if (!pivoting_) return z;
    if (!lu_ready_) lu_.compute(m_);
    lu_ready_ = true;
    return lu_.solve(r);
  }

  /// True when the last solve used the pivoted LU (the block form failed its check).
  bool pivoting() const noexcept { return pivoting_; }

 private:
  using Half = Eigen::Matrix<Scalar, H, H>;
  using HalfVector = Eigen::Matrix<Scalar, H, 1>;
  MatrixK m_ = MatrixK::Identity();
  Scalar norm_m_ = Scalar(1);
  Half a_inv_ = Half::Identity(), s_inv_ = Half::Identity(), e_ = Half::Zero(), c_ = Half::Zero();
  Eigen::PartialPivLU<MatrixK> lu_;
  bool pivoting_ = false;
  bool lu_ready_ = false;  // lu_ holds the factors of m_
};

}  // namespace detail
}  // namespace stickslip

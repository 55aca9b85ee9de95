#pragma once
/// \file ldlt_shift_invert.hpp
/// \brief Spectra operator y = (K - sigma M)^{-1} x with a sparse LDL^T factorisation (for
/// sigma < 0, K - sigma M is symmetric positive definite, so no pivoting is needed).

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <cmath>
#include <stdexcept>

namespace stickslip {
namespace detail {

/// Shift-invert operator in the form Spectra's SymGEigsShiftSolver expects (Scalar, rows(),
/// cols(), set_shift(sigma), perform_op(x, y)). Replaces Spectra's SymShiftInvert, which
/// factorises with SparseLU: for the SPD matrix K - sigma M, SimplicialLDLT (AMD ordering) needs
/// about half the memory and time.
///
/// Optional deflation of known modes R (R^T M R = I, e.g. the rigid-body modes): with the
/// M-orthogonal projector P = I - R R^T M the operator becomes y = P (K - sigma M)^{-1} P^T z,
/// so that (applied to z = M x) the modes in R have the eigenvalue 0 instead of 1/(lambda - sigma).
template <class Scalar_>
class LdltShiftInvert {
 public:
  using Scalar = Scalar_;
  using SparseMatrix = Eigen::SparseMatrix<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  LdltShiftInvert(const SparseMatrix& K, const SparseMatrix& M) : K_(K), M_(M) {}

  Eigen::Index rows() const noexcept { return K_.rows(); }
  Eigen::Index cols() const noexcept { return K_.cols(); }

  /// Factorise K - sigma M. Returns false (keeping no factorisation) when it is not
  /// numerically positive definite (a pivot <= 0 or non-finite).
  bool try_factorize(Scalar sigma) {
    const SparseMatrix shifted = K_ - sigma * M_;
    ldlt_.compute(shifted);
    if (ldlt_.info() != Eigen::Success) return false;
    const auto& d = ldlt_.vectorD();
    for (Eigen::Index i = 0; i < d.size(); ++i) {
      using std::isfinite;
      if (!(isfinite(d(i)) && d(i) > Scalar(0))) return false;
    }
    return true;
  }

  /// Spectra hook: the factorisation was done by try_factorize; sigma must match.
  void set_shift(const Scalar&) {}

  /// Deflate the M-orthonormal columns of `modes` from every later perform_op (an empty matrix
  /// switches deflation off).
  void deflate(const Matrix& modes) {
    deflated_ = modes;
    m_deflated_ = M_ * modes;
    work_.resize(rows());
  }

  /// y = (K - sigma M)^{-1} x, or P (K - sigma M)^{-1} P^T x with deflation
  void perform_op(const Scalar* x_in, Scalar* y_out) const {
    Eigen::Map<const Vector> x(x_in, rows());
    Eigen::Map<Vector> y(y_out, rows());
    if (deflated_.cols() == 0) {
      y.noalias() = ldlt_.solve(x);
      return;
    }
    work_.noalias() = x - m_deflated_ * (deflated_.transpose() * x);
    y.noalias() = ldlt_.solve(work_);
    y -= deflated_ * (m_deflated_.transpose() * y);
  }

 private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt_;
  Matrix deflated_;    // R, n x r
  Matrix m_deflated_;  // M R
  mutable Vector work_;
};

}  // namespace detail
}  // namespace stickslip

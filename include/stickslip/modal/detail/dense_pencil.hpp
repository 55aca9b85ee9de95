#pragma once
/// \file dense_pencil.hpp
/// \brief Dense symmetric-definite pencil A x = mu B x (B positive definite) by the Cholesky
/// reduction C = L^{-1} A L^{-T}, B = L L^T, and a symmetric tridiagonal QR of C.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <cmath>

namespace stickslip {
namespace detail {

/// Eigenpairs of A x = mu B x, mu ascending, X^T B X = I. Replaces
/// Eigen::GeneralizedSelfAdjointEigenSolver, which does not report a failed Cholesky of B.
template <class Scalar>
struct DensePencil {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  Vector mu;
  Matrix x;
  bool ok = false;  ///< false when B is not numerically positive definite or the QR failed

  DensePencil(const Matrix& A, const Matrix& B, bool vectors) {
    const Eigen::LLT<Matrix> chol(B);
    if (chol.info() != Eigen::Success) return;
    const auto d = chol.matrixLLT().diagonal();
    using std::isfinite;
    for (Eigen::Index i = 0; i < d.size(); ++i)
      if (!(isfinite(d(i)) && d(i) > Scalar(0))) return;
    Matrix C = A;
    chol.matrixL().solveInPlace(C);                                         // L^{-1} A
    chol.matrixU().template solveInPlace<Eigen::OnTheRight>(C);             // ... L^{-T}
    C = Scalar(0.5) * (C + C.transpose()).eval();                           // exact symmetry
    const Eigen::SelfAdjointEigenSolver<Matrix> eig(C, vectors ? Eigen::ComputeEigenvectors
                                                               : Eigen::EigenvaluesOnly);
    if (eig.info() != Eigen::Success) return;
    mu = eig.eigenvalues();
    if (vectors) {
      x = eig.eigenvectors();
      chol.matrixU().solveInPlace(x);  // x = L^{-T} v
    }
    ok = true;
  }
};

}  // namespace detail
}  // namespace stickslip

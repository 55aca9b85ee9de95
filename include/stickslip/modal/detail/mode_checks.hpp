#pragma once
/// \file mode_checks.hpp
/// \brief A-posteriori checks of computed eigenpairs of K phi = lambda M phi: backward error,
/// mass-orthonormality, sign, and the count of zero eigenvalues against the rigid-body count.

#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace stickslip {
namespace detail {

/// Eigenpairs as a solver returned them: lambda ascending; phi mass-normalised; err(i) an
/// estimate of the absolute error of lambda(i) (the zero test), +inf for modes that are
/// rigid-body modes by construction (deflated).
template <class Scalar>
struct RawModes {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> lambda;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> phi;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> err;
  std::string failure;  ///< non-empty when the solver itself failed (then the rest is unset)
};

/// What check_modes measured.
template <class Scalar>
struct ModeCheck {
  Scalar max_backward_error = Scalar(0);
  Scalar max_orthonormality_error = Scalar(0);
  Eigen::Index num_zero = 0;  ///< eigenvalues with |lambda| <= zero_factor * err
  std::string failure;        ///< empty when every check passed
};

/// Largest absolute column sum ||A||_1 (= ||A||_inf for symmetric A; >= ||A||_2).
template <class Scalar>
Scalar norm1(const Eigen::SparseMatrix<Scalar>& a) {
  Scalar best(0);
  for (Eigen::Index c = 0; c < a.outerSize(); ++c) {
    Scalar sum(0);
    for (typename Eigen::SparseMatrix<Scalar>::InnerIterator it(a, c); it; ++it) sum += std::abs(it.value());
    best = std::max(best, sum);
  }
  return best;
}

/// Factor of err(i) below which |lambda(i)| counts as zero (a round-off eigenvalue).
constexpr double kZeroFactor = 1e3;

/// Check raw (mass-normalised) against K phi = lambda M phi:
/// - relative backward error ||K phi - lambda M phi||_2 / ((||K||_1 + |lambda| ||M||_1) ||phi||_2)
///   <= backward_tolerance for every pair;
/// - max |Phi^T M Phi - I| <= orthonormality_tolerance;
/// - no lambda < -kZeroFactor * err (a negative eigenvalue beyond round-off);
/// - with a known rigid-body count r >= 0: exactly min(r, size) zero eigenvalues (|lambda| <=
///   kZeroFactor * err), all of them the lowest ones.
template <class Scalar>
ModeCheck<Scalar> check_modes(const Eigen::SparseMatrix<Scalar>& K, const Eigen::SparseMatrix<Scalar>& M,
                              const RawModes<Scalar>& raw, Eigen::Index known_rigid,
                              Scalar backward_tolerance, Scalar orthonormality_tolerance) {
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  ModeCheck<Scalar> out;
  const Eigen::Index m = raw.lambda.size();
  const Scalar norm_k = norm1(K), norm_m = norm1(M);
  const Matrix kphi = K * raw.phi, mphi = M * raw.phi;
  Eigen::Index worst = 0;
  for (Eigen::Index i = 0; i < m; ++i) {
    using std::abs;
    const Vector r = kphi.col(i) - raw.lambda(i) * mphi.col(i);
    const Scalar eta = r.norm() / ((norm_k + abs(raw.lambda(i)) * norm_m) * raw.phi.col(i).norm());
    using std::isnan;
    if (isnan(eta) || eta > out.max_backward_error) {
      out.max_backward_error = isnan(eta) ? std::numeric_limits<Scalar>::infinity() : eta;
      worst = i;
    }
  }
  const Matrix gram = raw.phi.transpose() * mphi - Matrix::Identity(m, m);
  out.max_orthonormality_error = gram.cwiseAbs().maxCoeff();
  using std::isnan;
  if (isnan(out.max_orthonormality_error)) out.max_orthonormality_error = std::numeric_limits<Scalar>::infinity();

  const auto mode = [](Eigen::Index i) { return "mode " + std::to_string(i + 1); };
  if (!(out.max_backward_error <= backward_tolerance)) {
    out.failure = mode(worst) + " (lambda = " + format_value(raw.lambda(worst)) +
                  ") has the backward error " + format_value(out.max_backward_error) +
                  " > " + format_value(backward_tolerance) + " in K phi = lambda M phi";
    return out;
  }
  if (!(out.max_orthonormality_error <= orthonormality_tolerance)) {
    Eigen::Index a = 0, b = 0;
    gram.cwiseAbs().maxCoeff(&a, &b);
    out.failure = "the modes are not mass-orthonormal: |Phi^T M Phi - I| = " +
                  format_value(out.max_orthonormality_error) + " > " +
                  format_value(orthonormality_tolerance) + " at (" + std::to_string(a + 1) + ", " +
                  std::to_string(b + 1) + ") (a repeated or spurious mode)";
    return out;
  }
  const Scalar factor(kZeroFactor);
  Eigen::Index last_zero = -1;
  for (Eigen::Index i = 0; i < m; ++i) {
    using std::abs;
    if (raw.lambda(i) < -factor * raw.err(i)) {
      out.failure = mode(i) + " has the negative eigenvalue lambda = " + format_value(raw.lambda(i)) +
                    " beyond its round-off " + format_value(factor * raw.err(i)) +
                    " (K is not positive semi-definite)";
      return out;
    }
    if (abs(raw.lambda(i)) <= factor * raw.err(i)) {
      ++out.num_zero;
      last_zero = i;
    }
  }
  if (known_rigid < 0) return out;
  const Eigen::Index expected = std::min(known_rigid, m);
  if (out.num_zero > expected || (out.num_zero > 0 && last_zero + 1 != out.num_zero)) {
    // With rigid joints (FrameModel) every zero-stiffness motion is a rigid-body motion, which
    // the count covers; an extra zero eigenvalue is then round-off swamping an elastic one.
    const Scalar diag_ratio = (K.diagonal().array() / M.diagonal().array()).maxCoeff();
    out.failure = std::to_string(out.num_zero) + " zero eigenvalue(s) (|lambda| within round-off) where the supports allow " +
                  std::to_string(known_rigid) +
                  " rigid-body mode(s): ill-conditioned stiffness if max K_ii/M_ii = " +
                  format_value(diag_ratio) + " exceeds the lowest elastic lambda by ~1/eps (elements of very different lengths or stiffnesses), else a mechanism not counted in num_rigid_body_modes";
    return out;
  }
  if (out.num_zero < expected)
    out.failure = "only " + std::to_string(out.num_zero) + " of the " + std::to_string(expected) +
                  " rigid-body modes the supports allow came out with lambda = 0 within round-off (lowest lambda = " +
                  format_value(raw.lambda(0)) + ")";
  return out;
}

}  // namespace detail
}  // namespace stickslip

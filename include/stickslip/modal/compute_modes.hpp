#pragma once
/// \file compute_modes.hpp
/// \brief Lowest natural frequencies and mass-normalised modes of an assembled frame:
/// K phi = omega^2 M phi (paper eq. 9 and the modal decoupling after eq. 24).

#include "stickslip/beam/assembled_frame.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/modal/detail/ldlt_shift_invert.hpp"
#include "stickslip/modal/modal_basis.hpp"
#include "stickslip/modal/modal_options.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

/// What compute_modes did (optional output).
template <class Scalar_>
struct ModalSolveReport {
  using Scalar = Scalar_;
  ModalSolver solver = ModalSolver::Auto;  ///< Dense or Sparse, as actually used
  Scalar shift = Scalar(0);                ///< sigma of the sparse solver [rad^2/s^2]
  Scalar lambda_scale = Scalar(0);         ///< trace(K) / trace(M) [rad^2/s^2]
  Eigen::Index ncv = 0;                    ///< Lanczos basis size (sparse)
  Eigen::Index iterations = 0;             ///< Lanczos restarts (sparse)
  Eigen::Index operations = 0;             ///< solves with K - sigma M (sparse)
  Eigen::Index factorizations = 0;         ///< LDL^T factorisations tried (sparse)
};

namespace detail {

template <class Scalar>
struct RawModes {
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> lambda;
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> phi;
};

template <class Scalar>
RawModes<Scalar> dense_modes(const AssembledFrame<Scalar>& frame, Eigen::Index nev) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Matrix K(frame.stiffness);
  const Matrix M(frame.mass);
  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> solver(K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success)
    throw std::runtime_error("compute_modes: the dense generalized eigensolver failed (is M positive definite?)");
  return {solver.eigenvalues().head(nev), solver.eigenvectors().leftCols(nev)};
}

template <class Scalar>
RawModes<Scalar> sparse_modes(const AssembledFrame<Scalar>& frame, const ModalOptions<Scalar>& options,
                              Eigen::Index nev, Scalar lambda_scale, ModalSolveReport<Scalar>& report) {
  using std::isnan;
  using std::sqrt;
  const Eigen::Index n = frame.num_free();
  LdltShiftInvert<Scalar> op(frame.stiffness, frame.mass);
  // Automatic shift sigma = -s with s = rel * lambda_scale: the first rel of a ladder for which
  // K - sigma M factorises with positive pivots. Without rigid-body modes K is positive definite
  // and s starts far below any elastic eigenvalue (eps^2); otherwise s starts above the round-off
  // level of the factorisation (100 eps). See docs/modal.md.
  Scalar sigma = options.shift;
  bool ok = false;
  if (!isnan(sigma)) {
    ok = op.try_factorize(sigma);
    ++report.factorizations;
    if (!ok)
      detail::throw_invalid("compute_modes", "options.shift does not make K - shift*M positive definite", sigma);
  } else {
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    Scalar rel = frame.num_rigid_body_modes == 0 ? eps * eps : Scalar(100) * eps;
    for (int attempt = 0; attempt < 5 && !ok; ++attempt, rel *= Scalar(1000)) {
      sigma = -rel * lambda_scale;
      ++report.factorizations;
      ok = op.try_factorize(sigma);
    }
    if (!ok) throw std::runtime_error("compute_modes: no negative shift made K - sigma M positive definite");
  }
  report.shift = sigma;

  Eigen::Index ncv = options.ncv > 0 ? options.ncv : std::max<Eigen::Index>(2 * nev + 1, nev + 20);
  ncv = std::min(std::max(ncv, nev + 1), n);
  report.ncv = ncv;
  Spectra::SparseSymMatProd<Scalar> mass_op(frame.mass);
  Spectra::SymGEigsShiftSolver<LdltShiftInvert<Scalar>, Spectra::SparseSymMatProd<Scalar>,
                               Spectra::GEigsMode::ShiftInvert>
      eigs(op, mass_op, nev, ncv, sigma);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
               Spectra::SortRule::SmallestAlge);
  report.iterations = eigs.num_iterations();
  report.operations = eigs.num_operations();
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("compute_modes: the sparse Lanczos solver did not converge in " +
                             std::to_string(options.max_iterations) +
                             " restarts (raise options.ncv or options.max_iterations)");
  return {eigs.eigenvalues(), eigs.eigenvectors()};
}

}  // namespace detail

/// The lowest modes of K phi = lambda M phi, lambda = omega^2, over the free DOFs of `frame`.
///
/// At most options.num_modes modes, dropping those with omega > options.max_omega. Modes are
/// sorted ascending and mass-normalised (Phi^T M Phi = I). Eigenvalues with
/// The first frame.num_rigid_body_modes modes are rigid-body modes (omega = 0); when that count
/// is unknown (-1), those with lambda <= options.rigid_body_tolerance * trace(K)/trace(M) are.
/// Dense solver: Eigen::GeneralizedSelfAdjointEigenSolver. Sparse solver: Spectra
/// SymGEigsShiftSolver (shift-and-invert Lanczos) about a negative shift sigma, so K - sigma M is
/// positive definite even with rigid-body modes (docs/modal.md).
/// \throws std::invalid_argument for invalid options, num_modes > number of free DOFs, a
///         Sparse request with num_modes >= number of free DOFs, or when no mode has
///         omega <= max_omega
/// \throws std::runtime_error when the eigensolver fails to converge
template <class Scalar>
ModalBasis<Scalar> compute_modes(const AssembledFrame<Scalar>& frame,
                                 const ModalOptions<Scalar>& options = ModalOptions<Scalar>{},
                                 ModalSolveReport<Scalar>* report = nullptr) {
  static const char* where = "compute_modes";
  options.validate(where);
  const Eigen::Index n = frame.num_free();
  if (n < 1 || frame.stiffness.rows() != n || frame.mass.rows() != n)
    detail::throw_invalid(where, "frame must have free DOFs and K, M of size num_free", n);
  if (options.num_modes > n)
    throw std::invalid_argument(std::string(where) + ": options.num_modes = " +
                                std::to_string(options.num_modes) + " exceeds the " +
                                std::to_string(n) + " free DOFs");
  const Eigen::Index nev = options.num_modes;
  ModalSolver solver = options.solver;
  if (solver == ModalSolver::Auto)
    solver = (n <= options.dense_limit || 2 * nev + 1 > n) ? ModalSolver::Dense : ModalSolver::Sparse;
  if (solver == ModalSolver::Sparse && nev >= n)
    throw std::invalid_argument(std::string(where) + ": options.num_modes = " + std::to_string(nev) +
                                " must be < " + std::to_string(n) +
                                " free DOFs for the sparse solver (use Dense)");

  ModalSolveReport<Scalar> local_report;
  local_report.solver = solver;
  const Scalar lambda_scale = frame.stiffness.diagonal().sum() / frame.mass.diagonal().sum();
  local_report.lambda_scale = lambda_scale;
  detail::RawModes<Scalar> raw = solver == ModalSolver::Dense
                                     ? detail::dense_modes(frame, nev)
                                     : detail::sparse_modes(frame, options, nev, lambda_scale, local_report);
  if (report) *report = local_report;

  // Sort ascending, mass-normalise, classify rigid-body modes, truncate at max_omega.
  const Eigen::Index found = raw.lambda.size();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(found));
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return raw.lambda(a) < raw.lambda(b); });
  const Scalar rigid_limit = options.rigid_body_tolerance * lambda_scale;
  const Eigen::Index known_rigid = frame.num_rigid_body_modes;
  Eigen::Index keep = 0, rigid = 0;
  typename ModalBasis<Scalar>::Vector omega(found);
  for (Eigen::Index i = 0; i < found; ++i) {
    const Scalar lambda = raw.lambda(order[static_cast<std::size_t>(i)]);
    const bool is_rigid = known_rigid >= 0 ? i < known_rigid : lambda <= rigid_limit;
    using std::sqrt;
    const Scalar w = is_rigid ? Scalar(0) : sqrt(std::max(lambda, Scalar(0)));
    if (w > options.max_omega) break;
    if (is_rigid) ++rigid;
    omega(keep++) = w;
  }
  if (keep == 0)
    detail::throw_invalid(where, "options.max_omega is below the lowest natural frequency " +
                                     detail::format_value(std::sqrt(std::max(raw.lambda.minCoeff(), Scalar(0)))) + " rad/s",
                          options.max_omega);
  typename ModalBasis<Scalar>::Matrix phi(n, keep);
  for (Eigen::Index i = 0; i < keep; ++i) {
    auto col = raw.phi.col(order[static_cast<std::size_t>(i)]);
    using std::sqrt;
    phi.col(i) = col / sqrt(col.dot(frame.mass * col));
  }
  return ModalBasis<Scalar>(omega.head(keep), std::move(phi), frame.dofs, frame.model_id, rigid);
}

}  // namespace stickslip

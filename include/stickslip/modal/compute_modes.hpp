#pragma once
/// \file compute_modes.hpp
/// \brief Lowest natural frequencies and mass-normalised modes of an assembled frame:
/// K phi = omega^2 M phi (paper eq. 9 and the modal decoupling after eq. 24).

#include "stickslip/beam/assembled_frame.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/modal/detail/dense_pencil.hpp"
#include "stickslip/modal/detail/ldlt_shift_invert.hpp"
#include "stickslip/modal/detail/mode_checks.hpp"
#include "stickslip/modal/modal_basis.hpp"
#include "stickslip/modal/modal_options.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

/// What compute_modes did (optional output).
template <class Scalar_>
struct ModalSolveReport {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  ModalSolver solver = ModalSolver::Auto;  ///< Dense or Sparse, as actually used (Dense after a fallback)
  Scalar shift = Scalar(0);                ///< sigma of the sparse solver or the dense inverse form [rad^2/s^2]
  Scalar lambda_scale = Scalar(0);         ///< trace(K) / trace(M) [rad^2/s^2]
  Eigen::Index ncv = 0;                    ///< Lanczos basis size (sparse)
  Eigen::Index iterations = 0;             ///< Lanczos restarts (sparse)
  Eigen::Index operations = 0;             ///< solves with K - sigma M (sparse)
  Eigen::Index factorizations = 0;         ///< LDL^T factorisations tried (sparse)
  Eigen::Index deflated = 0;               ///< rigid-body modes deflated before Lanczos (sparse)
  Eigen::Index inverse_modes = 0;          ///< modes taken from the dense inverse form M phi = mu (K - sigma M) phi
  Scalar backward_error = Scalar(0);       ///< max relative backward error of the returned pairs
  Scalar orthonormality_error = Scalar(0); ///< max |Phi^T M Phi - I| of the mass-normalised modes
  /// Why the sparse solver's result was rejected and the dense solver used instead (empty: no
  /// fallback).
  std::string fallback_reason;
};

namespace detail {

/// M-normalise the columns of raw.phi.
template <class Scalar>
void mass_normalise(const Eigen::SparseMatrix<Scalar>& M, RawModes<Scalar>& raw) {
  for (Eigen::Index i = 0; i < raw.phi.cols(); ++i) {
    using std::sqrt;
    raw.phi.col(i) /= sqrt(raw.phi.col(i).dot(M * raw.phi.col(i)));
  }
}

/// Dense solver. The standard reduction (Cholesky of M) has the absolute eigenvalue error
/// ~eps * lambda_max, too large for the lowest modes of an ill-conditioned K (fine meshes, an
/// element much shorter than its neighbours). When the first elastic mode's estimate
/// eps * lambda_max / lambda exceeds kDenseAccuracy, the inverse form
/// M phi = mu (K + s M) phi, lambda = 1/mu - s (Cholesky of K + s M), whose absolute error
/// eps * mu_max * (lambda + s)^2 is relative to the lowest modes, is solved too and supplies
/// every mode where its estimate is the smaller one (a contiguous block from the bottom).
template <class Scalar>
RawModes<Scalar> dense_modes(const AssembledFrame<Scalar>& frame, Eigen::Index nev, Scalar lambda_scale,
                             Scalar rigid_limit, ModalSolveReport<Scalar>& report) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  constexpr Scalar kDenseAccuracy = Scalar(1e-8);
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  const Matrix K(frame.stiffness);
  const Matrix M(frame.mass);
  const Eigen::Index n = K.rows();
  RawModes<Scalar> out;
  // Eigenvalues first; the standard form's vectors only when some mode is taken from it.
  const DensePencil<Scalar> standard(K, M, false);
  if (!standard.ok) {
    out.failure = "the Cholesky factorisation of M failed (M is not positive definite)";
    return out;
  }
  const auto take_standard = [&] {
    const DensePencil<Scalar> full(K, M, true);
    out.lambda = full.mu.head(nev);
    out.phi = full.x.leftCols(nev);
  };
  const Scalar lambda_max = standard.mu.cwiseAbs().maxCoeff();
  out.err = Vector::Constant(nev, eps * lambda_max);
  const Eigen::Index rigid = frame.num_rigid_body_modes >= 0
                                 ? frame.num_rigid_body_modes
                                 : (standard.mu.array() <= rigid_limit).template cast<Eigen::Index>().sum();
  if (rigid >= nev || standard.mu(rigid) * kDenseAccuracy >= eps * lambda_max) {
    take_standard();
    return out;
  }

  // Shift s: without rigid-body modes K is positive definite and s = eps^2 lambda_scale only
  // guards the Cholesky. With rigid-body modes s ~ the first elastic eigenvalue, so that their
  // mu = 1/s does not swamp the elastic ones: from the standard estimate when that is good to
  // 10 %, else from an eigenvalues-only inverse pass with the smallest factorising s of the
  // sparse ladder (100 eps lambda_scale, times 1000 per failure). The final s is raised by the
  // same ladder until K + s M factorises.
  const auto solve = [&](Scalar shift, bool vectors) { return DensePencil<Scalar>(M, K + shift * M, vectors); };
  Scalar s = eps * eps * lambda_scale;
  if (rigid > 0 && standard.mu(rigid) * Scalar(0.1) >= eps * lambda_max) {
    s = standard.mu(rigid);
  } else if (rigid > 0) {
    for (Scalar rel = Scalar(100) * eps; rel < Scalar(1e-2); rel *= Scalar(1000)) {
      const DensePencil<Scalar> probe = solve(rel * lambda_scale, false);
      if (!probe.ok) continue;
      s = std::max(Scalar(1) / probe.mu(n - 1 - rigid) - rel * lambda_scale, rel * lambda_scale);
      break;
    }
  }
  DensePencil<Scalar> inverse = solve(s, true);
  for (Scalar rel = Scalar(100) * eps; !inverse.ok && rel < Scalar(1e-2); rel *= Scalar(1000))
    inverse = solve(s = std::max(s, rel * lambda_scale), true);
  if (!inverse.ok) {
    take_standard();  // the checks judge it
    return out;
  }
  report.shift = -s;
  const Scalar mu_max = inverse.mu(n - 1);
  Eigen::Index taken = 0;
  Vector lambda_inverse(nev), err_inverse(nev);
  for (; taken < nev; ++taken) {
    const Scalar lambda = Scalar(1) / inverse.mu(n - 1 - taken) - s;
    err_inverse(taken) = eps * mu_max * (lambda + s) * (lambda + s);
    lambda_inverse(taken) = lambda;
    if (err_inverse(taken) >= out.err(taken)) break;
  }
  if (taken < nev) {
    take_standard();
  } else {
    out.lambda.resize(nev);
    out.phi.resize(n, nev);
  }
  out.lambda.head(taken) = lambda_inverse.head(taken);
  out.err.head(taken) = err_inverse.head(taken);
  out.phi.leftCols(taken) = inverse.x.rightCols(taken).rowwise().reverse();
  report.inverse_modes = taken;
  // A rigid-body eigenvalue is zero only up to the perturbation of K, ~eps * lambda_max in
  // either form (the elastic modes' structured accuracy does not extend to an exact null space).
  for (Eigen::Index i = 0; i < std::min(rigid, taken); ++i) out.err(i) = eps * lambda_max;
  return out;
}

/// Spectra's CompInfo as a sentence.
inline std::string describe(Spectra::CompInfo info, Eigen::Index max_iterations) {
  switch (info) {
    case Spectra::CompInfo::Successful: return "converged";
    case Spectra::CompInfo::NotConverging:
      return "the Lanczos iteration did not converge in " + std::to_string(max_iterations) +
             " restarts (raise options.ncv or options.max_iterations)";
    case Spectra::CompInfo::NumericalIssue:
      return "the Lanczos iteration hit a numerical issue (Spectra: NumericalIssue)";
    case Spectra::CompInfo::NotComputed: break;
  }
  return "the Lanczos iteration did not run (Spectra: NotComputed)";
}

/// M-orthonormalise the columns of x (Cholesky of the Gram matrix x^T M x).
template <class Scalar>
bool m_orthonormalise(const Eigen::SparseMatrix<Scalar>& M, Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& x) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Matrix gram = x.transpose() * (M * x);
  const Eigen::LLT<Matrix> chol(gram);
  if (chol.info() != Eigen::Success) return false;
  chol.matrixU().template solveInPlace<Eigen::OnTheRight>(x);  // x U^{-1}
  return true;
}

/// Sparse solver: shift-and-invert Lanczos (Spectra) about a negative shift. With r known
/// rigid-body modes they are first found by subspace iteration with (K - sigma M)^{-1} M (their
/// eigenvalue 1/(-sigma) exceeds the elastic ones by lambda_{r+1}/(-sigma), so three steps
/// separate them to round-off) and deflated; Lanczos then sees only the elastic spectrum.
/// Without deflation the dominant 1/(-sigma) makes Lanczos return spurious and inaccurate
/// modes on small frames.
template <class Scalar>
RawModes<Scalar> sparse_modes(const AssembledFrame<Scalar>& frame, const ModalOptions<Scalar>& options,
                              Eigen::Index nev, Scalar lambda_scale, ModalSolveReport<Scalar>& report) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using std::isnan;
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  const Eigen::Index n = frame.num_free();
  RawModes<Scalar> out;
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
    Scalar rel = frame.num_rigid_body_modes == 0 ? eps * eps : Scalar(100) * eps;
    for (int attempt = 0; attempt < 5 && !ok; ++attempt, rel *= Scalar(1000)) {
      sigma = -rel * lambda_scale;
      ++report.factorizations;
      ok = op.try_factorize(sigma);
    }
    if (!ok) {
      out.failure = "no negative shift made K - sigma M positive definite (K is indefinite)";
      return out;
    }
  }
  report.shift = sigma;

  const Eigen::Index rigid = std::max<Eigen::Index>(frame.num_rigid_body_modes, 0);
  Matrix rigid_phi(n, 0);
  Vector rigid_lambda(0);
  if (rigid > 0) {
    // Deterministic start (a fixed linear congruential sequence), three subspace iterations.
    rigid_phi.resize(n, rigid);
    std::uint32_t state = 20261123u;
    for (Eigen::Index j = 0; j < rigid; ++j)
      for (Eigen::Index i = 0; i < n; ++i) {
        state = state * 1664525u + 1013904223u;
        rigid_phi(i, j) = Scalar(state >> 8) / Scalar(1u << 24) - Scalar(0.5);
      }
    Vector mx(n);
    for (int it = 0; it < 3; ++it) {
      for (Eigen::Index j = 0; j < rigid; ++j) {
        mx = frame.mass * rigid_phi.col(j);
        op.perform_op(mx.data(), rigid_phi.col(j).data());
      }
      if (!m_orthonormalise(frame.mass, rigid_phi)) {
        out.failure = "the rigid-body subspace iteration lost rank";
        return out;
      }
    }
    // Rayleigh-Ritz in the subspace: the rigid-body lambdas (round-off).
    const Matrix kr = rigid_phi.transpose() * (frame.stiffness * rigid_phi);
    const Eigen::SelfAdjointEigenSolver<Matrix> rr(Scalar(0.5) * (kr + kr.transpose()));
    rigid_lambda = rr.eigenvalues();
    rigid_phi = rigid_phi * rr.eigenvectors();
    report.deflated = rigid;
    if (nev <= rigid) {
      out.lambda = rigid_lambda.head(nev);
      out.phi = rigid_phi.leftCols(nev);
      out.err = Vector::Constant(nev, std::numeric_limits<Scalar>::infinity());
      return out;
    }
    op.deflate(rigid_phi);
  }

  const Eigen::Index nev_elastic = nev - rigid, n_elastic = n - rigid;
  Eigen::Index ncv = options.ncv > 0 ? options.ncv : std::max<Eigen::Index>(2 * nev_elastic + 1, nev_elastic + 20);
  ncv = std::min(std::max(ncv, nev_elastic + 1), n_elastic);
  report.ncv = ncv;
  if (nev_elastic >= ncv) {
    out.failure = "too few free DOFs beyond the rigid-body modes for a Lanczos basis";
    return out;
  }
  Spectra::SparseSymMatProd<Scalar> mass_op(frame.mass);
  Spectra::SymGEigsShiftSolver<LdltShiftInvert<Scalar>, Spectra::SparseSymMatProd<Scalar>,
                               Spectra::GEigsMode::ShiftInvert>
      eigs(op, mass_op, nev_elastic, ncv, sigma);
  // Start vector: all ones, M-orthogonal to the deflated modes.
  Vector start = Vector::Ones(n);
  if (rigid > 0) start -= rigid_phi * (rigid_phi.transpose() * (frame.mass * start));
  eigs.init(start.data());
  eigs.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
               Spectra::SortRule::SmallestAlge);
  report.iterations = eigs.num_iterations();
  report.operations = eigs.num_operations();
  if (eigs.info() != Spectra::CompInfo::Successful) {
    out.failure = describe(eigs.info(), options.max_iterations);
    return out;
  }
  out.lambda.resize(nev);
  out.phi.resize(n, nev);
  out.err.resize(nev);
  out.lambda << rigid_lambda, eigs.eigenvalues();
  out.phi << rigid_phi, eigs.eigenvectors();
  // Ritz value theta = 1/(lambda - sigma) converged to tolerance * theta: lambda - sigma to the
  // same relative accuracy; a rigid (deflated) mode is zero by construction.
  out.err << Vector::Constant(rigid, std::numeric_limits<Scalar>::infinity()),
      (options.tolerance * (eigs.eigenvalues().array() - sigma)).matrix();
  return out;
}

}  // namespace detail

/// The lowest modes of K phi = lambda M phi, lambda = omega^2, over the free DOFs of `frame`.
///
/// At most options.num_modes modes, dropping those with omega > options.max_omega. Modes are
/// sorted ascending and mass-normalised (Phi^T M Phi = I). The first
/// frame.num_rigid_body_modes modes are rigid-body modes (omega = 0); when that count is unknown
/// (-1), those with lambda <= options.rigid_body_tolerance * trace(K)/trace(M) are.
/// Dense solver: Cholesky reduction of K phi = lambda M phi, and of the inverse form
/// M phi = mu (K + s M) phi for the low modes of an ill-conditioned K. Sparse solver: Spectra
/// SymGEigsShiftSolver (shift-and-invert Lanczos) about a negative shift sigma, with the
/// rigid-body modes deflated (docs/modal.md). Every returned pair is checked (backward error,
/// mass-orthonormality, sign, zero eigenvalues against the rigid-body count); a failed sparse
/// solve falls back to the dense solver up to options.dense_fallback_limit free DOFs
/// (report->fallback_reason says why).
/// \throws std::invalid_argument for invalid options, num_modes > number of free DOFs, a
///         Sparse request with num_modes >= number of free DOFs, or when no mode has
///         omega <= max_omega
/// \throws std::domain_error naming the cause when the modes fail the checks (or Lanczos fails)
///         and no (further) fallback is possible
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
  const Scalar rigid_limit = options.rigid_body_tolerance * lambda_scale;
  const Eigen::Index known_rigid = frame.num_rigid_body_modes;
  const Scalar eps = std::numeric_limits<Scalar>::epsilon();
  // Backward-error tolerance: a backward-stable dense solver leaves ~p(n) eps (p(n) ~ n in the
  // worst case, ~sqrt(n) typically); Lanczos leaves ~options.tolerance (the Ritz residual bound
  // times ||K - sigma M|| / ||K||). Orthonormality: ~eps / (relative gap) for the dense solver,
  // ~options.tolerance for Lanczos; sqrt(eps) admits close (symmetric-frame) pairs.
  const auto solve_and_check = [&](ModalSolver which, detail::ModeCheck<Scalar>& check) {
    detail::RawModes<Scalar> raw = which == ModalSolver::Dense
                                       ? detail::dense_modes(frame, nev, lambda_scale, rigid_limit, local_report)
                                       : detail::sparse_modes(frame, options, nev, lambda_scale, local_report);
    if (!raw.failure.empty()) {
      check.failure = raw.failure;
      return raw;
    }
    detail::mass_normalise(frame.mass, raw);
    using std::sqrt;
    const Scalar backward_tol = Scalar(100) * Scalar(std::max<Eigen::Index>(n, 10)) * eps +
                                (which == ModalSolver::Sparse ? Scalar(10) * options.tolerance : Scalar(0));
    const Scalar orth_tol = sqrt(eps) + (which == ModalSolver::Sparse ? Scalar(10) * options.tolerance : Scalar(0));
    check = detail::check_modes(frame.stiffness, frame.mass, raw, known_rigid, backward_tol, orth_tol);
    local_report.backward_error = check.max_backward_error;
    local_report.orthonormality_error = check.max_orthonormality_error;
    return raw;
  };
  detail::ModeCheck<Scalar> check;
  detail::RawModes<Scalar> raw = solve_and_check(solver, check);
  if (!check.failure.empty() && solver == ModalSolver::Sparse) {
    if (n > options.dense_fallback_limit)
      throw std::domain_error(std::string(where) + ": the sparse solver failed: " + check.failure +
                               "; no dense fallback for " + std::to_string(n) +
                               " free DOFs > options.dense_fallback_limit = " +
                               std::to_string(options.dense_fallback_limit));
    local_report.fallback_reason = check.failure;
    local_report.solver = solver = ModalSolver::Dense;
    local_report.shift = Scalar(0);  // ncv, iterations, ... keep describing the failed attempt
    check = detail::ModeCheck<Scalar>{};
    raw = solve_and_check(solver, check);
  }
  if (report) *report = local_report;
  if (!check.failure.empty())
    throw std::domain_error(std::string(where) + ": the dense solver failed: " + check.failure +
                             (local_report.fallback_reason.empty()
                                  ? std::string()
                                  : " (after the sparse solver failed: " + local_report.fallback_reason + ")"));

  // Sort ascending, classify rigid-body modes, truncate at max_omega.
  const Eigen::Index found = raw.lambda.size();
  std::vector<Eigen::Index> order(static_cast<std::size_t>(found));
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  std::sort(order.begin(), order.end(),
            [&](Eigen::Index a, Eigen::Index b) { return raw.lambda(a) < raw.lambda(b); });
  Eigen::Index keep = 0, rigid = 0;
  typename ModalBasis<Scalar>::Vector omega(found);
  for (Eigen::Index i = 0; i < found; ++i) {
    const Scalar lambda = raw.lambda(order[static_cast<std::size_t>(i)]);
    // Known count: the checks established that the first known_rigid are the zero eigenvalues.
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
  for (Eigen::Index i = 0; i < keep; ++i) phi.col(i) = raw.phi.col(order[static_cast<std::size_t>(i)]);
  return ModalBasis<Scalar>(omega.head(keep), std::move(phi), frame.dofs, frame.model_id, rigid);
}

}  // namespace stickslip

#ifdef STICKSLIP_COMPILED
// The compiled mode: compute_modes<double> is instantiated once, in stickslip::compiled
// (src/compute_modes.cpp).
namespace stickslip {
extern template ModalBasis<double> compute_modes<double>(const AssembledFrame<double>&,
                                                         const ModalOptions<double>&,
                                                         ModalSolveReport<double>*);
}  // namespace stickslip
#endif

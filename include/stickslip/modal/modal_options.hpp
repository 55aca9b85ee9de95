#pragma once
/// \file modal_options.hpp
/// \brief Options of compute_modes: how many modes, which eigensolver, its tolerances.

#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>

namespace stickslip {

/// Eigensolver used by compute_modes.
enum class ModalSolver : std::uint8_t {
  Auto,   ///< Dense when num_free <= dense_limit (or num_modes is a large share of num_free), else Sparse
  Dense,  ///< Cholesky reduction of dense K, M (and its inverse form for ill-conditioned K), O(n^3)
  Sparse  ///< Spectra shift-and-invert Lanczos with a sparse LDL^T of K - sigma M
};

/// Name of a solver ("auto", "dense", "sparse").
inline const char* to_string(ModalSolver s) noexcept {
  switch (s) {
    case ModalSolver::Auto: return "auto";
    case ModalSolver::Dense: return "dense";
    case ModalSolver::Sparse: return "sparse";
  }
  return "unknown";
}

/// Options of compute_modes. Aggregate: `ModalOptions<double>{10, 2e4, ModalSolver::Auto, 400}`.
template <class Scalar_>
struct ModalOptions {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Index type (Eigen's).
  using Index = Eigen::Index;

  Index num_modes = 10;  ///< at most this many lowest modes (>= 1, <= number of free DOFs)
  Scalar max_omega = std::numeric_limits<Scalar>::infinity();  ///< drop modes above [rad/s]
  /// Eigensolver: Auto (default), Dense or Sparse.
  ModalSolver solver = ModalSolver::Auto;
  Index dense_limit = 400;  ///< Auto uses Dense up to this many free DOFs
  /// Shift sigma [rad^2/s^2] of the sparse solver; NaN selects it automatically (see
  /// docs/modal.md). A user value must be < 0 so that K - sigma M is positive definite.
  Scalar shift = std::numeric_limits<Scalar>::quiet_NaN();
  Index ncv = 0;                 ///< Lanczos basis size of the sparse solver; 0 = automatic
  Scalar tolerance = Scalar(1e-10);  ///< relative Ritz-value tolerance of the sparse solver
  Index max_iterations = 1000;   ///< restarts allowed to the sparse solver
  /// Used only when AssembledFrame::num_rigid_body_modes is unknown (-1): a mode with
  /// omega^2 <= rigid_body_tolerance * trace(K)/trace(M) is then a rigid-body mode (omega = 0).
  Scalar rigid_body_tolerance = Scalar(1e-12);
  /// When the sparse solver fails or its modes fail the checks (docs/modal.md), compute_modes
  /// falls back to the dense solver up to this many free DOFs, and throws above.
  Index dense_fallback_limit = 3000;

  /// \throws std::invalid_argument naming `where` and the offending field
  void validate(const std::string& where) const {
    if (num_modes < 1) detail::throw_invalid(where, "options.num_modes must be >= 1", num_modes);
    if (!(max_omega > Scalar(0))) detail::throw_invalid(where, "options.max_omega must be > 0", max_omega);
    if (dense_limit < 0) detail::throw_invalid(where, "options.dense_limit must be >= 0", dense_limit);
    using std::isnan;
    if (!isnan(shift) && !(shift < Scalar(0) && shift > -std::numeric_limits<Scalar>::infinity()))
      detail::throw_invalid(where, "options.shift must be NaN (automatic) or finite and < 0", shift);
    if (ncv < 0) detail::throw_invalid(where, "options.ncv must be >= 0 (0 = automatic)", ncv);
    detail::require_positive(where, "options.tolerance", tolerance);
    if (max_iterations < 1)
      detail::throw_invalid(where, "options.max_iterations must be >= 1", max_iterations);
    detail::require_non_negative(where, "options.rigid_body_tolerance", rigid_body_tolerance);
    if (dense_fallback_limit < 0)
      detail::throw_invalid(where, "options.dense_fallback_limit must be >= 0", dense_fallback_limit);
  }
};

}  // namespace stickslip

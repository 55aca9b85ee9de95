#pragma once
/// \file modal_basis.hpp
/// \brief Mass-normalised modes of a frame, their frequencies and modal damping (paper eq. 9).

#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/dof_map.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

namespace stickslip {

/// The n lowest modes of K phi = omega^2 M phi over the free DOFs of a frame: omega ascending
/// [rad/s], Phi (num_free x n) with Phi^T M Phi = I and Phi^T K Phi = diag(omega^2). The free-DOF
/// displacement is x = Phi q (paper eq. 9), and each modal coordinate obeys
/// q_i'' + c_i q_i' + omega_i^2 q_i = phi_i^T f with c_i = damping_coefficients()(i)
/// (= 2 zeta_i omega_i for an elastic mode).
template <class Scalar_>
class ModalBasis {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Index type (Eigen's).
  using Index = Eigen::Index;
  /// Dynamic column vector (per-mode values).
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic matrix (Phi).
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// Dynamic row vector (a row of Phi).
  using RowVector = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>;
  /// A row of Phi (one nodal DOF, over the modes) without copy or allocation.
  using NodalRow = Eigen::Ref<const RowVector, 0, Eigen::InnerStride<>>;

  ModalBasis() = default;

  /// \param omega ascending circular frequencies [rad/s] (>= 0, rigid-body modes first)
  /// \param phi   mass-normalised modes, dofs.num_free() x omega.size()
  /// \param dofs  numbering of the free DOFs of the model the modes belong to
  /// \param model_id FrameModel::id() of that model at assembly
  /// \param num_rigid_body_modes number of leading zero-frequency (rigid-body) modes
  /// \throws std::invalid_argument on size mismatches, an empty basis, non-finite or negative or
  ///         descending omega, or num_rigid_body_modes outside [0, omega.size()]
  ModalBasis(Vector omega, Matrix phi, DofMap dofs, std::uint64_t model_id, Index num_rigid_body_modes)
      : omega_(std::move(omega)), phi_(std::move(phi)), dofs_(std::move(dofs)),
        model_id_(model_id), num_rigid_(num_rigid_body_modes) {
    static const char* where = "ModalBasis";
    if (omega_.size() < 1) detail::throw_invalid(where, "omega.size() must be >= 1", omega_.size());
    if (phi_.rows() != dofs_.num_free() || phi_.cols() != omega_.size())
      throw std::invalid_argument(std::string(where) + ": phi is " + std::to_string(phi_.rows()) +
                                  " x " + std::to_string(phi_.cols()) + ", expected num_free = " +
                                  std::to_string(dofs_.num_free()) + " x omega.size() = " +
                                  std::to_string(omega_.size()));
    for (Index i = 0; i < omega_.size(); ++i) {
      detail::require_non_negative(where, "omega", omega_(i));
      if (i > 0 && omega_(i) < omega_(i - 1))
        detail::throw_invalid(where, "omega must be ascending; omega(" + std::to_string(i) + ")", omega_(i));
    }
    if (num_rigid_ < 0 || num_rigid_ > omega_.size())
      detail::throw_invalid(where, "num_rigid_body_modes must be in [0, omega.size()]", num_rigid_);
    zeta_ = Vector::Zero(omega_.size());
    damping_ = Vector::Zero(omega_.size());
    zero_row_ = RowVector::Zero(omega_.size());
  }

  const Vector& omega() const noexcept { return omega_; }  ///< ascending [rad/s]
  /// Natural frequencies omega / (2 pi) [Hz].
  Vector frequencies_hz() const { return omega_ / (Scalar(2) * Scalar(EIGEN_PI)); }
  const Matrix& phi() const noexcept { return phi_; }  ///< num_free x size(), Phi^T M Phi = I
  /// Number of modes n.
  Index size() const noexcept { return omega_.size(); }
  /// Number of free DOFs (rows of Phi).
  Index num_free() const noexcept { return phi_.rows(); }
  /// Numbering of the free DOFs.
  const DofMap& dofs() const noexcept { return dofs_; }
  std::uint64_t model_id() const noexcept { return model_id_; }  ///< FrameModel::id() at assembly
  /// Number of leading rigid-body (zero-frequency) modes.
  Index num_rigid_body_modes() const noexcept { return num_rigid_; }
  /// Modal damping ratios zeta_i (0 until set; a rigid-body mode's ratio is 0, see
  /// damping_coefficients()).
  const Vector& damping_ratios() const noexcept { return zeta_; }
  /// Modal damping coefficients c_i [1/s] of q_i'' + c_i q_i' + omega_i^2 q_i = ...:
  /// 2 zeta_i omega_i, or alpha + beta omega_i^2 after with_rayleigh_damping (also for a
  /// rigid-body mode, which keeps the mass-proportional part alpha).
  const Vector& damping_coefficients() const noexcept { return damping_; }

  /// Row of Phi for a nodal DOF: the DOF's value in each mode (zeros when constrained).
  /// O(1), no allocation; the view stays valid while this basis lives.
  /// \throws std::invalid_argument for a node outside the model
  NodalRow nodal(NodeId node, Dof dof) const {
    const Index f = dofs_.free_index(node, dof);
    if (f < 0) return NodalRow(zero_row_);
    return NodalRow(phi_.row(f));
  }

  /// Free-DOF displacements x = Phi q. \throws std::invalid_argument when q.size() != size()
  template <class Derived>
  Vector expand(const Eigen::MatrixBase<Derived>& q) const {
    check_modal_vector("ModalBasis::expand", q.size());
    return phi_ * q;
  }

  /// Displacements of all 3 * num_nodes nodal DOFs (constrained DOFs 0), ordered 3 * node + dof.
  /// \throws std::invalid_argument when q.size() != size()
  template <class Derived>
  Vector nodal_displacements(const Eigen::MatrixBase<Derived>& q) const {
    check_modal_vector("ModalBasis::nodal_displacements", q.size());
    return dofs_.scatter(phi_ * q);
  }

  /// The n lowest modes (with their damping). \throws std::invalid_argument unless 1 <= n <= size()
  ModalBasis truncated(Index n) const {
    if (n < 1 || n > size())
      throw std::invalid_argument("ModalBasis::truncated: n = " + std::to_string(n) +
                                  " must be in [1, " + std::to_string(size()) + "]");
    ModalBasis out(omega_.head(n), phi_.leftCols(n), dofs_, model_id_,
                   num_rigid_ < n ? num_rigid_ : n);
    out.zeta_ = zeta_.head(n);
    out.damping_ = damping_.head(n);
    return out;
  }

  /// Copy with modal damping ratios zeta_i (c_i = 2 zeta_i omega_i, so 0 for rigid-body modes).
  /// \throws std::invalid_argument when ratios.size() != size() or a ratio is non-finite or < 0
  ModalBasis with_modal_damping(const Vector& ratios) const {
    static const char* where = "ModalBasis::with_modal_damping";
    check_modal_vector(where, ratios.size());
    for (Index i = 0; i < ratios.size(); ++i) detail::require_non_negative(where, "ratios", ratios(i));
    ModalBasis out(*this);
    out.zeta_ = ratios;
    out.damping_ = Scalar(2) * ratios.cwiseProduct(omega_);
    return out;
  }

  /// Copy with Rayleigh damping C = alpha M + beta K: c_i = alpha + beta omega_i^2 and
  /// zeta_i = alpha / (2 omega_i) + beta omega_i / 2 for omega_i > 0; for a rigid-body mode
  /// zeta_i = 0 (undefined) while c_i = alpha is kept.
  /// \throws std::invalid_argument when alpha [1/s] or beta [s] is non-finite or < 0
  ModalBasis with_rayleigh_damping(Scalar alpha, Scalar beta) const {
    static const char* where = "ModalBasis::with_rayleigh_damping";
    detail::require_non_negative(where, "alpha", alpha);
    detail::require_non_negative(where, "beta", beta);
    ModalBasis out(*this);
    for (Index i = 0; i < size(); ++i) {
      const Scalar w = omega_(i);
      out.damping_(i) = alpha + beta * w * w;
      out.zeta_(i) = w > Scalar(0) ? out.damping_(i) / (Scalar(2) * w) : Scalar(0);
    }
    return out;
  }

 private:
  void check_modal_vector(const char* where, Index n) const {
    if (n != size())
      throw std::invalid_argument(std::string(where) + ": vector size " + std::to_string(n) +
                                  " must equal the number of modes " + std::to_string(size()));
  }

  Vector omega_;
  Matrix phi_;
  DofMap dofs_;
  std::uint64_t model_id_ = 0;
  Index num_rigid_ = 0;
  Vector zeta_;
  Vector damping_;
  RowVector zero_row_;
};

}  // namespace stickslip

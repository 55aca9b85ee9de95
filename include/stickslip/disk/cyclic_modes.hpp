#pragma once
/// \file cyclic_modes.hpp
/// \brief Modes of a tuned bladed disk from one sector by cyclic symmetry: for each nodal
/// diameter h = 0 ... floor(N/2) the sector's Hermitian eigenproblem K_h x = omega^2 M_h x, and
/// its modes expanded to the annulus (docs/disks.md).
///
/// A mode of the annulus with nodal diameter h has, in sector k, the displacement
///   u_k = Re(x e^{i k phi_h}),   phi_h = 2 pi h / N   (inter-blade phase angle),
/// with x the complex sector shape. Sector k's right attachment R is coupled to sector k + 1's
/// left L (u_L of sector k + 1 = x_L e^{i phi} relative to sector k) and its L to sector k - 1's
/// R (x_R e^{-i phi}), so with the coupling blocks K_c = [K_RR, K_RL; K_LR, K_LL]:
///   K_h = K_s + P_R^T K_RR P_R + P_L^T K_LL P_L + e^{i phi} P_R^T K_RL P_L + e^{-i phi} P_L^T K_LR P_R
/// (the same for M with the ring element's mass), Hermitian since K_LR = K_RL^T. For h = 0 and
/// h = N/2 (N even) K_h is real and each mode is one annulus mode; for 0 < h < N/2 each omega is
/// a degenerate pair of annulus modes, Re and Im of x e^{i k phi} (standing waves, or their
/// combinations: the forward and backward travelling waves).

#include "stickslip/beam/mass_type.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/modal/modal_basis.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Options of compute_cyclic_modes.
template <class Scalar>
struct CyclicModalOptions {
  Eigen::Index num_modes = 10;  ///< lowest modes kept per nodal diameter (>= 1)
  Scalar max_omega = std::numeric_limits<Scalar>::infinity();  ///< drop modes above [rad/s]
  MassType mass_type = MassType::Consistent;  ///< element mass matrices, as FrameModel::assemble
  /// A mode with omega^2 <= rigid_body_tolerance * trace(K_h) / trace(M_h) is a rigid-body mode
  /// (omega = 0).
  Scalar rigid_body_tolerance = Scalar(1e-12);
};

/// The modes of one nodal diameter h.
template <class Scalar>
struct NodalDiameterModes {
  using ComplexMatrix = Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, Eigen::Dynamic>;  ///< shapes
  Eigen::Index nodal_diameter = 0;                  ///< h
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> omega;   ///< ascending [rad/s]
  /// Complex sector shapes x (columns, over the reference sector's free DOFs), x^H M_h x = 1;
  /// real for h = 0 and h = N/2.
  ComplexMatrix sector_shapes;
  bool pairs = false;  ///< 0 < h < N/2: each omega is a degenerate pair of annulus modes
  /// Which eigenproblem form gave the modes: true the inverse form M_h x = mu K_h x (K_h positive
  /// definite; eigenvalue error ~ eps omega^2 * omega^2 / omega_1^2 relative, accurate at the
  /// lowest modes), false the standard Cholesky reduction of M_h (error ~ eps omega_max^2).
  bool inverse_form = false;
};

/// Cyclic-symmetry modes of a tuned disk: the families h = 0 ... floor(N/2).
template <class Scalar>
struct CyclicModes {
  Eigen::Index num_sectors = 0;                       ///< N
  std::uint64_t model_id = 0;                         ///< the disk's frame().id()
  std::vector<NodalDiameterModes<Scalar>> families;   ///< families[h], h = 0 ... N/2
};

/// K_h and M_h of the reference sector for nodal diameter h (see the file comment), dense over
/// the sector's free DOFs. \throws std::invalid_argument for h outside [0, N)
template <class Scalar>
std::pair<Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, Eigen::Dynamic>,
          Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, Eigen::Dynamic>>
cyclic_sector_matrices(const BladedDisk<Scalar>& disk, Eigen::Index h, MassType type = MassType::Consistent) {
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
  using Index = Eigen::Index;
  const Index N = disk.num_sectors();
  if (h < 0 || h >= N)
    detail::throw_invalid("cyclic_sector_matrices", "h must be in [0, num_sectors = " + std::to_string(N) + ")", h);
  const AssembledFrame<Scalar> sector = disk.sector_frame().assemble(type);
  ComplexMatrix K = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>(sector.stiffness).template cast<Complex>();
  ComplexMatrix M = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>(sector.mass).template cast<Complex>();
  const auto kc = disk.coupling_stiffness();
  const auto mc = disk.coupling_mass(type);
  const auto dofs = disk.coupling_sector_dofs();
  using std::cos;
  using std::sin;
  const Scalar phi = Scalar(2) * Scalar(EIGEN_PI) * Scalar(h) / Scalar(N);
  const Complex e(cos(phi), sin(phi));  // e^{i phi}
  for (Index r = 0; r < 6; ++r) {
    const Index fr = dofs[static_cast<std::size_t>(r)];
    if (fr < 0) continue;
    for (Index c = 0; c < 6; ++c) {
      const Index fc = dofs[static_cast<std::size_t>(c)];
      if (fc < 0) continue;
      // Same block (RR or LL): factor 1; RL: e^{i phi}; LR: e^{-i phi}.
      const Complex f = (r < 3) == (c < 3) ? Complex(1) : (r < 3 ? e : std::conj(e));
      K(fr, fc) += f * kc(r, c);
      M(fr, fc) += f * mc(r, c);
    }
  }
  return {std::move(K), std::move(M)};
}

namespace detail {

/// Lowest eigenpairs of the Hermitian pencil (K, M), M positive definite: the inverse form
/// M x = mu K x when K factorises (positive definite), else the standard form. lambda ascending,
/// x M-normalised. Returns true when the inverse form was used.
template <class Matrix>
bool hermitian_pencil_modes(const Matrix& K, const Matrix& M, Eigen::Matrix<typename Eigen::NumTraits<typename Matrix::Scalar>::Real, Eigen::Dynamic, 1>& lambda,
                            Matrix& x) {
  using Real = typename Eigen::NumTraits<typename Matrix::Scalar>::Real;
  const Eigen::Index n = K.rows();
  const Eigen::LLT<Matrix> k_chol(K);
  if (k_chol.info() == Eigen::Success) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> es(M, K);  // M x = mu K x, mu = 1 / lambda
    if (es.info() == Eigen::Success && es.eigenvalues().minCoeff() > Real(0)) {
      lambda = es.eigenvalues().reverse().cwiseInverse();
      x = es.eigenvectors().rowwise().reverse();
      for (Eigen::Index j = 0; j < n; ++j) {
        using std::sqrt;
        x.col(j) /= sqrt(std::real(x.col(j).dot(M * x.col(j))));
      }
      return true;
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> es(K, M);  // eigenvectors: x^H M x = 1
  if (es.info() != Eigen::Success)
    throw std::invalid_argument("compute_cyclic_modes: the eigen solve of the sector's K_h, M_h failed (M_h not "
                                "positive definite?)");
  lambda = es.eigenvalues();
  x = es.eigenvectors();
  return false;
}

}  // namespace detail

/// Modes of the tuned disk by cyclic symmetry, from the reference sector alone: for each h =
/// 0 ... floor(N/2), the lowest options.num_modes eigenpairs of K_h x = omega^2 M_h x (dense,
/// O(n_s^3) per h for a sector of n_s free DOFs, against O((N n_s)^3) for the annulus).
/// \throws std::invalid_argument naming the option (num_modes < 1, max_omega <= 0,
///         rigid_body_tolerance < 0), for a mistuned disk (mistuning), or when an eigen solve
///         fails
template <class Scalar>
CyclicModes<Scalar> compute_cyclic_modes(const BladedDisk<Scalar>& disk, const CyclicModalOptions<Scalar>& options = {}) {
  static const char* where = "compute_cyclic_modes";
  using Index = Eigen::Index;
  using Complex = std::complex<Scalar>;
  using ComplexMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
  using RealMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  if (options.num_modes < 1) detail::throw_invalid(where, "options.num_modes must be >= 1", options.num_modes);
  if (!(options.max_omega > Scalar(0))) detail::throw_invalid(where, "options.max_omega must be > 0", options.max_omega);
  detail::require_non_negative(where, "options.rigid_body_tolerance", options.rigid_body_tolerance);
  if (!disk.is_tuned())
    throw std::invalid_argument(std::string(where) + ": disk.mistuning() must be all zero (cyclic symmetry holds "
                                                     "only for a tuned disk; use the annulus' modes)");
  const Index N = disk.num_sectors();
  CyclicModes<Scalar> out;
  out.num_sectors = N;
  out.model_id = disk.frame().id();
  for (Index h = 0; 2 * h <= N; ++h) {
    auto km = cyclic_sector_matrices(disk, h, options.mass_type);
    NodalDiameterModes<Scalar> family;
    family.nodal_diameter = h;
    family.pairs = h > 0 && 2 * h < N;
    Vector lambda;
    ComplexMatrix x;
    if (family.pairs) {
      family.inverse_form = detail::hermitian_pencil_modes(km.first, km.second, lambda, x);
    } else {  // real symmetric: real shapes, also inside repeated frequencies of the family
      const RealMatrix K = km.first.real(), M = km.second.real();
      RealMatrix xr;
      family.inverse_form = detail::hermitian_pencil_modes(K, M, lambda, xr);
      x = xr.template cast<Complex>();
    }
    const Scalar scale = km.first.trace().real() / km.second.trace().real();
    Index keep = std::min<Index>(options.num_modes, lambda.size());
    using std::sqrt;
    Vector omega(keep);
    for (Index j = 0; j < keep; ++j)
      omega(j) = lambda(j) <= options.rigid_body_tolerance * scale ? Scalar(0) : sqrt(lambda(j));
    while (keep > 0 && omega(keep - 1) > options.max_omega) --keep;
    family.omega = omega.head(keep);
    family.sector_shapes = x.leftCols(keep);
    out.families.push_back(std::move(family));
  }
  return out;
}

/// The annulus modes of family h, mode j (columns over the annulus' free DOFs, mass-normalised
/// against disk.assemble(type)): for 0 < h < N/2 the pair sqrt(2/N) Re(x e^{i k phi}),
/// sqrt(2/N) Im(x e^{i k phi}) in sector k; else the single sqrt(1/N) x (+-1)^k.
/// \throws std::invalid_argument for a family or mode out of range, or modes of another disk
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> expand_cyclic_mode(const BladedDisk<Scalar>& disk,
                                                                         const CyclicModes<Scalar>& modes,
                                                                         Eigen::Index h, Eigen::Index j) {
  static const char* where = "expand_cyclic_mode";
  using Index = Eigen::Index;
  using Complex = std::complex<Scalar>;
  if (modes.model_id != disk.frame().id())
    detail::throw_invalid(where, "modes must be computed from this disk (model id)", modes.model_id);
  if (h < 0 || h >= static_cast<Index>(modes.families.size()))
    detail::throw_invalid(where, "h must be in [0, floor(N/2)]", h);
  const NodalDiameterModes<Scalar>& f = modes.families[static_cast<std::size_t>(h)];
  if (j < 0 || j >= f.omega.size()) detail::throw_invalid(where, "j must be in [0, family size)", j);
  const Index N = disk.num_sectors();
  using std::cos;
  using std::sin;
  using std::sqrt;
  const Index columns = f.pairs ? 2 : 1;
  const Scalar norm = sqrt((f.pairs ? Scalar(2) : Scalar(1)) / Scalar(N));
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> u =
      Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>::Zero(disk.annulus_dofs().num_free(), columns);
  for (Index k = 0; k < N; ++k) {
    // phase k h / N of a full turn, reduced exactly in integers before the trigonometry
    const Scalar angle = Scalar(2) * Scalar(EIGEN_PI) * Scalar((k * h) % N) / Scalar(N);
    const Complex e(cos(angle), sin(angle));
    for (Index i = 0; i < f.sector_shapes.rows(); ++i) {
      const Complex v = f.sector_shapes(i, j) * e * norm;
      const Index a = disk.annulus_free_index(k, i);
      u(a, 0) = v.real();
      if (f.pairs) u(a, 1) = v.imag();
    }
  }
  return u;
}

/// The cyclic modes of every family expanded to the annulus (pairs as two modes), ascending in
/// omega, as a ModalBasis of disk.frame(): the tuned disk's modes at the cost of one sector, for
/// ContactSystem and the other components. Damping none (set it on the result).
/// \throws std::invalid_argument for modes of another disk
template <class Scalar>
ModalBasis<Scalar> annulus_basis(const BladedDisk<Scalar>& disk, const CyclicModes<Scalar>& modes) {
  using Index = Eigen::Index;
  struct Entry {
    Scalar omega;
    Index h, j;
  };
  std::vector<Entry> entries;
  for (const auto& f : modes.families)
    for (Index j = 0; j < f.omega.size(); ++j) entries.push_back({f.omega(j), f.nodal_diameter, j});
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.omega < b.omega; });
  Index count = 0;
  for (const Entry& e : entries) count += modes.families[static_cast<std::size_t>(e.h)].pairs ? 2 : 1;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> omega(count);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> phi(disk.annulus_dofs().num_free(), count);
  Index c = 0, rigid = 0;
  for (const Entry& e : entries) {
    const auto u = expand_cyclic_mode(disk, modes, e.h, e.j);
    for (Index m = 0; m < u.cols(); ++m, ++c) {
      omega(c) = e.omega;
      phi.col(c) = u.col(m);
      if (e.omega == Scalar(0)) ++rigid;
    }
  }
  return ModalBasis<Scalar>(std::move(omega), std::move(phi), disk.annulus_dofs(), disk.frame().id(), rigid);
}

}  // namespace stickslip

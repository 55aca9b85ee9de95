#pragma once
/// \file cyclic_shift.hpp
/// \brief The cyclic index shift of a tuned bladed disk's state (blade k takes the place of
/// blade k + sigma) and the shift time tau over which engine-order forcing repeats itself up to
/// that shift: the symmetry a travelling wave's relative periodic orbit is closed with
/// (travelling_wave.hpp, docs/disks.md).

#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/disk/engine_order.hpp"
#include "stickslip/modal/modal_basis.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

namespace stickslip {

/// The engine-order symmetry of a tuned disk: with r = EO mod N and g = gcd(r, N) (g = N for
/// r = 0), the loads F_k(t) = F cos(Omega t + 2 pi EO k / N) satisfy
///     F_k(t + tau) = F_{k + sigma}(t),   tau = (g / N) T,   r sigma = g (mod N),
/// the shortest delay tau > 0 after which the forcing repeats up to a shift of the blades. A
/// tuned disk's travelling-wave response has the same symmetry, x(t + tau) = S x(t) with
/// (S x)_k = x_{k + sigma} (blade k's state after tau is blade k + sigma's now), and
/// L = N / g shifts make one forcing period T.
struct EngineOrderSymmetry {
  Eigen::Index num_sectors = 0;      ///< N
  Eigen::Index engine_order = 0;     ///< EO reduced to [0, N)
  Eigen::Index sector_shift = 0;     ///< sigma in [0, N)
  Eigen::Index shifts_per_period = 1;  ///< L = N / g = T / tau
  /// tau / T = g / N = 1 / L.
  double period_fraction() const { return 1.0 / double(shifts_per_period); }
};

/// sigma, g and L for engine order `engine_order` on `num_sectors` blades (see
/// EngineOrderSymmetry). \throws std::invalid_argument for num_sectors < 2
inline EngineOrderSymmetry engine_order_symmetry(Eigen::Index engine_order, Eigen::Index num_sectors) {
  if (num_sectors < 2) detail::throw_invalid("engine_order_symmetry", "num_sectors must be >= 2", num_sectors);
  EngineOrderSymmetry s;
  s.num_sectors = num_sectors;
  s.engine_order = reduced_engine_order(engine_order, num_sectors);
  const Eigen::Index g = s.engine_order == 0 ? num_sectors : std::gcd(s.engine_order, num_sectors);
  s.shifts_per_period = num_sectors / g;
  // r sigma = g (mod N): r = 0 (g = N, tau = T) takes sigma = 1 (every blade alike).
  s.sector_shift = 1;
  if (s.engine_order != 0)
    for (Eigen::Index sigma = 1; sigma < num_sectors; ++sigma)
      if ((s.engine_order * sigma) % num_sectors == g % num_sectors) {
        s.sector_shift = sigma;
        break;
      }
  return s;
}

/// The shift in the annulus basis' modal coordinates: with P the permutation of the annulus'
/// free DOFs that puts sector k + sigma's DOFs in sector k's place ((P u)_k = u_{k + sigma}) and
/// Phi the mass-normalised modes, S_q = Phi^T M P Phi, so that q -> S_q q is u -> P u for every
/// u in the span of Phi. A basis closed under the shift (whole nodal-diameter families, e.g.
/// annulus_basis with every family's modes, or every mode of the annulus) makes S_q orthogonal;
/// a truncation that splits a degenerate pair does not, and is refused.
/// \throws std::invalid_argument naming the parameter: a basis of another frame (basis), a
///         mistuned disk (disk: no cyclic symmetry), sigma out of [0, N), or a basis not closed
///         under the shift (basis: S_q^T S_q departs from I by more than `tolerance`).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> modal_cyclic_shift(const BladedDisk<Scalar>& disk,
                                                                        const ModalBasis<Scalar>& basis,
                                                                        Eigen::Index sigma,
                                                                        Scalar tolerance = Scalar(1e-8)) {
  static const char* where = "modal_cyclic_shift";
  using Index = Eigen::Index;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  if (basis.model_id() != disk.frame().id())
    detail::throw_invalid(where, "basis must be a basis of disk.frame() (model id)", basis.model_id());
  if (!disk.is_tuned()) detail::throw_invalid(where, "disk must be tuned (no mistuning): a mistuned disk has no cyclic symmetry", "mistuned");
  const Index N = disk.num_sectors();
  if (sigma < 0 || sigma >= N) detail::throw_invalid(where, "sigma must be in [0, num_sectors)", sigma);
  const auto fe = disk.assemble();
  const Matrix& phi = basis.phi();
  // P Phi: row i of sector k's DOF takes the same DOF of sector k + sigma.
  Matrix shifted(phi.rows(), phi.cols());
  const Index P = disk.nodes_per_sector();
  for (Index i = 0; i < phi.rows(); ++i) {
    const auto nd = disk.annulus_dofs().node_dof(i);
    const Index k = nd.first / P, local = nd.first % P;
    const NodeId from = disk.node((k + sigma) % N, NodeId(local));
    shifted.row(i) = phi.row(disk.annulus_dofs().free_index(from, nd.second));
  }
  Matrix S = phi.transpose() * (fe.mass * shifted);
  const Scalar defect = (S.transpose() * S - Matrix::Identity(S.cols(), S.cols())).cwiseAbs().maxCoeff();
  if (!(defect <= tolerance))
    detail::throw_invalid(where, "basis must be closed under the blade shift (whole nodal-diameter families; a "
                                 "split degenerate pair is not): max |S^T S - I|", defect);
  return S;
}

}  // namespace stickslip

#pragma once
/// \file engine_order.hpp
/// \brief Engine-order excitation of a bladed disk: the same harmonic load on every blade with
/// the phase lag of a travelling wave, F_k(t) = F cos(Omega t + 2 pi EO k / N), as point loads.

#include "stickslip/beam/ids.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/model/point_load.hpp"
#include "stickslip/model/structure_point.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace stickslip {

/// The engine order EO reduced to [0, N): EO and EO + N (and EO - N) give the same load on every
/// blade, since blades sit only at k = 0 ... N - 1 (the aliasing of the zig-zag diagram); a
/// negative EO is the wave travelling the other way. \throws std::invalid_argument for N < 1
inline Eigen::Index reduced_engine_order(Eigen::Index engine_order, Eigen::Index num_sectors) {
  if (num_sectors < 1) detail::throw_invalid("reduced_engine_order", "num_sectors must be >= 1", num_sectors);
  return ((engine_order % num_sectors) + num_sectors) % num_sectors;
}

/// The nodal diameter h in [0, floor(N/2)] that engine order EO excites: h = EO mod N folded,
/// min(r, N - r) with r = reduced_engine_order(EO, N). The load F_k = Re(F e^{i 2 pi EO k / N}
/// e^{i Omega t}) holds only the spatial harmonics EO and -EO (mod N), the two travelling
/// waves of the family h. \throws std::invalid_argument for N < 1
inline Eigen::Index engine_order_nodal_diameter(Eigen::Index engine_order, Eigen::Index num_sectors) {
  const Eigen::Index r = reduced_engine_order(engine_order, num_sectors);
  return r <= num_sectors - r ? r : num_sectors - r;
}

/// One PointLoad per blade: on member `sector_member` (reference sector numbering) of sector k at
/// `coordinate` (mapped by BladedDisk::point), in `direction`, F_k(t) = amplitude cos(omega t + 2 pi EO k / N) (as PointLoad's
/// amplitude sin(omega t + phase) with phase = 2 pi ((EO mod N) k mod N) / N + pi / 2, reduced in
/// integers so that large EO k lose no phase accuracy). Any integer EO is accepted (see
/// reduced_engine_order). Loads k = 0 ... N - 1 in order.
/// \throws std::invalid_argument naming the parameter: sector_member out of range, coordinate,
///         amplitude or omega not finite (the coordinate's range is checked where the loads are
///         used, e.g. ContactSystem)
template <class Scalar>
std::vector<PointLoad<Scalar>> engine_order_loads(const BladedDisk<Scalar>& disk, MemberId sector_member,
                                                  Scalar coordinate, LoadDirection direction, Scalar amplitude,
                                                  Scalar omega, Eigen::Index engine_order) {
  static const char* where = "engine_order_loads";
  using Index = Eigen::Index;
  if (sector_member < 0 || sector_member >= disk.members_per_sector())
    detail::throw_invalid(where, "sector_member must be in [0, members_per_sector() = " +
                                     std::to_string(disk.members_per_sector()) + ")",
                          Index(sector_member));
  detail::require_finite(where, "coordinate", coordinate);
  detail::require_finite(where, "amplitude", amplitude);
  detail::require_finite(where, "omega", omega);
  const Index N = disk.num_sectors();
  const Index eo = reduced_engine_order(engine_order, N);
  std::vector<PointLoad<Scalar>> loads;
  loads.reserve(static_cast<std::size_t>(N));
  for (Index k = 0; k < N; ++k) {
    const Scalar phase = Scalar(2) * Scalar(EIGEN_PI) * Scalar((eo * k) % N) / Scalar(N) + Scalar(EIGEN_PI) / Scalar(2);
    const StructurePoint<Scalar> at = disk.point(k, StructurePoint<Scalar>{sector_member, coordinate});
    loads.push_back(PointLoad<Scalar>::harmonic(at.member, at.coordinate, direction, amplitude, omega, phase));
  }
  return loads;
}

}  // namespace stickslip

#pragma once
/// \file orbit_probe.hpp
/// \brief Probes: an orbit's outputs in physical units at points of the structure chosen by the
/// user (the displacement or velocity of a material point along an in-plane direction), measured
/// over the orbit's own period from the run that closed it (ShootingOptions::outputs,
/// OrbitSignal).

#include <stickslip/beam/frame_model.hpp>
#include <stickslip/detail/validate.hpp>
#include <stickslip/modal/modal_basis.hpp>
#include <stickslip/model/structure_point.hpp>
#include <stickslip/steady_state/shooting_options.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace stickslip {

/// What a probe measures at its point.
enum class ProbeQuantity : std::uint8_t {
  Displacement,  ///< u_d = psi_d(point) . q [m]
  Velocity       ///< u_d' = psi_d(point) . q' [m/s]
};

/// A probe: the displacement (or velocity) of `point` along `direction`, a unit in-plane vector.
template <class Scalar>
struct OrbitProbe {
  StructurePoint<Scalar> point;                     ///< member and coordinate [m] along it
  PlaneDirection<Scalar> direction;                 ///< unit direction (global X by default)
  ProbeQuantity quantity = ProbeQuantity::Displacement;  ///< displacement or velocity
};

/// The output rows of `probes` for a modal state whose modal coordinates q start at `q_offset`
/// and their velocities q' at `qd_offset` (FrictionDampedSystem: q_offset(), qd_offset()), with
/// `state_size` columns: row j = psi_j (structure_point_row) placed over q or q'. The basis must
/// be the system's (its modes, in its order). \throws std::invalid_argument naming the probe for
/// a point off the frame, a direction that is not a unit vector, a basis of another model or
/// offsets that do not fit the state.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> probe_rows(
    const FrameModel<Scalar>& frame, const ModalBasis<Scalar>& basis,
    const std::vector<OrbitProbe<Scalar>>& probes, Eigen::Index state_size, Eigen::Index q_offset,
    Eigen::Index qd_offset) {
  static const std::string where = "probe_rows";
  const Eigen::Index n = basis.size();
  if (q_offset < 0 || q_offset + n > state_size)
    detail::throw_invalid(where, "q_offset + the basis' modes must fit state_size", q_offset);
  if (qd_offset < 0 || qd_offset + n > state_size)
    detail::throw_invalid(where, "qd_offset + the basis' modes must fit state_size", qd_offset);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> rows =
      Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>::Zero(
          static_cast<Eigen::Index>(probes.size()), state_size);
  for (std::size_t j = 0; j < probes.size(); ++j) {
    const OrbitProbe<Scalar>& p = probes[j];
    const auto row = structure_point_row(frame, basis, p.point, p.direction,
                                         where + ": probes[" + std::to_string(j) + "]");
    const Eigen::Index at = p.quantity == ProbeQuantity::Velocity ? qd_offset : q_offset;
    rows.row(static_cast<Eigen::Index>(j)).segment(at, n) = row.transpose();
  }
  return rows;
}

/// Sets options.outputs to the rows of `probes` for `system` (a FrictionDampedSystem built on
/// `frame` and `basis`), with `harmonics` harmonics each, and raises samples_per_period to
/// 2 harmonics + 1 where it is below: every orbit of Shooting and Continuation then carries
/// outputs[j], the probe's min, max, amplitude() (half the peak-to-peak), mean and harmonics
/// 1 .. harmonics in metres (m/s for a velocity), from the run that closed the orbit.
template <class Scalar, class System>
void set_probes(ShootingOptions<Scalar>& options, const System& system, const FrameModel<Scalar>& frame,
                const ModalBasis<Scalar>& basis, const std::vector<OrbitProbe<Scalar>>& probes,
                int harmonics = 3) {
  if (harmonics < 0) detail::throw_invalid("set_probes", "harmonics must be >= 0", harmonics);
  if (basis.size() != system.num_modes())
    detail::throw_invalid("set_probes", "basis must have the system's modes (" +
                                            std::to_string(system.num_modes()) + "), modes",
                          basis.size());
  options.outputs = probe_rows(frame, basis, probes, system.state_size(), system.q_offset(),
                               system.qd_offset());
  options.output_harmonics = harmonics;
  if (options.samples_per_period <= 2 * harmonics) options.samples_per_period = 2 * harmonics + 1;
}

}  // namespace stickslip

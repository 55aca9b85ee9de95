#pragma once
/// \file peak_response.hpp
/// \brief The largest stable steady response over every branch found (period-T branches,
/// subharmonic k T branches, the 2T branches born at flips, asymmetric ones): the objective of a
/// design search that must not miss a response the structure settles on because it is not on
/// the period-1 branch.

#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/orbit_signal.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

/// Which orbit sets the largest stable response (largest_stable_response).
template <class Scalar>
struct PeakResponse {
  bool found = false;        ///< a stable orbit with the output was found
  std::size_t branch = 0;    ///< index of its branch in the list given
  std::size_t point = 0;     ///< index of its point on that branch
  Scalar parameter = 0;      ///< the point's parameter
  Scalar value = 0;          ///< the output's half peak-to-peak over the orbit's own period
  Scalar period = 0;         ///< the orbit's period (k T for a subharmonic orbit)
};

/// The stable orbit (floquet.stable) with the largest amplitude (OrbitSignal::amplitude(): half
/// the peak-to-peak over the orbit's own period, its whole k T for a subharmonic orbit) of output
/// `output` (ShootingOptions::outputs) over every point of every branch in `branches`, and where
/// it is. Unstable orbits are left out: the structure does not stay on them. Not found when no
/// point is stable. Throws std::invalid_argument when a stable orbit has no output `output`.
template <class System>
PeakResponse<typename System::Scalar> largest_stable_response(
    const std::vector<const ContinuationResult<System>*>& branches, std::size_t output = 0) {
  PeakResponse<typename System::Scalar> best;
  for (std::size_t b = 0; b < branches.size(); ++b) {
    if (!branches[b]) continue;
    const auto& pts = branches[b]->points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto& o = pts[i].orbit;
      if (!o.ok() || !o.floquet.stable) continue;
      if (output >= o.outputs.size())
        throw std::invalid_argument("largest_stable_response: output " + std::to_string(output) +
                                    " is not among the orbits' outputs (ShootingOptions::outputs has " +
                                    std::to_string(o.outputs.size()) + " rows)");
      const auto a = o.outputs[output].amplitude();
      if (!best.found || a > best.value) {
        best.found = true;
        best.branch = b;
        best.point = i;
        best.parameter = pts[i].parameter;
        best.value = a;
        best.period = o.period;
      }
    }
  }
  return best;
}

}  // namespace stickslip

#pragma once
// The peak of a frequency-response curve that the structure can show: the largest tip amplitude
// over the curve's stable orbits. An unstable orbit is a point of the curve, not a response:
// the structure leaves it (a transient from it goes elsewhere), so it does not set the peak.

#include <cstddef>
#include <vector>

namespace blade {

/// Index of the stable point (Point::stable) with the largest Point::tip_amplitude, or
/// points.size() when no point is stable.
template <class Point>
std::size_t stable_peak(const std::vector<Point>& points) {
  std::size_t best = points.size();
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].stable && (best == points.size() || points[i].tip_amplitude > points[best].tip_amplitude)) best = i;
  return best;
}

}  // namespace blade

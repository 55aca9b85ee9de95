#pragma once
/// \file progress.hpp
/// \brief Progress of a periodic-orbit computation and an estimate of what remains: what
/// ShootingOptions::progress (per Newton iteration) and ContinuationOptions::progress (per point
/// of a branch) are called with. Times are the CPU seconds of the calling thread.

#include <algorithm>
#include <cmath>
#include <functional>

namespace stickslip {

/// One Newton iteration of Shooting, after its orbit run.
struct ShootingProgress {
  int iteration = 0;        ///< Newton iterations done (0: the run of the guess)
  int max_iterations = 0;   ///< ShootingOptions::max_iterations
  int runs = 0;             ///< orbit runs made so far (iterations and backtracking trials)
  double residual = 0;      ///< max |x_i(T) - x_i(0)| over the periodic components now
  double tolerance = 0;     ///< the residual Newton stops at
  double cpu_seconds = 0;   ///< CPU seconds since the computation started
  /// Estimated CPU seconds still needed: the mean cost per iteration times the iterations the
  /// residual's last contraction rate needs to reach the tolerance (at most the iterations left;
  /// 0 when the residual is already below the tolerance). An estimate, not a bound.
  double remaining_seconds = 0;
};

/// One accepted point of a Continuation branch.
struct ContinuationProgress {
  int points = 0;             ///< points of the branch so far (the start included)
  int max_points = 0;         ///< ContinuationOptions::max_points
  double parameter = 0;       ///< the parameter of the newest point
  /// Fraction of the way from the start parameter to the end of the range in the direction of
  /// the branch, in [0, 1] (it can fall back where the branch turns at a fold).
  double covered = 0;
  double cpu_seconds = 0;     ///< CPU seconds since the run started
  double seconds_per_point = 0;  ///< CPU seconds of the newest point (its corrector and retries)
  /// Estimated CPU seconds to the end of the range: cpu_seconds (1 - covered) / covered, at most
  /// the mean cost per point times the points left before max_points; -1 (not known) while no
  /// part of the range is covered (the start point). An estimate, not a bound: steps shrink where
  /// the branch is hard (folds, stick phases opening).
  double remaining_seconds = 0;
};

/// Called per Newton iteration of Shooting (ShootingOptions::progress).
using ShootingProgressCallback = std::function<void(const ShootingProgress&)>;
/// Called per accepted point of Continuation (ContinuationOptions::progress).
using ContinuationProgressCallback = std::function<void(const ContinuationProgress&)>;

namespace detail {

/// The remaining-cost estimate of a Newton iteration: with rate = residual / previous residual
/// < 1, the iterations k with residual rate^k <= tolerance, at most `left`; `left` when the
/// residual does not contract.
inline double newton_remaining(double residual, double previous, double tolerance, int left,
                               double seconds_per_iteration) {
  if (!(residual > tolerance)) return 0;
  double k = left;
  if (previous > 0 && residual < previous)
    k = std::min(k, std::ceil(std::log(tolerance / residual) / std::log(residual / previous)));
  return std::max(0.0, k) * seconds_per_iteration;
}

/// The remaining-cost estimate of a branch (ContinuationProgress::remaining_seconds; -1 while
/// nothing is covered).
inline double branch_remaining(double covered, double cpu_seconds, int points, int max_points) {
  if (!(covered > 0)) return -1;
  const int done = std::max(points - 1, 1);  // points after the start
  const double by_points = cpu_seconds / done * std::max(max_points - points, 0);
  return std::min(cpu_seconds * (1 - std::min(covered, 1.0)) / covered, by_points);
}

}  // namespace detail

}  // namespace stickslip

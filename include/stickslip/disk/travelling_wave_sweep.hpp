#pragma once
/// \file travelling_wave_sweep.hpp
/// \brief A frequency-response curve of travelling-wave orbits: a natural-parameter sweep in the
/// forcing frequency with a secant predictor, each point solved by TravellingWaveShooting
/// (docs/disks.md).
///
/// Why not Continuation (steady_state/continuation.hpp): its residual is Shooting's
/// x_P(t0 + T) - x_P, which the cyclic shift S cannot enter, and its set_parameter edits one
/// system in place, while a ContactSystem's loads (their frequency) are fixed at construction.
/// A natural-parameter sweep does not turn at folds: a branch with a fold ends there (the
/// point's status says so) or jumps to the other branch (compare the amplitudes).

#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/travelling_wave.hpp"

#include <Eigen/Core>

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// One point of a travelling-wave frequency sweep.
template <class System>
struct TravellingWaveSweepPoint {
  typename System::Scalar omega{};    ///< forcing frequency Omega [rad/s]
  TravellingWaveOrbit<System> orbit;  ///< the orbit at Omega (t0 = 0), or the failed solve
};

/// Travelling-wave orbits at the frequencies `omegas` in order (t0 = 0, T = 2 pi / Omega):
/// `make_system(Omega)` builds the scene forced at Omega (same structure, bodies and contacts at
/// every Omega; the shift is taken once from the first). The first point starts from `guess`
/// (mode, x0); the next ones from the secant through the last two converged orbits
/// (x_pred = x_k + (x_k - x_{k-1}) (Omega - Omega_k) / (Omega_k - Omega_{k-1})), or the last one
/// alone, in the last converged orbit's mode, made consistent at the prediction
/// (make_consistent) when its own solve fails. A failed point is kept with its status and the
/// sweep goes on from the last converged one. `on_point` (optional) is called after each point.
/// \throws std::invalid_argument naming the parameter: empty or non-finite omegas or an
///         Omega <= 0 (omegas), an empty make_system or make_shift, and TravellingWaveShooting's
///         refusals
template <class System>
std::vector<TravellingWaveSweepPoint<System>> travelling_wave_sweep(
    const std::function<System(typename System::Scalar)>& make_system,
    const std::function<TravellingWaveShift<typename System::Scalar>(const System&)>& make_shift,
    const std::vector<typename System::Scalar>& omegas, const typename System::Mode& mode,
    const typename System::State& guess, const TravellingWaveOptions<typename System::Scalar>& options = {},
    const std::function<void(const TravellingWaveSweepPoint<System>&)>& on_point = {}) {
  using Scalar = typename System::Scalar;
  using State = typename System::State;
  static const char* where = "travelling_wave_sweep";
  if (omegas.empty()) detail::throw_invalid(where, "omegas must not be empty; size", omegas.size());
  for (std::size_t i = 0; i < omegas.size(); ++i)
    if (!(omegas[i] > Scalar(0)) || !std::isfinite(omegas[i]))
      detail::throw_invalid(where, "omegas[" + std::to_string(i) + "] must be finite and > 0", omegas[i]);
  if (!make_system) detail::throw_invalid(where, "make_system must be set", "empty");
  if (!make_shift) detail::throw_invalid(where, "make_shift must be set", "empty");
  const Scalar two_pi = Scalar(2) * Scalar(EIGEN_PI);
  std::vector<TravellingWaveSweepPoint<System>> points;
  std::vector<std::pair<Scalar, State>> converged;  // (Omega, x0) of the last two converged points
  typename System::Mode last_mode = mode;
  std::optional<TravellingWaveShift<Scalar>> shift;
  for (const Scalar omega : omegas) {
    System system = make_system(omega);
    if (!shift) shift = make_shift(system);
    TravellingWaveShooting<System> tw(system, *shift, options);
    State x = guess;
    if (converged.size() == 1) x = converged.back().second;
    if (converged.size() == 2) {
      const auto& [w0, x0] = converged[0];
      const auto& [w1, x1] = converged[1];
      x = x1 + (x1 - x0) * ((omega - w1) / (w1 - w0));
    }
    TravellingWaveSweepPoint<System> point;
    point.omega = omega;
    point.orbit = tw.solve(last_mode, Scalar(0), x, two_pi / omega);
    if (!point.orbit.ok()) {
      auto m = last_mode;
      State xc = x;
      if (system.make_consistent(m, Scalar(0), xc) && m != last_mode) {
        auto retry = tw.solve(m, Scalar(0), xc, two_pi / omega);
        if (retry.ok()) point.orbit = std::move(retry);
      }
    }
    if (point.orbit.ok()) {
      last_mode = point.orbit.mode;
      converged.emplace_back(omega, point.orbit.x0);
      if (converged.size() > 2) converged.erase(converged.begin());
    }
    if (on_point) on_point(point);
    points.push_back(std::move(point));
  }
  return points;
}

}  // namespace stickslip

#pragma once
/// \file contact_statistics.hpp
/// \brief Per-contact statistics of one period of a periodic orbit whose mode is a vector of
/// ContactState (e.g. FrictionDampedSystem): stick fraction and switches per period.

#include <stickslip/contact/contact_state.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <Eigen/Core>

#include <algorithm>

namespace stickslip {

/// One contact's share of a period in Stick and its switches in that period.
template <class Scalar>
struct OrbitContactStatistics {
  Scalar stick_fraction = 0;  ///< time in Stick / T, in [0, 1]
  int switches = 0;           ///< changes of this contact's state over the period's events
};

/// Statistics of contact i over one period of `orbit`, from its start mode and its events (the
/// mode is constant between events): stick_fraction = (sum of the Stick intervals in
/// [t0, t0 + T]) / T, switches = number of events that change mode[i].
template <class System>
OrbitContactStatistics<typename System::Scalar> orbit_contact_statistics(
    const PeriodicOrbit<System>& orbit, Eigen::Index i) {
  using Scalar = typename System::Scalar;
  OrbitContactStatistics<Scalar> s;
  Scalar t = orbit.t0, stuck = 0;
  ContactState state = orbit.mode[i];
  for (const auto& e : orbit.events) {
    if (state == ContactState::Stick) stuck += e.t - t;
    t = e.t;
    if (e.to[i] != state) ++s.switches;
    state = e.to[i];
  }
  if (state == ContactState::Stick) stuck += orbit.t0 + orbit.period - t;
  s.stick_fraction = orbit.period > 0 ? std::clamp(stuck / orbit.period, Scalar(0), Scalar(1)) : Scalar(0);
  return s;
}

}  // namespace stickslip

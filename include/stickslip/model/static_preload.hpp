#pragma once
/// \file static_preload.hpp
/// \brief A start from static equilibrium under the dampers' preloads (instead of the preload
/// applied as a step at t = 0 on the structure at rest).

#include "stickslip/contact.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/friction_damped_system.hpp"
#include "stickslip/model/point_load.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <string>

namespace stickslip {

/// A state and a discrete mode to start a run from.
template <class System>
struct StartState {
  typename System::State x;     ///< the state
  typename System::Mode mode;   ///< the dampers' states (all stuck where they can stick)
};

/// The static equilibrium of the structure under the preloads N0 with every damper stuck at X0
/// and its spring unstretched: with q' = 0, x = x' = 0 (so f_i = k_i x_i = 0) and N_i = N0_i,
/// eq 25 reduces to
///   Omega^2 q0 = sum_i N0_i a_i,   a_i = side_i psi_w(X0_i)   (paper eqs 25-27 with q'' = 0),
/// i.e. q0_j = sum_i N0_i a_ij / omega_j^2; the contact coordinates stay at X0 and the
/// energy-audit integrals at 0. The mode is Stick for every damper with a stick state (a
/// regularised damper keeps requested_mode()'s state: at V = 0 its friction is 0). A run from it
/// without loads stays at rest; external loads (also their constant offsets) are not included.
/// Call make_consistent(mode, t0, x) before the run as usual (it confirms the stick: |f| = 0).
/// \throws std::invalid_argument (naming `basis`) when a preload drives a rigid-body mode
///         (omega_j = 0): there is no static equilibrium
template <class System>
StartState<System> static_preload_start(const System& system) {
  using Scalar = typename System::Scalar;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  StartState<System> start{system.initial_state(), system.requested_mode()};
  const Eigen::Index n = system.num_modes();
  Vector load = Vector::Zero(n);  // sum_i N0_i a_i
  for (std::size_t i = 0; i < system.dampers().size(); ++i) {
    const auto& d = system.dampers()[i];
    load += d.preload * d.side * system.point_shape(d.member, d.contact_coordinate, LoadDirection::Transverse);
    if (detail::law_has_stick_state(d.law)) start.mode[static_cast<Eigen::Index>(i)] = ContactState::Stick;
  }
  const Vector& w2 = system.omega_squared();
  for (Eigen::Index j = 0; j < n; ++j) {
    if (w2[j] > Scalar(0)) {
      start.x[system.q_offset() + j] = load[j] / w2[j];
    } else if (load[j] != Scalar(0)) {
      detail::throw_invalid("static_preload_start",
                            "basis has a rigid-body mode (omega = 0) that the preloads drive: no static "
                            "equilibrium; mode",
                            j);
    }
  }
  return start;
}

}  // namespace stickslip

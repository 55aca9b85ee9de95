#pragma once
/// \file shape_values.hpp
/// \brief Mode values and derivatives at one point of a member, and the caller-held element hint.

#include <Eigen/Core>

#include "stickslip/detail/validate.hpp"

namespace stickslip {

/// Row vectors over the retained modes (stored as column vectors, one entry per mode) of the
/// paper's approximate analytical modes at a point eps of a member, in the member's local axes
/// (paper eqs 4-7 and 10; psi_w' and psi_w'' enter eqs 18-29):
/// - `psi_u`   axial displacement psi_u(eps) [m per unit modal coordinate],
/// - `dpsi_u`  axial strain psi_u'(eps) [1/unit modal coordinate], constant within an element,
/// - `psi_w`   transverse displacement psi_w(eps),
/// - `dpsi_w`  slope psi_w'(eps) = rotation theta [rad per unit modal coordinate],
/// - `ddpsi_w` curvature psi_w''(eps) [1/m per unit modal coordinate], linear within an element.
/// With a fixed `Modes` every vector is fixed-size and nothing is allocated.
template <class Scalar_, int Modes = Eigen::Dynamic>
struct ShapeValues {
  static_assert(Modes == Eigen::Dynamic || Modes > 0, "ShapeValues: Modes must be > 0 or Dynamic");
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// One value per mode (fixed-size with a fixed `Modes`).
  using Vector = Eigen::Matrix<Scalar, Modes, 1>;
  /// Number of modes fixed at compile time, or Eigen::Dynamic (template parameter `Modes`).
  static constexpr int modes_at_compile_time = Modes;

  ///@{
  /// psi_u, psi_u', psi_w, psi_w', psi_w'' at the point, one entry per mode (see above).
  Vector psi_u, dpsi_u, psi_w, dpsi_w, ddpsi_w;
  ///@}

  ShapeValues() = default;
  /// Values for n modes (n must equal Modes when Modes is fixed).
  explicit ShapeValues(Eigen::Index n) { resize(n); }

  /// Size every vector to n modes; allocates only when n changes, a no-op for fixed Modes.
  void resize(Eigen::Index n) {
    if constexpr (Modes == Eigen::Dynamic) {
      psi_u.resize(n);
      dpsi_u.resize(n);
      psi_w.resize(n);
      dpsi_w.resize(n);
      ddpsi_w.resize(n);
    } else {
      STICKSLIP_ASSERT(n == Modes && "ShapeValues::resize: fixed Modes");
      static_cast<void>(n);
    }
  }

  /// Number of modes held.
  Eigen::Index size() const noexcept { return psi_w.size(); }
};

/// Locality hint for repeated evaluations at a slowly moving point: the element found by the
/// previous call. Held by the caller (one per moving load), so a MemberShapes has no mutable state
/// and may be shared between threads. A default or stale cursor is valid: it only costs a search.
struct ElementCursor {
  /// Element found by the last call (-1: none yet).
  Eigen::Index element = -1;
};

}  // namespace stickslip

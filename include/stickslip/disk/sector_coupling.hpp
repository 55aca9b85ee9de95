#pragma once
/// \file sector_coupling.hpp
/// \brief The linear element that couples a sector of a bladed disk to its neighbour: springs
/// between two attachment nodes, a ring (disk rim) beam element between them, or both.

#include "stickslip/beam/frame_element.hpp"
#include "stickslip/beam/mass_type.hpp"
#include "stickslip/beam/section_properties.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cmath>
#include <optional>
#include <string>

namespace stickslip {

/// How sector k is tied to sector k + 1 (and sector N - 1 to sector 0): between the right
/// attachment node R of sector k and the left attachment node L of sector k + 1.
///
/// Over the six DOFs (u_R; u_L) = (X, Y, Rz of R in sector k; X, Y, Rz of L in sector k + 1) the
/// coupling adds the element matrices
///   K_c = [D, -D; -D, D] + K_ring,   M_c = M_ring,   D = diag(k_x, k_y, k_rz),
/// where K_ring, M_ring are those of one Euler-Bernoulli frame element (beam/frame_element.hpp)
/// from R to L + (pitch, 0): the rim segment between the two sectors as it lies in the unrolled
/// annulus. Either part may be absent; at least one must be present.
template <class Scalar_>
struct SectorCoupling {
  using Scalar = Scalar_;                                  ///< floating-point type
  using Matrix6 = Eigen::Matrix<Scalar, 6, 6>;             ///< element matrix over (u_R; u_L)
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;             ///< a position (X, Y) [m]

  Scalar k_x = Scalar(0);   ///< spring along X between R and L [N/m]
  Scalar k_y = Scalar(0);   ///< spring along Y between R and L [N/m]
  Scalar k_rz = Scalar(0);  ///< rotational spring about Z between R and L [N m/rad]
  /// Section of the ring element from R to L (none: springs only).
  std::optional<SectionProperties<Scalar>> ring;

  /// Springs only (root or platform springs between neighbours).
  static SectorCoupling springs(Scalar kx, Scalar ky, Scalar krz) {
    SectorCoupling c;
    c.k_x = kx;
    c.k_y = ky;
    c.k_rz = krz;
    return c;
  }
  /// A ring (rim) beam element of `section` from R to the next sector's L.
  static SectorCoupling ring_member(const SectionProperties<Scalar>& section) {
    SectorCoupling c;
    c.ring = section;
    return c;
  }

  /// \throws std::invalid_argument naming `where` and the field: a spring non-finite or < 0, an
  ///         invalid ring section, or no coupling at all (every spring 0 and no ring).
  void validate(const std::string& where) const {
    detail::require_non_negative(where, "coupling.k_x", k_x);
    detail::require_non_negative(where, "coupling.k_y", k_y);
    detail::require_non_negative(where, "coupling.k_rz", k_rz);
    if (ring) ring->validate(where + ": coupling.ring");
    if (!ring && k_x == Scalar(0) && k_y == Scalar(0) && k_rz == Scalar(0))
      detail::throw_invalid(where, "coupling must have a spring > 0 or a ring section; coupling.k_x", k_x);
  }

  /// The ring element from R at `right` to L at `left_next` (the next sector's L, in the
  /// unrolled plane). \throws std::invalid_argument when the two points coincide.
  FrameElement<Scalar> ring_element(const Vector2& right, const Vector2& left_next) const {
    const Vector2 axis = left_next - right;
    const Scalar length = axis.stableNorm();
    if (!(length > Scalar(0)))
      detail::throw_invalid("SectorCoupling", "coupling.ring needs the next sector's left attachment away from the "
                                              "right one (ring length)", length);
    return FrameElement<Scalar>(length, axis.x() / length, axis.y() / length, *ring);
  }

  /// K_c over (u_R; u_L) (see the class comment).
  Matrix6 stiffness(const Vector2& right, const Vector2& left_next) const {
    Matrix6 k = Matrix6::Zero();
    const Scalar d[3] = {k_x, k_y, k_rz};
    for (int i = 0; i < 3; ++i) {
      k(i, i) = k(i + 3, i + 3) = d[i];
      k(i, i + 3) = k(i + 3, i) = -d[i];
    }
    if (ring) k += ring_element(right, left_next).global_stiffness();
    return k;
  }

  /// M_c over (u_R; u_L): the ring element's (consistent or lumped) mass, zero without a ring.
  Matrix6 mass(const Vector2& right, const Vector2& left_next, MassType type) const {
    if (!ring) return Matrix6::Zero();
    return ring_element(right, left_next).global_mass(type);
  }
};

}  // namespace stickslip

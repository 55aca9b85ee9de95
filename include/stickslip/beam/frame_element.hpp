#pragma once
/// \file frame_element.hpp
/// \brief Two-node Euler-Bernoulli plane frame element: a linear bar for the axial displacement u
/// and a cubic Hermite beam for the transverse displacement w (paper eqs. 2-7).

#include "stickslip/beam/mass_type.hpp"
#include "stickslip/beam/section_properties.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cmath>
#include <limits>

namespace stickslip {

/// A straight two-node plane frame element of length L whose axis points from node a to node b
/// in the direction (cos, sin) of the global X-Y plane.
///
/// Local DOFs (u1, w1, theta1, u2, w2, theta2): u along the axis, w rotated 90 degrees
/// counter-clockwise from u, theta about Z. Shape functions (paper, after eq. 7):
/// N_u = [1 - e/L, e/L], N_w = [1 - 3x^2 + 2x^3, L(x - 2x^2 + x^3), 3x^2 - 2x^3, L(x^3 - x^2)],
/// x = e/L. Axial and bending are uncoupled in the local frame.
template <class Scalar_>
class FrameElement {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// 6 x 6 element matrix over (u1, w1, theta1, u2, w2, theta2).
  using Matrix6 = Eigen::Matrix<Scalar, 6, 6>;
  /// Material and section of the element.
  using Section = SectionProperties<Scalar>;

  /// \param length  element length L [m], finite and > 0
  /// \param cos_a, sin_a  direction cosines of the axis (node a -> node b); must satisfy
  ///        |cos^2 + sin^2 - 1| <= sqrt(machine epsilon)
  /// \param section material and section (E, rho, A, I > 0, SectionProperties::validate)
  /// \throws std::invalid_argument naming the parameter (also for an invalid section)
  FrameElement(Scalar length, Scalar cos_a, Scalar sin_a, const Section& section)
      : length_(length), cos_(cos_a), sin_(sin_a), section_(section) {
    static const char* where = "FrameElement";
    detail::require_positive(where, "length", length);
    detail::require_finite(where, "cos", cos_a);
    detail::require_finite(where, "sin", sin_a);
    using std::abs;
    using std::sqrt;
    const Scalar unit = cos_a * cos_a + sin_a * sin_a;
    if (!(abs(unit - Scalar(1)) <= sqrt(std::numeric_limits<Scalar>::epsilon())))
      detail::throw_invalid(where, "cos^2 + sin^2 must be 1", unit);
    section.validate(where);
  }

  /// Element length L [m].
  Scalar length() const noexcept { return length_; }
  /// Direction cosine of the axis (node a -> node b) with global X.
  Scalar cos() const noexcept { return cos_; }
  /// Direction cosine of the axis (node a -> node b) with global Y.
  Scalar sin() const noexcept { return sin_; }
  /// Material and section.
  const Section& section() const noexcept { return section_; }

  /// Local stiffness: EA/L [1 -1; -1 1] on (u1, u2) and
  /// EI/L^3 [12 6L -12 6L; 6L 4L^2 -6L 2L^2; -12 -6L 12 -6L; 6L 2L^2 -6L 4L^2] on
  /// (w1, theta1, w2, theta2). Units N/m, N, N m.
  Matrix6 local_stiffness() const {
    const Scalar L = length_;
    const Scalar a = section_.axial_rigidity() / L;
    const Scalar b = section_.bending_rigidity() / (L * L * L);
    Matrix6 k = Matrix6::Zero();
    k(0, 0) = k(3, 3) = a;
    k(0, 3) = k(3, 0) = -a;
    k(1, 1) = k(4, 4) = b * 12;
    k(1, 4) = k(4, 1) = -b * 12;
    k(1, 2) = k(2, 1) = k(1, 5) = k(5, 1) = b * 6 * L;
    k(2, 4) = k(4, 2) = k(4, 5) = k(5, 4) = -b * 6 * L;
    k(2, 2) = k(5, 5) = b * 4 * L * L;
    k(2, 5) = k(5, 2) = b * 2 * L * L;
    return k;
  }

  /// Local consistent mass: rho A L / 6 [2 1; 1 2] on (u1, u2) and
  /// rho A L / 420 [156 22L 54 -13L; 22L 4L^2 13L -3L^2; 54 13L 156 -22L; -13L -3L^2 -22L 4L^2]
  /// on (w1, theta1, w2, theta2). Units kg, kg m, kg m^2.
  Matrix6 local_consistent_mass() const {
    const Scalar L = length_;
    const Scalar m = section_.mass_per_length() * L;
    const Scalar c = m / Scalar(420);
    Matrix6 mm = Matrix6::Zero();
    mm(0, 0) = mm(3, 3) = m / Scalar(3);
    mm(0, 3) = mm(3, 0) = m / Scalar(6);
    // Diagonal and same-node coupling: 156, 22L, 4L^2 (sign of 22L flips at node 2).
    mm(1, 1) = mm(4, 4) = c * 156;
    mm(2, 2) = mm(5, 5) = c * 4 * L * L;
    mm(1, 2) = mm(2, 1) = c * 22 * L;
    mm(4, 5) = mm(5, 4) = -c * 22 * L;
    // Node 1 - node 2 coupling: 54, 13L, -13L, -3L^2.
    mm(1, 4) = mm(4, 1) = c * 54;
    mm(1, 5) = mm(5, 1) = -c * 13 * L;
    mm(2, 4) = mm(4, 2) = c * 13 * L;
    mm(2, 5) = mm(5, 2) = -c * 3 * L * L;
    return mm;
  }

  /// Local HRZ-lumped (Hinton-Rock-Zienkiewicz) mass: the diagonal of the consistent matrix,
  /// scaled so that each translation carries the element mass: diag(m/2, m/2, m L^2/78, m/2,
  /// m/2, m L^2/78) with m = rho A L. The rotary term m L^2/78 = (420/312) * 4 m L^2/420 keeps the
  /// matrix positive definite; it vanishes as L^2 under refinement.
  Matrix6 local_lumped_mass() const {
    const Scalar L = length_;
    const Scalar m = section_.mass_per_length() * L;
    Matrix6 mm = Matrix6::Zero();
    mm(0, 0) = mm(1, 1) = mm(3, 3) = mm(4, 4) = m / Scalar(2);
    mm(2, 2) = mm(5, 5) = m * L * L / Scalar(78);
    return mm;
  }

  /// Local mass of the requested type.
  Matrix6 local_mass(MassType type) const {
    return type == MassType::Consistent ? local_consistent_mass() : local_lumped_mass();
  }

  /// Rotation T with d_local = T d_global: blockdiag(R, R), R = [c s 0; -s c 0; 0 0 1].
  Matrix6 rotation() const {
    Matrix6 t = Matrix6::Zero();
    for (int n = 0; n < 2; ++n) {
      const int o = 3 * n;
      t(o, o) = cos_;
      t(o, o + 1) = sin_;
      t(o + 1, o) = -sin_;
      t(o + 1, o + 1) = cos_;
      t(o + 2, o + 2) = Scalar(1);
    }
    return t;
  }

  /// Global stiffness T^T k T over (X1, Y1, Rz1, X2, Y2, Rz2).
  Matrix6 global_stiffness() const { return to_global(local_stiffness()); }

  /// Global mass T^T m T of the requested type.
  Matrix6 global_mass(MassType type = MassType::Consistent) const {
    return to_global(local_mass(type));
  }

 private:
  Matrix6 to_global(const Matrix6& local) const {
    const Matrix6 t = rotation();
    return t.transpose() * local * t;
  }

  Scalar length_;
  Scalar cos_;
  Scalar sin_;
  Section section_;
};

}  // namespace stickslip

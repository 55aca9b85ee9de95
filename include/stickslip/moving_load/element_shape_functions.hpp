#pragma once
/// \file element_shape_functions.hpp
/// \brief Shape functions of the two-node Euler-Bernoulli frame element at one point: linear for
/// the axial displacement u, Hermite cubics for the transverse displacement w (paper eq. 8 text).

namespace stickslip {

/// Weights of the element's nodal values (u1, w1, theta1, u2, w2, theta2) in u, u', w, w', w''
/// at the dimensionless position xi = x / Le of an element of length Le [m]:
///
///     N_u  = [1 - xi, xi]
///     N_w  = [(1 - xi)^2 (1 + 2 xi),  Le xi (1 - xi)^2,  xi^2 (3 - 2 xi),  -Le xi^2 (1 - xi)]
///
/// and their x-derivatives. The rotation functions carry the factor Le (the paper's printed
/// N_w omits it; without it w' would not equal theta at the nodes). The factored forms make
/// every weight exactly 0 or 1 at xi = 0 and xi = 1, so nodal values are reproduced exactly.
/// Outside [0, 1] the same polynomials extrapolate.
template <class Scalar_>
struct ElementShapeFunctions {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;

  ///@{
  Scalar u1, u2;                    ///< N_u: weights of u1, u2 in u
  ///@}
  Scalar du;                        ///< N_u' = [-du, du], du = 1 / Le [1/m]
  ///@{
  Scalar w1, t1, w2, t2;            ///< N_w: weights of w1, theta1, w2, theta2 in w
  ///@}
  ///@{
  Scalar dw1, dt1, dw2, dt2;        ///< N_w'
  ///@}
  ///@{
  Scalar ddw1, ddt1, ddw2, ddt2;    ///< N_w''
  ///@}

  /// Shape functions at xi for an element of length le > 0.
  ElementShapeFunctions(Scalar xi, Scalar le) noexcept {
    const Scalar one(1), two(2), three(3), six(6), twelve(12);
    const Scalar eta = one - xi;
    const Scalar inv = one / le;
    u1 = eta;
    u2 = xi;
    du = inv;
    w1 = eta * eta * (one + two * xi);
    t1 = le * xi * eta * eta;
    w2 = xi * xi * (three - two * xi);
    t2 = -le * xi * xi * eta;
    dw1 = -six * xi * eta * inv;
    dt1 = eta * (one - three * xi);
    dw2 = -dw1;
    dt2 = xi * (three * xi - two);
    ddw1 = (twelve * xi - six) * inv * inv;
    ddt1 = (six * xi - two * two) * inv;
    ddw2 = -ddw1;
    ddt2 = (six * xi - two) * inv;
  }
};

}  // namespace stickslip

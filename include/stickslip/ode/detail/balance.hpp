#pragma once
/// \file balance.hpp
/// \brief Diagonal balancing of a square matrix by powers of two (Parlett and Reinsch): the
/// similarity B = D^-1 A D that brings each row's and column's off-diagonal 1-norms within a
/// factor of two of each other, exact in floating point.

#include <Eigen/Core>

#include <cmath>

namespace stickslip {
namespace detail {

/// m <- D^-1 m D with D = diag(scale) (powers of 2, scale set here): sweeps until no component's
/// scaling lowers its row + column off-diagonal norm below 95 % (at most 32 sweeps).
template <class Matrix, class Vector>
void balance_by_powers_of_two(Matrix& m, Vector& scale) {
  using Scalar = typename Matrix::Scalar;
  const Eigen::Index d = m.rows();
  scale.setOnes(d);
  for (int sweep = 0; sweep < 32; ++sweep) {
    bool done = true;
    for (Eigen::Index i = 0; i < d; ++i) {
      Scalar c = m.col(i).cwiseAbs().sum() - std::abs(m(i, i));
      Scalar r = m.row(i).cwiseAbs().sum() - std::abs(m(i, i));
      if (!(c > 0) || !(r > 0)) continue;
      const Scalar total = c + r;
      Scalar f = 1;
      while (c < r / 2) {
        c *= 2;
        r /= 2;
        f *= 2;
      }
      while (c >= r * 2) {
        c /= 2;
        r *= 2;
        f /= 2;
      }
      if (c + r >= Scalar(0.95) * total) continue;
      done = false;
      scale[i] *= f;
      m.col(i) *= f;
      m.row(i) /= f;
    }
    if (done) break;
  }
}

}  // namespace detail
}  // namespace stickslip

#pragma once
/// \file pade_exponential.hpp
/// \brief exp(A) by diagonal Padé approximants with scaling and squaring, in a workspace that is
/// kept between calls (internal to AugmentedFlow): no heap allocation once the sizes are known.
///
/// Higham, "The scaling and squaring method for the matrix exponential revisited", SIAM J.
/// Matrix Anal. Appl. 26 (2005) 1179-1193, Algorithm 2.3: with the 1-norm ||A||_1,
///
///     m = 3, 5, 7, 9 where ||A||_1 <= theta_m, else m = 13 on A / 2^s, ||A / 2^s||_1 <= theta_13,
///     r_m(A) = (V - U)^-1 (V + U),   U = A sum_{j odd} c_j A^(j-1),   V = sum_{j even} c_j A^j,
///     exp(A) = r_m(A / 2^s)^(2^s),
///
/// c_j = (2m - j)! m! / ((2m)! j! (m - j)!) the coefficients of the [m/m] Padé approximant of
/// e^x, theta_m (Higham's Table 2.3, double precision) the largest norms for which the backward
/// error of r_m is below the unit round-off 2^-53. The same choice of m and s as Eigen's
/// MatrixFunctions module, which this replaces because its temporaries are allocated per call.

#include <Eigen/Core>
#include <Eigen/LU>

#include <array>
#include <cmath>

namespace stickslip {
namespace detail {

template <class Scalar>
class PadeExponential {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// out = exp(a) (a square; out must not alias a). Allocates only when the size of a changes.
  template <class Derived>
  void compute(const Eigen::MatrixBase<Derived>& a, Matrix& out) {
    using std::frexp;
    static constexpr std::array<double, 5> degree{3, 5, 7, 9, 13};
    static constexpr std::array<double, 5> theta{1.495585217958292e-2, 2.539398330063230e-1,
                                                 9.504178996162932e-1, 2.097847961257068e0,
                                                 5.371920351148152e0};
    a_ = a;
    const Scalar norm = a_.cwiseAbs().colwise().sum().maxCoeff();
    std::size_t k = 0;
    while (k + 1 < degree.size() && !(norm <= Scalar(theta[k]))) ++k;
    int squarings = 0;
    if (k + 1 == degree.size() && norm > Scalar(theta[k])) {
      frexp(norm / Scalar(theta[k]), &squarings);  // norm / theta = f 2^s, f in [1/2, 1)
      if (squarings > 0) a_ *= std::ldexp(Scalar(1), -squarings);
    }
    const int m = static_cast<int>(degree[k]);
    // c_0 = 1, c_j = c_{j-1} (m - j + 1) / (j (2m - j + 1)).
    std::array<Scalar, 14> c{};
    c[0] = 1;
    for (int j = 1; j <= m; ++j)
      c[static_cast<std::size_t>(j)] =
          c[static_cast<std::size_t>(j - 1)] * Scalar(m - j + 1) / Scalar(j * (2 * m - j + 1));
    const auto cj = [&](int j) { return c[static_cast<std::size_t>(j)]; };
    const Eigen::Index n = a_.rows();
    a2_.noalias() = a_ * a_;
    if (m <= 9) {
      // Even powers A^2 .. A^(m-1), then both sums by powers.
      pw_[0] = a2_;
      for (int p = 1; 2 * (p + 1) < m + 1; ++p)
        pw_[static_cast<std::size_t>(p)].noalias() = pw_[static_cast<std::size_t>(p - 1)] * a2_;
      tmp_.setIdentity(n, n);
      tmp_ *= cj(1);
      v_.setIdentity(n, n);
      v_ *= cj(0);
      for (int j = 2; j <= m; j += 2) {
        const Matrix& p = pw_[static_cast<std::size_t>(j / 2 - 1)];
        v_ += cj(j) * p;
        if (j + 1 <= m) tmp_ += cj(j + 1) * p;
      }
    } else {
      // m = 13 with three products (Higham's eq. 2.2 grouping): powers A^2, A^4, A^6.
      pw_[0] = a2_;
      pw_[1].noalias() = a2_ * a2_;
      pw_[2].noalias() = pw_[1] * a2_;
      const Matrix &a4 = pw_[1], &a6 = pw_[2];
      v_ = cj(13) * a6 + cj(11) * a4 + cj(9) * a2_;
      tmp_.noalias() = a6 * v_;
      tmp_ += cj(7) * a6 + cj(5) * a4 + cj(3) * a2_;
      tmp_.diagonal().array() += cj(1);
      u_ = cj(12) * a6 + cj(10) * a4 + cj(8) * a2_;
      v_.noalias() = a6 * u_;
      v_ += cj(6) * a6 + cj(4) * a4 + cj(2) * a2_;
      v_.diagonal().array() += cj(0);
    }
    u_.noalias() = a_ * tmp_;
    // (V - U) out = V + U.
    tmp_ = v_ - u_;
    lu_.compute(tmp_);
    tmp_ = v_ + u_;
    out.resize(n, n);
    out = lu_.solve(tmp_);
    for (int s = 0; s < squarings; ++s) {
      tmp_.noalias() = out * out;
      out.swap(tmp_);
    }
  }

 private:
  Matrix a_, a2_, u_, v_, tmp_;
  std::array<Matrix, 4> pw_;
  Eigen::PartialPivLU<Matrix> lu_;
};

}  // namespace detail
}  // namespace stickslip

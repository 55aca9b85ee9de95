#pragma once
/// \file half_period_map.hpp
/// \brief The half-period map of an orbit under a symmetry with a half-period shift
/// (SymmetricBranches::half_period_shift): x(t0 + T/2) from x(t0), compared with S x(t0), and
/// H = S dx(t0 + T/2)/dx(t0) over the periodic components, whose square is the monodromy.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/shooting_options.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <string>

namespace stickslip::detail {

/// One half period of an orbit from (mode, t0, x0).
template <class System>
struct HalfPeriodMap {
  using Scalar = typename System::Scalar;
  using State = typename System::State;
  using Mode = typename System::Mode;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  bool ok = false;
  std::string message;  ///< why not ok
  State x_half;         ///< x(t0 + T/2)
  Mode mode_half{};     ///< the mode at t0 + T/2
  Scalar asymmetry = 0; ///< max |x_i(t0 + T/2) - image_i| over the periodic components
  Matrix H;             ///< (S dx(t0 + T/2)/dx(t0))_PP (empty unless asked for)
};

/// Runs half a period of `period` from (mode, t0, x0) with options' integrator, its sensitivity
/// when `sensitivity` (the run's monodromy option: variational or finite differences);
/// `image` is x0's image under the symmetry (S x0, or c + S (x0 - c) about a centre c).
template <class System>
HalfPeriodMap<System> half_period_map(System& sys, const ShootingOptions<typename System::Scalar>& options,
                                      const Eigen::Matrix<typename System::Scalar, Eigen::Dynamic, Eigen::Dynamic>& S,
                                      const typename System::State& image, const typename System::Mode& mode, typename System::Scalar t0,
                                      const typename System::State& x0, typename System::Scalar period,
                                      bool sensitivity) {
  using Scalar = typename System::Scalar;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  HalfPeriodMap<System> h;
  const PeriodRun<System> run = run_period(sys, mode, t0, x0, period / 2, options, sensitivity);
  if (!run.ok()) {
    h.message = "the half-period run from t0 = " + format_value(t0) + " failed: " + run.message;
    return h;
  }
  h.x_half = run.x_end;
  h.mode_half = run.mode_end;
  const auto P = options.periodic_indices(x0.size());
  for (const auto i : P) h.asymmetry = std::max(h.asymmetry, std::abs(run.x_end[i] - image[i]));
  if (sensitivity) {
    const Matrix SM = S * run.monodromy;
    const auto np = static_cast<Eigen::Index>(P.size());
    h.H.resize(np, np);
    for (Eigen::Index a = 0; a < np; ++a)
      for (Eigen::Index b = 0; b < np; ++b) h.H(a, b) = SM(P[std::size_t(a)], P[std::size_t(b)]);
    if (!all_finite(h.H)) {
      h.message = "the half-period map is not finite";
      return h;
    }
  }
  h.ok = true;
  return h;
}

/// det(H - target I): its sign changes where a real eigenvalue of H crosses `target` (a complex
/// pair contributes |h - target|^2 > 0).
template <class Matrix, class Scalar>
Scalar det_shifted(const Matrix& H, Scalar target) {
  return (H - target * Matrix::Identity(H.rows(), H.cols())).determinant();
}

/// The real eigenvalue of H nearest `target` (imaginary part below `imag_tolerance` of its
/// modulus), with its real eigenvector scaled to max norm 1 in *v; NaN when there is none.
template <class Matrix, class Vector, class Scalar>
Scalar nearest_real_eigenvalue(const Matrix& H, Scalar target, Scalar imag_tolerance, Vector* v) {
  if (H.rows() == 0) return std::numeric_limits<Scalar>::quiet_NaN();
  const Eigen::EigenSolver<Matrix> es(H, v != nullptr);
  Eigen::Index k = -1;
  Scalar best = std::numeric_limits<Scalar>::infinity();
  for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
    const std::complex<Scalar> h = es.eigenvalues()[i];
    if (std::abs(h.imag()) > imag_tolerance * std::abs(h)) continue;
    if (std::abs(h.real() - target) < best) {
      best = std::abs(h.real() - target);
      k = i;
    }
  }
  if (k < 0) return std::numeric_limits<Scalar>::quiet_NaN();
  if (v) {
    *v = es.eigenvectors().col(k).real();
    const Scalar s = v->cwiseAbs().maxCoeff();
    if (s > 0) *v /= s;
  }
  return es.eigenvalues()[k].real();
}

}  // namespace stickslip::detail

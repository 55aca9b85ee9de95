#pragma once
/// \file mode_residence.hpp
/// \brief A proof that a run stays in its start mode: lower bounds of the affine guards of an
/// exact linear mode over [t0, t_end] (mode_residence).
///
/// In an exact mode (LinearPart::exact) with affine guards the state and the guards are
///
///     x' = A x + b0 + sum_k (bc_k cos w_k t + bs_k sin w_k t),
///     g(t) = Gx x + g0 + sum_k (gc_k cos w_k t + gs_k sin w_k t).
///
/// The solution is x = x_p + h with the forced (particular) response
///
///     x_p(t) = c0 + sum_k Re(z_k e^{i w_k t}),   A c0 = -b0,   (i w_k I - A) z_k = bc_k - i bs_k,
///
/// and the free response h(t) = e^{A (t - t0)} h0, h0 = x(t0) - x_p(t0). With A = V diag(lambda) V^-1,
///
///     |(Gx h(t))_i| <= sum_j |(Gx V)_ij| |(V^-1 h0)_j| e^{max(Re lambda_j, 0) (t_end - t0)},
///
/// and each guard of the forced response is at least its mean less the sum of its harmonic
/// amplitudes. Their difference is a lower bound of g_i over [t0, t_end]: where every bound is
/// positive no guard can fire and the run never leaves the mode. The bound is exact for one
/// harmonic and a start on the forced response (h0 = 0); otherwise it is conservative (it adds the
/// free response's modal amplitudes as if they could all peak at once).

#include "stickslip/ode/detail/balance.hpp"
#include "stickslip/ode/linear_part.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

namespace stickslip {

/// Result of mode_residence: whether the bound could be formed, and the guards' lower bounds.
template <class Scalar>
struct ModeResidence {
  /// Dynamic column vector.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// True when the bound was formed (see `why_not` otherwise).
  bool bounded = false;
  /// True when bounded and every lower bound is positive: the run stays in the mode.
  bool stays = false;
  /// Lower bound of each guard over [t0, t_end] (empty unless bounded).
  Vector lower;
  /// Index of the guard with the smallest lower bound (-1 when there is none).
  Eigen::Index tightest = -1;
  /// Why the bound could not be formed (empty when bounded).
  std::string why_not;
};

/// Lower bounds over [t0, t_end] of the affine guards of the exact mode `lp` started at the linear
/// components `x0` (lp.size() of them) at t0 (see the file comment). Not bounded (with the reason)
/// when the mode is not exact or has no affine guards, when A c0 = -b0 has no solution (a constant
/// load that drifts a free body), when a forcing frequency is an eigenfrequency of A (resonance:
/// no bounded forced response), or when A is defective (V^-1 has a condition number above
/// 1e8 after balancing: a free rigid-body motion grows linearly). Quantities that stay constant in
/// the mode (left null vectors of A that no load drives) are set aside first. Costs a few SVDs and
/// an eigen-decomposition of A (O(n^3)).
/// Allocates; call it once per run, not per step.
template <class Scalar>
ModeResidence<Scalar> mode_residence(const LinearPart<Scalar>& lp, Scalar t0,
                                     const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& x0, Scalar t_end) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Complex = std::complex<Scalar>;
  using CMatrix = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic>;
  using CVector = Eigen::Matrix<Complex, Eigen::Dynamic, 1>;
  using std::abs;
  using std::cos;
  using std::exp;
  using std::sin;
  using std::sqrt;
  ModeResidence<Scalar> r;
  const Eigen::Index n = lp.size(), G = lp.Gx.rows(), K = static_cast<Eigen::Index>(lp.omega.size());
  if (!lp.exact) {
    r.why_not = "the mode is not exactly linear";
    return r;
  }
  if (!lp.has_affine_guards() || lp.Gx.cols() != n) {
    r.why_not = "the mode has no affine guards";
    return r;
  }
  if (x0.size() < n) {
    r.why_not = "the start state is shorter than the linear part";
    return r;
  }
  const Scalar eps = Eigen::NumTraits<Scalar>::epsilon();
  // Balanced coordinates z = D^-1 x (modal and physical coordinates differ in scale by orders of
  // magnitude): A <- D^-1 A D, loads D^-1 b, guard rows Gx D, start D^-1 x0.
  Matrix A = lp.A;
  Vector scale;
  detail::balance_by_powers_of_two(A, scale);
  Matrix loads(n, 1 + 2 * K);  // [b0 | bc | bs]
  loads.col(0) = lp.b0;
  if (K > 0) {
    loads.middleCols(1, K) = lp.bc;
    loads.rightCols(K) = lp.bs;
  }
  loads = scale.cwiseInverse().asDiagonal() * loads;
  Matrix Gx = lp.Gx * scale.asDiagonal();
  Vector g0 = lp.g0;
  Vector start = scale.cwiseInverse().asDiagonal() * Vector(x0.head(n));
  // Invariant quantities set aside: c^T z with c^T A = 0 and c^T b(t) = 0 is constant, so the
  // motion stays on {C^T z = C^T z0} (a frozen contact coordinate; a stuck damper's slip rate, then
  // its slip). Restricted there by z = z* + W y (W orthonormal, C^T W = 0, z* = C C^T z0) until no
  // such c is left, so that a stuck slip's nilpotent chain (s' = v, v' = 0) does not make A
  // defective. A load on c^T z (a drift) keeps it: A c0 = -b0 then has no solution (below).
  for (Eigen::Index round = 0; round < n && A.rows() > 0; ++round) {
    const Eigen::Index d = A.rows();
    Eigen::BDCSVD<Matrix> svd(A, Eigen::ComputeFullU);
    const Vector sigma = svd.singularValues();
    const Scalar top = sigma.size() ? sigma[0] : Scalar(0);
    Eigen::Index k = 0;
    while (k < d && !(sigma[d - 1 - k] > Scalar(1e-12) * top)) ++k;
    if (k == 0) break;
    const Matrix U0 = svd.matrixU().rightCols(k);  // left null space of A
    const Matrix M = loads.transpose() * U0;      // (1 + 2K) x k: the loads seen by each c
    Matrix C;
    const Scalar load_scale = loads.cwiseAbs().maxCoeff();
    if (!(load_scale > 0)) {
      C = U0;
    } else {
      Eigen::BDCSVD<Matrix> msvd(M, Eigen::ComputeFullV);
      const Vector ms = msvd.singularValues();
      Eigen::Index rank = 0;
      while (rank < ms.size() && ms[rank] > Scalar(1e-12) * load_scale) ++rank;
      C = U0 * msvd.matrixV().rightCols(k - rank);
    }
    const Eigen::Index kept = C.cols();
    if (kept == 0) break;
    Eigen::HouseholderQR<Matrix> qr(C);
    const Matrix Q = qr.householderQ() * Matrix::Identity(d, d);
    const Matrix W = Q.rightCols(d - kept);
    const Vector zstar = C * (C.transpose() * start);
    loads.col(0) += A * zstar;
    g0 += Gx * zstar;
    A = (W.transpose() * A * W).eval();
    loads = (W.transpose() * loads).eval();
    Gx = (Gx * W).eval();
    start = (W.transpose() * start).eval();
  }
  const Eigen::Index m = A.rows();
  const Vector b0 = loads.col(0);
  const Matrix bc = loads.middleCols(1, K), bs = loads.rightCols(K);
  const Scalar a_norm = m > 0 ? A.cwiseAbs().rowwise().sum().maxCoeff() : Scalar(0);
  // Forced response: constant part c0 (A may still be singular: a static equilibrium family).
  Vector c0 = Vector::Zero(m);
  CMatrix V(m, m), Vinv(m, m);
  CVector lambda(m);
  Scalar cond = 1;
  if (m > 0) {
    Eigen::CompleteOrthogonalDecomposition<Matrix> cod(A);
    c0 = cod.solve(-b0);
    const Scalar residual = (A * c0 + b0).cwiseAbs().maxCoeff();
    if (!(residual <= Scalar(1e-9) * (a_norm * c0.cwiseAbs().maxCoeff() + b0.cwiseAbs().maxCoeff()) + eps)) {
      r.why_not = "the constant load has no steady response (A c0 = -b0 has no solution)";
      return r;
    }
    Eigen::EigenSolver<Matrix> es(A, true);
    if (es.info() != Eigen::Success) {
      r.why_not = "the eigen-decomposition of A failed";
      return r;
    }
    V = es.eigenvectors();
    lambda = es.eigenvalues();
    Vinv = V.partialPivLu().inverse();
    cond = V.cwiseAbs().rowwise().sum().maxCoeff() * Vinv.cwiseAbs().rowwise().sum().maxCoeff();
    if (!(cond <= Scalar(1e8))) {
      r.why_not = "A is defective (eigenvector matrix condition " + std::to_string(double(cond)) +
                  "): a free motion may grow without bound";
      return r;
    }
  }
  // Harmonic forced responses z_k and the forced guard's mean and harmonic amplitudes.
  Vector mean = Gx * c0 + g0, amplitude = Vector::Zero(G);
  Vector xp0 = c0;
  for (Eigen::Index k = 0; k < K; ++k) {
    const Scalar w = lp.omega[static_cast<std::size_t>(k)];
    for (Eigen::Index j = 0; j < m; ++j)
      if (abs(lambda[j] - Complex(0, w)) <= Scalar(1e-9) * (abs(w) + a_norm)) {
        r.why_not = "a forcing frequency is an eigenfrequency of the mode (resonance)";
        return r;
      }
    Vector pc = Vector::Zero(m), ps = Vector::Zero(m);
    if (m > 0) {
      CMatrix M = -A.template cast<Complex>();
      M.diagonal().array() += Complex(0, w);
      const CVector rhs = bc.col(k).template cast<Complex>() - Complex(0, 1) * bs.col(k).template cast<Complex>();
      const CVector z = M.partialPivLu().solve(rhs);
      pc = z.real();
      ps = -z.imag();
    }
    xp0 += pc * cos(w * t0) + ps * sin(w * t0);
    const Vector a = Gx * pc + (lp.gc.size() ? Vector(lp.gc.col(k)) : Vector::Zero(G));
    const Vector b = Gx * ps + (lp.gs.size() ? Vector(lp.gs.col(k)) : Vector::Zero(G));
    amplitude.array() += (a.array().square() + b.array().square()).sqrt();
  }
  // Free response: modal amplitudes of h0, grown by e^{max(Re lambda, 0) (t_end - t0)}.
  const CVector modal = Vinv * (start - xp0).template cast<Complex>();
  Vector weight(m);
  const Scalar span = std::max(t_end - t0, Scalar(0));
  for (Eigen::Index j = 0; j < m; ++j) weight[j] = abs(modal[j]) * exp(std::max(lambda[j].real(), Scalar(0)) * span);
  const Matrix GV = (Gx.template cast<Complex>() * V).cwiseAbs();
  const Vector free_bound = GV * weight;
  // Round-off of the decomposition: a relative allowance of cond * eps on every term.
  const Scalar slack = Scalar(1) + Scalar(100) * cond * eps;
  r.lower = mean - slack * (amplitude + free_bound);
  r.bounded = true;
  if (G > 0) {
    r.lower.minCoeff(&r.tightest);
    r.stays = r.lower[r.tightest] > Scalar(0);
  } else {
    r.stays = true;
  }
  return r;
}

}  // namespace stickslip

#ifdef STICKSLIP_COMPILED
// The compiled mode: mode_residence<double> (SVDs, an eigen-decomposition, complex LU) is
// instantiated once, in stickslip::compiled (src/mode_residence.cpp).
namespace stickslip {
extern template ModeResidence<double> mode_residence<double>(const LinearPart<double>&, double,
                                                             const Eigen::Matrix<double, Eigen::Dynamic, 1>&,
                                                             double);
}  // namespace stickslip
#endif

// Continuation of forced periodic orbits on smooth oscillators (tests/steady_state/smooth_forced_systems.hpp):
//  - a linear 2-DOF damped scene: the frequency-response curve against the closed-form complex
//    receptance, every point stable with multipliers exp(lambda_k T);
//  - a hardening Duffing oscillator: the branch passes both folds, the middle branch is unstable
//    through +1, the fold frequencies agree with the one-harmonic balance, and det M = exp(-c T)
//    (Liouville) at every point.

#include "steady_state/smooth_forced_systems.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <complex>
#include <vector>

namespace steady_state_continuation_test {
namespace {

using namespace steady_state_test;
constexpr double kPi = 3.14159265358979323846;
using cd = std::complex<double>;

template <class Sys>
stickslip::Continuation<Sys> frequency_continuation(Sys& sys, double w_lo, double w_hi,
                                                    double max_step) {
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = w_lo;
  co.parameter_max = w_hi;
  co.max_step = max_step;
  co.initial_step = 0.01;
  co.max_points = 2000;
  return stickslip::Continuation<Sys>(
      sys, [](Sys& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, {}, co);
}

// M = I, K = [2 -1; -1 2] (natural frequencies 1 and sqrt 3), C = 0.02 K + 0.01 I, force on
// DOF 0. Closed form: q(t) = Re(H f e^{i w t}), H = (K - w^2 M + i w C)^-1, so at t0 = 0
// q(0) = Re(H f), q'(0) = -w Im(H f), amplitude |(H f)_i|; monodromy exp(A T), A = [0 I; -K -C].
TEST(SteadyStateContinuation, LinearTwoDofFrequencyResponseIsTheReceptance) {
  using Sys = ForcedOscillator<2>;
  Sys sys;
  sys.K << 2, -1, -1, 2;
  sys.C = 0.02 * sys.K + 0.01 * Eigen::Matrix2d::Identity();
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.topRightCorner<2, 2>().setIdentity();
  A.bottomLeftCorner<2, 2>() = -sys.K;
  A.bottomRightCorner<2, 2>() = -sys.C;
  // The dynamic-size solver that floquet_multipliers instantiates anyway (a fixed 4 x 4 one cost
  // this unit ~8 s of compilation).
  const Eigen::Vector4cd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(A)).eigenvalues();

  auto cont = frequency_continuation(sys, 0.5, 2.2, 1.0);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 0.5);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_GE(branch.points.size(), 30u);
  double w_max = 0;
  for (const auto& pt : branch.points) {
    const double w = pt.parameter;
    SCOPED_TRACE(::testing::Message() << "omega " << w);
    w_max = std::max(w_max, w);
    const Eigen::Matrix2cd D = sys.K.cast<cd>() - w * w * Eigen::Matrix2cd::Identity() +
                               cd(0, w) * sys.C.cast<cd>();
    const Eigen::Vector2cd Hf = D.partialPivLu().solve(sys.f.cast<cd>());
    // The orbit's error is (M - I)^-1 times the end-state error (the Newton tolerance 1e-9 and
    // the run error, rtol 1e-10 over ~100 steps: ~1e-9 of the scale), and |(M - I)^-1| <=
    // 1 / min_k |1 - mu_k| (~11 at resonance, where mu = exp(-zeta w T) is closest to 1):
    // 1e-8 of the scale times that factor.
    const double T = 2 * kPi / w;
    double gap = 1e300;
    for (int k = 0; k < 4; ++k) gap = std::min(gap, std::abs(1.0 - std::exp(lambda[k] * T)));
    const double scale = std::max(1.0, Hf.cwiseAbs().maxCoeff() * w) / gap;
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(pt.orbit.x0[i], Hf[i].real(), 1e-8 * scale);
      EXPECT_NEAR(pt.orbit.x0[2 + i], -w * Hf[i].imag(), 1e-8 * scale);
      // max over 256 samples per period (and the steps): a sampled cosine is short of its peak by
      // at most 1 - cos(pi / 256) = 7.5e-5 of the amplitude.
      EXPECT_NEAR(pt.orbit.amplitudes[i], std::abs(Hf[i]), 8e-5 * std::abs(Hf[i]) + 1e-8 * scale);
    }
    EXPECT_TRUE(pt.orbit.floquet.stable);
    EXPECT_FALSE(pt.stability_changed);
    // Every exp(lambda_k T) is a computed multiplier (central-difference Jacobian of a linear
    // rhs: exact to round-off; the run error rtol 1e-10 on Phi of O(1)): 1e-8.
    for (int k = 0; k < 4; ++k) {
      const cd ref = std::exp(lambda[k] * T);
      double nearest = 1e300;
      for (Eigen::Index j = 0; j < pt.orbit.floquet.multipliers.size(); ++j)
        nearest = std::min(nearest, std::abs(pt.orbit.floquet.multipliers[j] - ref));
      EXPECT_LT(nearest, 1e-8) << "multiplier " << ref;
    }
  }
  EXPECT_GT(w_max, 2.1);  // reached the end of the range through both resonances
}

// One-harmonic balance of x'' + c x' + x + k3 x^3 = F cos(w t), x = A cos(w t - phi):
// ((1 + 3/4 k3 A^2 - w^2) A)^2 + (c w A)^2 = F^2, a quadratic in u = w^2. w_plus(A) is the
// larger root (the right-hand, hardening side); the folds are its local min and max over A.
double hb_w_plus(double A, double c, double k3, double F) {
  const double KA = 1 + 0.75 * k3 * A * A;
  const double b = 2 * KA - c * c, q = KA * KA - F * F / (A * A);
  const double disc = b * b - 4 * q;
  return disc < 0 ? std::nan("") : std::sqrt((b + std::sqrt(disc)) / 2);
}

// Vertex (in p) of the parabola p(a) through three points (a_i, p_i).
double parabola_vertex(double a0, double p0, double a1, double p1, double a2, double p2) {
  Eigen::Matrix3d V;
  V << a0 * a0, a0, 1, a1 * a1, a1, 1, a2 * a2, a2, 1;
  const Eigen::Vector3d coef = V.partialPivLu().solve(Eigen::Vector3d(p0, p1, p2));
  return coef[2] - coef[1] * coef[1] / (4 * coef[0]);
}

TEST(SteadyStateContinuation, DuffingBranchPassesBothFoldsWithStabilityChangeThroughPlusOne) {
  using Sys = ForcedOscillator<1>;
  const double c = 0.02, k3 = 0.1, F = 0.02;
  Sys sys;
  sys.C(0, 0) = c;
  sys.k3 = k3;
  sys.f(0) = F;
  auto cont = frequency_continuation(sys, 0.9, 1.15, 0.05);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 0.9);
  ASSERT_TRUE(branch.completed()) << branch.message;
  const auto& pts = branch.points;
  ASSERT_GE(pts.size(), 20u);

  // Turning points: where the parameter's direction along the branch reverses.
  std::vector<std::size_t> turns;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double before = pts[i].parameter - pts[i - 1].parameter;
    const double after = pts[i + 1].parameter - pts[i].parameter;
    if (before * after < 0) turns.push_back(i);
  }
  ASSERT_EQ(turns.size(), 2u) << "expected the upper and the lower fold";

  // Fold frequencies from the branch (parabola through the three points around each turn, in
  // terms of the amplitude) vs the one-harmonic balance (local max and min of w_plus(A) on a
  // fine grid). The balance neglects the third harmonic (relative size k3 A^2 / 32 / 8 ~ 4e-4 at
  // A ~ 1), whose effect on the frequency is of second order, ~(3/4 k3 A^2)^2 / 32 ~ 2e-4;
  // measured: 9e-5 and 1e-5. 5e-4 allowed (the fold spacing is 9e-3).
  // w_plus falls from large values at small A (far right of the resonance) to its local min
  // (the lower, jump-up fold), then rises to its local max (the upper, jump-down fold) before
  // the two roots merge at the peak amplitude.
  double hb_min = std::nan(""), hb_max = std::nan("");
  double prev = hb_w_plus(0.05, c, k3, F), slope = -1;
  for (double A = 0.05 + 1e-5; A < 2.0; A += 1e-5) {
    const double w = hb_w_plus(A, c, k3, F);
    if (std::isnan(w)) break;
    const double s = w - prev;
    if (slope < 0 && s > 0) hb_min = prev;
    if (slope > 0 && s < 0) hb_max = prev;
    slope = s;
    prev = w;
  }
  ASSERT_FALSE(std::isnan(hb_min) || std::isnan(hb_max));
  double fold[2];
  for (int k = 0; k < 2; ++k) {
    const std::size_t i = turns[static_cast<std::size_t>(k)];
    fold[k] = parabola_vertex(pts[i - 1].orbit.amplitudes[0], pts[i - 1].parameter,
                              pts[i].orbit.amplitudes[0], pts[i].parameter,
                              pts[i + 1].orbit.amplitudes[0], pts[i + 1].parameter);
  }
  EXPECT_NEAR(fold[0], hb_max, 5e-4 * hb_max);  // the jump-down (upper) fold comes first
  EXPECT_NEAR(fold[1], hb_min, 5e-4 * hb_min);

  // Stability: stable outside the folds, unstable between them through +1 (a real multiplier
  // > 1); the two changes at the folds. Points next to a turn are skipped (their multiplier is
  // within the step of 1).
  int changes = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    changes += pts[i].stability_changed ? 1 : 0;
    const bool near_turn = i + 1 >= turns[0] && i <= turns[0] + 1;
    const bool near_turn2 = i + 1 >= turns[1] && i <= turns[1] + 1;
    if (near_turn || near_turn2) continue;
    const bool middle = i > turns[0] && i < turns[1];
    EXPECT_EQ(pts[i].orbit.floquet.stable, !middle) << "point " << i << " omega " << pts[i].parameter;
    if (middle) {
      EXPECT_EQ(pts[i].orbit.floquet.instability, stickslip::Instability::Fold);
    }
    // Liouville: det M = exp(trace(df/dx) T) = exp(-c T) (the cubic term has zero trace).
    // 1e-8: central-difference Jacobian (h = 1e-6, cubic: error h^2 k3 ~ 1e-13) and the run
    // error rtol 1e-10 over one period.
    const double T = 2 * kPi / pts[i].parameter;
    EXPECT_NEAR(pts[i].orbit.monodromy.determinant(), std::exp(-c * T), 1e-8);
  }
  EXPECT_EQ(changes, 2);
}

}  // namespace
}  // namespace steady_state_continuation_test

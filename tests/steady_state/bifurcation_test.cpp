// Bifurcations along a branch and branch switching at a period doubling, on the strongly forced
// Duffing oscillator x'' + 0.2 x' + x + x^3 = 20 cos(w t), whose period-1 branch coming down
// from w = 0.82 loses stability through -1 near w = 0.795 (long transients from rest: period 1
// at 0.80-0.82, period 2 at 0.75-0.79):
//  - the continuation reports the crossing as a period doubling, and locate_flip puts it where
//    an independent computation does: Fourier collocation of the period-1 orbit and the sign of
//    the determinant of its linearisation on antiperiodic functions (v(t + T) = -v(t): a
//    multiplier -1 exactly where that operator is singular), bisected in w;
//  - the period-2T branch born there: its orbits are not period 1, and one of them is the
//    attractor a long transient from rest (plain RK4 written here) settles on, with the
//    amplitude that transient shows; the largest stable response over both branches
//    (largest_stable_response) counts it.

#include "steady_state/duffing_reference.hpp"
#include "steady_state/smooth_forced_systems.hpp"

#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/peak_response.hpp>
#include <stickslip/steady_state/period_doubling.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace steady_state_bifurcation_test {  // named: the steady-state test files share one unity TU
namespace {

using Duffing = steady_state_test::ForcedOscillator<1>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 0.2, kF = 20;

Duffing duffing(double w) {
  Duffing d;
  d.C(0, 0) = kC;
  d.k3 = 1;
  d.f(0) = kF;
  d.omega = w;
  return d;
}

// Plain RK4 of the Duffing oscillator, n steps per period, from (x, v) at t = 0 over `periods`
// periods; `sample` (size n) gets the last period's x at t = j T / n when given.
Eigen::Vector2d rk4(double w, Eigen::Vector2d y, int periods, int n, Eigen::VectorXd* sample = nullptr,
                    double* lo = nullptr, double* hi = nullptr) {
  const double T = 2 * kPi / w, h = T / n;
  auto f = [w](double t, const Eigen::Vector2d& s) {
    return Eigen::Vector2d(s[1], kF * std::cos(w * t) - kC * s[1] - s[0] - s[0] * s[0] * s[0]);
  };
  for (int p = 0; p < periods; ++p)
    for (int j = 0; j < n; ++j) {
      if (sample && p == periods - 1) (*sample)[j] = y[0];
      if (lo && p >= periods - 2) {  // extremes over the last two periods
        *lo = std::min(*lo, y[0]);
        *hi = std::max(*hi, y[0]);
      }
      const double t = p * T + j * h;
      const Eigen::Vector2d k1 = f(t, y), k2 = f(t + h / 2, y + h / 2 * k1), k3 = f(t + h / 2, y + h / 2 * k2),
                            k4 = f(t + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
  return y;
}

// Sign of det of the period-1 orbit's linearisation on antiperiodic functions, by collocation on
// N (even) points of [0, T): v'' + c v' + (1 + 3 x^2) v with the derivative of the 2N-point grid
// on [0, 2T) restricted to v_{j+N} = -v_j (N even: the 2N grid's Nyquist harmonic is even, not
// antiperiodic). The collocated orbit x is updated to w (Newton from the given samples).
int antiperiodic_sign(double w, Eigen::VectorXd& x) {
  const int N = static_cast<int>(x.size());
  steady_state_test::DuffingParameters p{kC, 1, 1, kF, w};
  EXPECT_LT(steady_state_test::duffing_collocation(p, N, x), 1e-9) << "w = " << w;
  const Eigen::MatrixXd D2N = steady_state_test::fourier_derivative(2 * N, 2 * (2 * kPi / w));
  const Eigen::MatrixXd Da = D2N.topLeftCorner(N, N) - D2N.topRightCorner(N, N);
  Eigen::MatrixXd A = Da * Da + kC * Da;
  A.diagonal().array() += 1 + 3 * x.array().square();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
  int sign = static_cast<int>(lu.permutationP().determinant());
  for (Eigen::Index i = 0; i < N; ++i) sign *= lu.matrixLU()(i, i) < 0 ? -1 : 1;
  return sign;
}

// locate_bifurcations on constructed points whose monodromy is M = diag-like with known
// multipliers: one real multiplier through +1 while the parameter keeps increasing (pitchfork),
// the same with the parameter turning back (fold), a real one through -1 (period doubling) and a
// complex pair of argument 1 rad through the circle (Neimark-Sacker), each at the parameter
// where the interpolated |mu| is 1.
struct FakePoint {
  using Scalar = double;
  double parameter = 0;
  struct {
    stickslip::FloquetMultipliers<double> floquet;
  } orbit;
};
FakePoint fake(double p, double mu_a, double mu_b, bool complex_pair = false) {
  Eigen::Matrix2d M;
  if (complex_pair)  // mu_a e^{+-i}: a rotation by 1 rad scaled by mu_a
    M << mu_a * std::cos(1.0), -mu_a * std::sin(1.0), mu_a * std::sin(1.0), mu_a * std::cos(1.0);
  else
    M << mu_a, 0, 0, mu_b;
  FakePoint f;
  f.parameter = p;
  f.orbit.floquet = stickslip::floquet_multipliers<double>(M, false, 1e-6);
  return f;
}

TEST(SteadyStateBifurcation, CrossingsAreClassifiedByTheMultiplierAndTheBranchTurn) {
  using stickslip::BifurcationKind;
  const auto kinds = [](const std::vector<FakePoint>& pts) {
    const auto b = stickslip::locate_bifurcations(pts);
    EXPECT_EQ(b.size(), 1u);
    return b.empty() ? stickslip::BifurcationPoint<double>{} : b[0];
  };
  // +1 with p increasing throughout: pitchfork at p = 1.5 (|mu| - 1 = -0.1 -> +0.1).
  auto b = kinds({fake(0, 0.8, 0.5), fake(1, 0.9, 0.5), fake(2, 1.1, 0.5), fake(3, 1.2, 0.5)});
  EXPECT_EQ(b.kind, BifurcationKind::Pitchfork);
  EXPECT_NEAR(b.parameter, 1.5, 1e-12);
  EXPECT_EQ(b.before, 1u);
  EXPECT_TRUE(b.destabilising);
  // The same multipliers on a branch that turns (p 0, 1, 1.2, 1.1): fold.
  b = kinds({fake(0, 0.8, 0.5), fake(1, 0.9, 0.5), fake(1.2, 1.1, 0.5), fake(1.1, 1.2, 0.5)});
  EXPECT_EQ(b.kind, BifurcationKind::Fold);
  // Through -1, and back in (stabilising).
  b = kinds({fake(0, -0.9, 0.5), fake(1, -1.3, 0.5)});
  EXPECT_EQ(b.kind, BifurcationKind::PeriodDoubling);
  EXPECT_NEAR(b.parameter, 0.25, 1e-12);
  b = kinds({fake(0, -1.3, 0.5), fake(1, -0.9, 0.5)});
  EXPECT_EQ(b.kind, BifurcationKind::PeriodDoubling);
  EXPECT_FALSE(b.destabilising);
  // A complex pair through the circle.
  b = kinds({fake(0, 0.95, 0, true), fake(1, 1.05, 0, true)});
  EXPECT_EQ(b.kind, BifurcationKind::NeimarkSacker);
  EXPECT_NEAR(b.parameter, 0.5, 1e-12);
  // A pair colliding outside the circle into two real multipliers: no crossing, nothing reported.
  EXPECT_TRUE(stickslip::locate_bifurcations(std::vector<FakePoint>{fake(0, 1.5, 0, true), fake(1, 1.6, 1.4)}).empty());
}

TEST(SteadyStateBifurcation, DuffingFlipLocatedAtTheCollocationReferenceAndItsPeriodTwoBranchIsTheAttractor) {
  const double w0 = 0.82;
  Duffing sys = duffing(w0);
  stickslip::ShootingOptions<double> so;
  so.outputs = Eigen::RowVector2d(1, 0);  // y = x
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = 0.76;
  co.parameter_max = w0;
  co.direction = -1;
  co.initial_step = 0.01;
  co.max_step = 0.05;
  co.max_points = 200;
  auto set_w = [](Duffing& s, double w) { s.omega = w; };
  auto period_of = [](double w) { return 2 * kPi / w; };
  stickslip::Continuation<Duffing> cont(sys, set_w, period_of, so, co);
  // The start: the end of a transient from rest (the attractor at 0.82, period 1).
  const Eigen::Vector2d x_start = rk4(w0, Eigen::Vector2d::Zero(), 300, 2000);
  const auto branch = cont.run(0, 0.0, x_start, w0);
  ASSERT_FALSE(branch.points.empty()) << branch.message;
  const stickslip::BifurcationPoint<double>* flip_at = nullptr;
  for (const auto& b : branch.bifurcations) {
    std::printf("bifurcation %s at w ~ %.6f (between points %zu and %zu)\n", stickslip::to_string(b.kind), b.parameter,
                b.before, b.before + 1);
    if (!flip_at && b.kind == stickslip::BifurcationKind::PeriodDoubling) flip_at = &b;
  }
  ASSERT_NE(flip_at, nullptr) << "no period doubling on the branch (" << branch.points.size() << " points, "
                              << stickslip::to_string(branch.status) << ")";
  EXPECT_TRUE(flip_at->destabilising);
  stickslip::PeriodDoubling<Duffing> pd(sys, set_w, period_of, so, co);
  const auto flip = pd.locate_flip(branch.points[flip_at->before], branch.points[flip_at->before + 1], 1e-9);
  ASSERT_TRUE(flip.ok) << flip.message;
  EXPECT_NEAR(flip.multiplier, -1, 1e-9);

  // The reference: the collocated period-1 orbit from the RK4 transient's last period at 0.82,
  // followed down in w; the determinant's sign change bracketed on a 0.002 grid and bisected.
  const int N = 128;
  Eigen::VectorXd x(N);
  {
    Eigen::VectorXd fine(N * 16);
    rk4(w0, Eigen::Vector2d::Zero(), 300, N * 16, &fine);
    for (int j = 0; j < N; ++j) x[j] = fine[16 * j];
  }
  // The collocation resolves the orbit: its top harmonics (near N / 2 = 64) are ~1e-11 of the
  // first, and the orbit's truncation error with them.
  {
    steady_state_test::DuffingParameters p{kC, 1, 1, kF, w0};
    ASSERT_LT(steady_state_test::duffing_collocation(p, N, x), 1e-9);
    const auto fx = steady_state_test::fourier(x, 63);
    ASSERT_LT(std::hypot(fx.a[60], fx.b[60]), 1e-10 * std::hypot(fx.a[0], fx.b[0]));
  }
  double hi = w0;
  int s_hi = antiperiodic_sign(hi, x);
  double lo = hi;
  Eigen::VectorXd x_hi = x;
  for (;;) {
    lo = hi - 0.002;
    ASSERT_GT(lo, 0.77) << "no sign change of the antiperiodic determinant";
    if (antiperiodic_sign(lo, x) != s_hi) break;
    hi = lo;
    x_hi = x;
  }
  while (hi - lo > 1e-11) {
    const double mid = (lo + hi) / 2;
    Eigen::VectorXd xm = x_hi;
    if (antiperiodic_sign(mid, xm) == s_hi) {
      hi = mid;
      x_hi = xm;
    } else {
      lo = mid;
    }
  }
  const double w_ref = (lo + hi) / 2;
  std::printf("flip: located at w = %.10f (mu = %.12f), collocation reference %.10f\n", flip.parameter,
              flip.multiplier, w_ref);
  // 1e-7: the located multiplier is -1 to 1e-9 and the monodromy is the runs' (rtol 1e-10, a few
  // 1e-9 after a period of ~4000 steps) against dmu/dw ~ O(10); the reference resolves the orbit
  // to ~1e-12 (top harmonics) and bisects w to 1e-11. Measured difference: printed above.
  EXPECT_NEAR(flip.parameter, w_ref, 1e-7);

  // The period-2T branch, 0.05 from the flip along the eigenvector.
  const auto two = pd.period_doubled_branch(flip, 0.05);
  ASSERT_GE(two.points.size(), 3u) << stickslip::to_string(two.status) << ": " << two.message;
  for (const auto& pt : two.points) {
    EXPECT_NEAR(pt.orbit.period, 2 * 2 * kPi / pt.parameter, 1e-12);
    EXPECT_LT(pt.parameter, flip.parameter + 1e-9);  // born on the side where period 1 is unstable
  }
  // A stable point of the 2T branch against the attractor of a long transient from rest: after
  // 600 periods (decay exp(-0.1 t): e^-480) RK4 with T / 4000 steps (error ~(w_eff h)^4, w_eff ~ 5:
  // ~1e-9) sits on the period-2 orbit: its sections at even and odd periods are the orbit's x0
  // and its state after one period (in either order). 1e-6 allowed.
  const auto* probe = &two.points.back();
  for (const auto& pt : two.points)
    if (pt.orbit.floquet.stable && pt.parameter < flip.parameter - 0.003) {
      probe = &pt;
      break;
    }
  ASSERT_TRUE(probe->orbit.floquet.stable) << "no stable 2T orbit 0.003 below the flip";
  const double w = probe->parameter;
  double lo2 = HUGE_VAL, hi2 = -HUGE_VAL;
  const Eigen::Vector2d even = rk4(w, Eigen::Vector2d::Zero(), 600, 4000);
  const Eigen::Vector2d odd = rk4(w, Eigen::Vector2d::Zero(), 601, 4000, nullptr, &lo2, &hi2);
  Duffing at_w = duffing(w);
  stickslip::HybridStepper<Duffing, stickslip::DormandPrince54> stepper(at_w, so.stepper);
  const auto half = stepper.integrate(0, probe->orbit.t0, probe->orbit.x0, probe->orbit.t0 + 2 * kPi / w);
  ASSERT_TRUE(half.ok());
  const Eigen::Vector2d a = probe->orbit.x0, b = half.x;
  EXPECT_GT((a - b).norm(), 1e-3);  // not period 1
  const double direct = std::max((even - a).norm(), (odd - b).norm());
  const double swapped = std::max((even - b).norm(), (odd - a).norm());
  std::printf("2T orbit at w = %.5f: |x(T) - x(0)| = %.3e, transient's sections off by %.2e\n", w, (a - b).norm(),
              std::min(direct, swapped));
  EXPECT_LT(std::min(direct, swapped), 1e-6);
  // Its amplitude (over its own 2T) is the transient's half peak-to-peak over two periods: both
  // sampled (256 and 4000 a period: short of the peak by at most A (1 - cos(pi / 256)) = 7.5e-5 A).
  const double A = probe->orbit.outputs.at(0).amplitude();
  EXPECT_NEAR(A, (hi2 - lo2) / 2, 1e-4 * A);
  // The objective over both branches counts the 2T response: at least this orbit's amplitude,
  // from a stable orbit.
  const auto peak = stickslip::largest_stable_response<Duffing>({&branch, &two});
  ASSERT_TRUE(peak.found);
  EXPECT_GE(peak.value, A);
  const auto& best = (peak.branch == 0 ? branch : two).points.at(peak.point);
  EXPECT_TRUE(best.orbit.floquet.stable);
  EXPECT_DOUBLE_EQ(best.orbit.outputs[0].amplitude(), peak.value);
  std::printf("largest stable response over both branches: %.6f at w = %.5f (branch %zu, period %.4f)\n", peak.value,
              peak.parameter, peak.branch, peak.period);
}

}  // namespace
}  // namespace steady_state_bifurcation_test

// Continuation of forced periodic orbits on smooth oscillators (tests/steady_state/smooth_forced_systems.hpp):
//  - a linear 2-DOF damped scene: the frequency-response curve against the closed-form complex
//    receptance, every point stable with multipliers exp(lambda_k T);
//  - a hardening Duffing oscillator: the branch passes both folds, the middle branch is unstable
//    through +1, the fold frequencies agree with the one-harmonic balance, and det M = exp(-c T)
//    (Liouville) at every point;
//  - SplitContinuation: the same branches in parts on threads, joined (or not, where a part's
//    start lies on the other side of a fold) into the serial branch.

#include "steady_state/smooth_forced_systems.hpp"
#include "steady_state/steady_state_test_support.hpp"

#include <stickslip/steady_state/split_continuation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <algorithm>
#include <complex>
#include <vector>

namespace steady_state_continuation_test {
namespace {

using namespace steady_state_test;
constexpr double kPi = 3.14159265358979323846;
using cd = std::complex<double>;

// Continuation options over the excitation frequency range [w_lo, w_hi].
stickslip::ContinuationOptions<double> frequency_options(double w_lo, double w_hi, double max_step) {
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = w_lo;
  co.parameter_max = w_hi;
  co.max_step = max_step;
  co.initial_step = 0.01;
  co.max_points = 2000;
  return co;
}

template <class Sys>
stickslip::Continuation<Sys> frequency_continuation(Sys& sys, double w_lo, double w_hi,
                                                    double max_step, int chord_iterations = 0) {
  stickslip::ContinuationOptions<double> co = frequency_options(w_lo, w_hi, max_step);
  co.chord_iterations = chord_iterations;
  return stickslip::Continuation<Sys>(
      sys, [](Sys& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, {}, co);
}

// M = I, K = [2 -1; -1 2] (natural frequencies 1 and sqrt 3), C = 0.02 K + 0.01 I, force on
// DOF 0. Closed form: q(t) = Re(H f e^{i w t}), H = (K - w^2 M + i w C)^-1, so at t0 = 0
// q(0) = Re(H f), q'(0) = -w Im(H f), amplitude |(H f)_i|; monodromy exp(A T), A = [0 I; -K -C].
// The linear 2-DOF scene of the receptance tests.
ForcedOscillator<2> two_dof_scene() {
  ForcedOscillator<2> sys;
  sys.K << 2, -1, -1, 2;
  sys.C = 0.02 * sys.K + 0.01 * Eigen::Matrix2d::Identity();
  return sys;
}

// Every point of a branch of the 2-DOF scene against the closed-form receptance and multipliers;
// returns the largest frequency reached.
double expect_receptance(const ForcedOscillator<2>& sys,
                         const std::vector<stickslip::ContinuationPoint<ForcedOscillator<2>>>& points) {
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.topRightCorner<2, 2>().setIdentity();
  A.bottomLeftCorner<2, 2>() = -sys.K;
  A.bottomRightCorner<2, 2>() = -sys.C;
  // The dynamic-size solver that floquet_multipliers instantiates anyway (a fixed 4 x 4 one cost
  // this unit ~8 s of compilation).
  const Eigen::Vector4cd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(A)).eigenvalues();
  double w_max = 0;
  for (const auto& pt : points) {
    const double w = pt.parameter;
    SCOPED_TRACE(::testing::Message() << "omega " << w);
    w_max = std::max(w_max, w);
    const Eigen::Matrix2cd D = sys.K.cast<cd>() - w * w * Eigen::Matrix2cd::Identity() +
                               cd(0, w) * sys.C.cast<cd>();
    // q(t0) = Re(H f e^{i w t0}) at the orbit's own section t0 (0 unless the start was later).
    const Eigen::Vector2cd Hf = D.partialPivLu().solve(sys.f.cast<cd>()) * std::exp(cd(0, w * pt.orbit.t0));
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
  return w_max;
}

// M = I, K = [2 -1; -1 2] (natural frequencies 1 and sqrt 3), C = 0.02 K + 0.01 I, force on
// DOF 0. Closed form: q(t) = Re(H f e^{i w t}), H = (K - w^2 M + i w C)^-1, so at t0 = 0
// q(0) = Re(H f), q'(0) = -w Im(H f), amplitude |(H f)_i|; monodromy exp(A T), A = [0 I; -K -C].
TEST(SteadyStateContinuation, LinearTwoDofFrequencyResponseIsTheReceptance) {
  using Sys = ForcedOscillator<2>;
  Sys sys = two_dof_scene();
  auto cont = frequency_continuation(sys, 0.5, 2.2, 1.0);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 0.5);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_GE(branch.points.size(), 30u);
  EXPECT_GT(expect_receptance(sys, branch.points), 2.1);  // reached the end of the range through both resonances
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

constexpr double kDuffingC = 0.02, kDuffingK3 = 0.1, kDuffingF = 0.02;

ForcedOscillator<1> duffing_scene() {
  ForcedOscillator<1> sys;
  sys.C(0, 0) = kDuffingC;
  sys.k3 = kDuffingK3;
  sys.f(0) = kDuffingF;
  return sys;
}

// The folds of the one-harmonic balance: the local min and max of w_plus(A) on a fine grid.
// w_plus falls from large values at small A (far right of the resonance) to its local min (the
// lower, jump-up fold), then rises to its local max (the upper, jump-down fold) before the two
// roots merge at the peak amplitude.
void balance_folds(double& hb_min, double& hb_max) {
  const double c = kDuffingC, k3 = kDuffingK3, F = kDuffingF;
  hb_min = std::nan("");
  hb_max = std::nan("");
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
}

// Turning points of a branch: where the parameter's direction along the branch reverses.
template <class Points>
std::vector<std::size_t> turning_points(const Points& pts) {
  std::vector<std::size_t> turns;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const double before = pts[i].parameter - pts[i - 1].parameter;
    const double after = pts[i + 1].parameter - pts[i].parameter;
    if (before * after < 0) turns.push_back(i);
  }
  return turns;
}

// The Duffing branch over [0.9, 1.15] passes both folds at the balance's frequencies, unstable
// through +1 between them, with det M = exp(-c T) at every point.
void expect_duffing_branch(const std::vector<stickslip::ContinuationPoint<ForcedOscillator<1>>>& pts) {
  ASSERT_GE(pts.size(), 20u);
  const std::vector<std::size_t> turns = turning_points(pts);
  ASSERT_EQ(turns.size(), 2u) << "expected the upper and the lower fold";

  // Fold frequencies from the branch (parabola through the three points around each turn, in
  // terms of the amplitude) vs the one-harmonic balance. The balance neglects the third harmonic
  // (relative size k3 A^2 / 32 / 8 ~ 4e-4 at A ~ 1), whose effect on the frequency is of second
  // order, ~(3/4 k3 A^2)^2 / 32 ~ 2e-4; measured: 9e-5 and 1e-5. 5e-4 allowed (the fold spacing
  // is 9e-3).
  double hb_min = 0, hb_max = 0;
  balance_folds(hb_min, hb_max);
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
    EXPECT_NEAR(pts[i].orbit.monodromy.determinant(), std::exp(-kDuffingC * T), 1e-8);
  }
  EXPECT_EQ(changes, 2);
}

TEST(SteadyStateContinuation, DuffingBranchPassesBothFoldsWithStabilityChangeThroughPlusOne) {
  using Sys = ForcedOscillator<1>;
  Sys sys = duffing_scene();
  auto cont = frequency_continuation(sys, 0.9, 1.15, 0.05);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 0.9);
  ASSERT_TRUE(branch.completed()) << branch.message;
  expect_duffing_branch(branch.points);
  // The two stability changes are folds (the branch turns at both): the upper one loses
  // stability, the lower one regains it.
  ASSERT_EQ(branch.bifurcations.size(), 2u);
  for (const auto& b : branch.bifurcations) EXPECT_EQ(b.kind, stickslip::BifurcationKind::Fold);
  EXPECT_TRUE(branch.bifurcations[0].destabilising);
  EXPECT_FALSE(branch.bifurcations[1].destabilising);
}

// The same branch with chord iterations (plain runs solved with the last point's [M - I, dG/dp]
// before Newton's variational runs): every point is still confirmed by Newton's test, so the
// same closed-form checks hold - through both folds, where the Jacobian changes fastest and the
// chord must hand over to Newton.
TEST(SteadyStateContinuation, DuffingBranchWithChordIterationsPassesBothFoldsAsWithNewton) {
  using Sys = ForcedOscillator<1>;
  Sys sys = duffing_scene();
  auto cont = frequency_continuation(sys, 0.9, 1.15, 0.05, 4);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 0.9);
  ASSERT_TRUE(branch.completed()) << branch.message;
  expect_duffing_branch(branch.points);
}

// A start at the end of a transient, t0 = 200 T(0.5): at that fixed section the orbit's state
// turns with the forcing phase w t0 (|dx0/dw| ~ |x| t0 = 2500 |x|), a helix of 200 turns per
// unit of w T / (2 pi) that the secant predictor cannot follow: 30 points do not reach the first
// resonance (each advances w by at most max_step / (|x| t0) ~ 4e-4). Reduced into the first
// period (ContinuationOptions::wrap_section, the default), the branch passes the first resonance
// (w = 1) and is the closed form's at each orbit's own t0, as from t0 = 0.
TEST(SteadyStateContinuation, StartLateInTimeIsWrappedIntoThePeriodAndFollowsTheReceptance) {
  using Sys = ForcedOscillator<2>;
  const double w0 = 0.5, w1 = 1.3, t0 = 200 * (2 * kPi / w0);
  Sys sys = two_dof_scene();
  auto cont = frequency_continuation(sys, w0, w1, 1.0);
  const auto branch = cont.run(0, t0, Sys::State::Zero(), w0);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_GE(branch.points.size(), 10u);
  EXPECT_LT(branch.points.size(), 200u);
  for (const auto& pt : branch.points) {
    EXPECT_GE(pt.orbit.t0, 0.0);
    EXPECT_LT(pt.orbit.t0, pt.orbit.period);
  }
  EXPECT_GT(expect_receptance(sys, branch.points), 1.2);

  Sys fixed_sys = two_dof_scene();
  stickslip::ContinuationOptions<double> co = frequency_options(w0, w1, 1.0);
  co.max_points = 30;
  co.wrap_section = false;
  stickslip::Continuation<Sys> fixed(
      fixed_sys, [](Sys& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, {}, co);
  const auto helix = fixed.run(0, t0, Sys::State::Zero(), w0);
  EXPECT_FALSE(helix.completed());
  EXPECT_LT(helix.points.back().parameter, 0.6);  // not even near the first resonance
}

// A start within the first period is left where it is: the same points, bit for bit, with and
// without wrap_section (a smooth system has no events, so the section never moves).
TEST(SteadyStateContinuation, StartWithinThePeriodIsTheSameBranchWithOrWithoutWrapping) {
  using Sys = ForcedOscillator<1>;
  const double w0 = 0.9;
  auto branch = [&](bool wrap) {
    Sys sys = duffing_scene();
    stickslip::ContinuationOptions<double> co = frequency_options(w0, 1.15, 0.05);
    co.wrap_section = wrap;
    stickslip::Continuation<Sys> cont(
        sys, [](Sys& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, {}, co);
    return cont.run(0, 0.3 * (2 * kPi / w0), Sys::State::Zero(), w0);
  };
  const auto a = branch(true), b = branch(false);
  ASSERT_TRUE(a.completed()) << a.message;
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].parameter, b.points[i].parameter);
    EXPECT_EQ(a.points[i].orbit.t0, b.points[i].orbit.t0);
    EXPECT_EQ(a.points[i].orbit.x0, b.points[i].orbit.x0);
  }
}

// ---- SplitContinuation: one branch in parts on threads ------------------------------------------

template <class Sys>
stickslip::SplitContinuation<Sys> split_frequency_continuation(std::vector<Sys>& systems, double w_lo,
                                                               double w_hi, double max_step) {
  std::vector<Sys*> ptrs;
  for (Sys& s : systems) ptrs.push_back(&s);
  return stickslip::SplitContinuation<Sys>(
      ptrs, [](Sys& s, double w) { s.omega = w; }, [](double w) { return 2 * kPi / w; }, {},
      frequency_options(w_lo, w_hi, max_step));
}

// No gap at a join: the step into the first point of each joined part after the first is at
// most 1.1 times the longest step inside the parts (the next start lies within 0.1 |y_b - y_a|
// of the step (y_a, y_b) that joins it, so |y_s - y_a| <= 1.1 |y_b - y_a|).
template <class Result>
void expect_no_gap_at_the_joins(const Result& result) {
  const auto& pts = result.branch.points;
  auto step = [&](std::size_t i) {
    Eigen::VectorXd d(pts[i].orbit.x0.size() + 1);
    d << pts[i].orbit.x0 - pts[i - 1].orbit.x0, pts[i].parameter - pts[i - 1].parameter;
    return d.norm();
  };
  std::vector<std::size_t> joins;
  for (std::size_t k = 0, first = 0; k + 1 < result.parts.size() && result.parts[k].joined; ++k)
    joins.push_back(first += result.parts[k].kept);
  double inside = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (std::find(joins.begin(), joins.end(), i) == joins.end()) inside = std::max(inside, step(i));
  for (std::size_t i : joins) {
    ASSERT_LT(i, pts.size());
    EXPECT_LE(step(i), 1.1 * inside) << "the join before point " << i;
    EXPECT_NEAR(pts[i].step, step(i), 1e-12 * step(i));  // the joined point's step is that distance
  }
}

// Three parts over [0.5, 2.2] (starts at 0.5, 1.067, 1.633; [1.2, 2.2] under the sanitizers),
// each from rest: the linear scene has
// one orbit per frequency, so every part joins the next, and the joined branch is the receptance
// at every point (the closed form of the serial test), increasing in frequency, without a gap
// at a join; the same downwards in two parts.
TEST(SplitContinuation, LinearTwoDofCurveInPartsUpAndDownIsTheReceptanceWithEveryPartJoined) {
  using Sys = ForcedOscillator<2>;
#if defined(STICKSLIP_SANITIZED)
  const double lo = 1.2;  // the second resonance only: the sanitizers ran the whole range in 9 s
#else
  const double lo = 0.5;
#endif
  std::vector<Sys> systems(3, two_dof_scene());
  auto split = split_frequency_continuation(systems, lo, 2.2, 1.0);
  const auto result = split.run([](Sys&, double) {
    return stickslip::SplitContinuation<Sys>::Guess{0, 0.0, Sys::State::Zero()};
  });
  ASSERT_TRUE(result.completed()) << result.branch.message;
  ASSERT_EQ(result.parts.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(::testing::Message() << "part " << k);
    EXPECT_NEAR(result.parts[k].start_parameter, lo + static_cast<double>(k) * (2.2 - lo) / 3, 1e-12);
    EXPECT_EQ(result.parts[k].joined, k < 2);
    EXPECT_GE(result.parts[k].kept, 3u);
  }
  const auto& pts = result.branch.points;
  EXPECT_EQ(pts.size(), result.parts[0].kept + result.parts[1].kept + result.parts[2].kept);
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_GT(pts[i].parameter, pts[i - 1].parameter);
  expect_no_gap_at_the_joins(result);
  EXPECT_GT(expect_receptance(systems[0], pts), 2.1);

  // Downwards (direction -1) over [1.2, 2.2], the second resonance, in two parts: the cut at 1.7,
  // part 0 from 2.2, the joined branch decreasing in frequency and still the receptance.
  stickslip::ContinuationOptions<double> down = frequency_options(1.2, 2.2, 1.0);
  down.direction = -1;
  std::vector<Sys> two(2, two_dof_scene());
  stickslip::SplitContinuation<Sys> split_down({&two[0], &two[1]}, [](Sys& s, double w) { s.omega = w; },
                                               [](double w) { return 2 * kPi / w; }, {}, down);
  const auto result_down = split_down.run([](Sys&, double) {
    return stickslip::SplitContinuation<Sys>::Guess{0, 0.0, Sys::State::Zero()};
  });
  ASSERT_TRUE(result_down.completed()) << result_down.branch.message;
  EXPECT_NEAR(result_down.parts[0].start_parameter, 2.2, 1e-12);
  EXPECT_NEAR(result_down.parts[1].start_parameter, 1.7, 1e-12);
  EXPECT_TRUE(result_down.parts[0].joined);
  const auto& dpts = result_down.branch.points;
  ASSERT_GE(dpts.size(), 4u);
  for (std::size_t i = 1; i < dpts.size(); ++i) EXPECT_LT(dpts[i].parameter, dpts[i - 1].parameter);
  EXPECT_LT(dpts.back().parameter, 1.3);  // reached the lower end
  expect_no_gap_at_the_joins(result_down);
  expect_receptance(two[0], dpts);
}

// 1-DOF oscillator x'' + 0.3 x' + x = cos(w t) over [0.5, 1.5] in 20 parts of 0.05, narrower
// than the first (and largest) step 0.3: a part's first step crosses the next cut, so parts join
// on their first step. Such a part must still publish its start and second point for the part
// before it (it did not: the chain of joins broke, one part computed the branch alone and others
// ran to the end for nothing). Every part but the last joins, and the branch is the closed form
// x(t) = Re(H e^{i w t}), H = 1 / (1 - w^2 + 0.3 i w), at t0 = 0 (tolerance as in
// expect_receptance: the Newton tolerance 1e-9 and the runs' error times |(M - I)^-1| <= ~3 here).
TEST(SplitContinuation, PartsNarrowerThanTheFirstStepAllJoin) {
  using Sys = ForcedOscillator<1>;
  Sys base;
  base.C(0, 0) = 0.3;
  std::vector<Sys> systems(20, base);
  std::vector<Sys*> ptrs;
  for (Sys& s : systems) ptrs.push_back(&s);
  stickslip::ContinuationOptions<double> co = frequency_options(0.5, 1.5, 0.3);
  co.initial_step = 0.3;
  stickslip::SplitContinuation<Sys> split(ptrs, [](Sys& s, double w) { s.omega = w; },
                                          [](double w) { return 2 * kPi / w; }, {}, co);
  const auto result = split.run([](Sys&, double) {
    return stickslip::SplitContinuation<Sys>::Guess{0, 0.0, Sys::State::Zero()};
  });
  ASSERT_TRUE(result.completed()) << result.branch.message;
  std::size_t computed = 0;
  for (std::size_t k = 0; k < result.parts.size(); ++k) {
    EXPECT_EQ(result.parts[k].joined, k + 1 < result.parts.size()) << "part " << k;
    computed += result.parts[k].points;
  }
  const auto& pts = result.branch.points;
  EXPECT_EQ(pts.size(), computed);  // nothing computed for nothing
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_GT(pts[i].parameter, pts[i - 1].parameter);
  EXPECT_GT(pts.back().parameter, 1.4);
  for (const auto& pt : pts) {
    const double w = pt.parameter;
    const cd H = 1.0 / cd(1 - w * w, 0.3 * w);
    EXPECT_NEAR(pt.orbit.x0[0], H.real(), 1e-7) << "omega " << w;
    EXPECT_NEAR(pt.orbit.x0[1], -w * H.imag(), 1e-7) << "omega " << w;
  }
}

// The user's period is defined on the declared range only (NaN above 2.2, as a table lookup
// would be): the start at 2.2 - 1e-9 and every corrector take dG/dp one-sided there instead of
// a run at T(p + h) = NaN, which threw std::invalid_argument out of run(). The branch down to
// 1.8 is the receptance.
TEST(SteadyStateContinuation, PeriodUndefinedJustOutsideTheRangeIsNotEvaluated) {
  using Sys = ForcedOscillator<2>;
  Sys sys = two_dof_scene();
  stickslip::ContinuationOptions<double> co = frequency_options(1.8, 2.2, 0.1);
  co.direction = -1;
  stickslip::Continuation<Sys> cont(
      sys, [](Sys& s, double w) { s.omega = w; },
      [](double w) { return w <= 2.2 ? 2 * kPi / w : std::nan(""); }, {}, co);
  const auto branch = cont.run(0, 0.0, Sys::State::Zero(), 2.2 - 1e-9);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_GE(branch.points.size(), 3u);
  EXPECT_LT(branch.points.back().parameter, 1.9);
  expect_receptance(sys, branch.points);
}

// The same curve in two parts with a join tolerance of 1e-5: the chord of the step over the cut
// misses the next start by ~kappa |dy|^2 / 8, far more than 1e-5 |dy| on this curved branch, so
// only the fallback joins them: part 0's orbit at the cut, shot from the chord's point there, is
// the next start's orbit (a linear scene: Newton lands on it to the runs' ~1e-10). The joined
// branch is still the receptance, without a gap.
TEST(SplitContinuation, ChordThatMissesTheNextStartJoinsByTheOrbitAtTheCut) {
  using Sys = ForcedOscillator<2>;
  std::vector<Sys> systems(2, two_dof_scene());
  auto split = split_frequency_continuation(systems, 1.2, 2.2, 1.0);
  split.join_tolerance(1e-5);
  const auto result = split.run([](Sys&, double) {
    return stickslip::SplitContinuation<Sys>::Guess{0, 0.0, Sys::State::Zero()};
  });
  ASSERT_TRUE(result.completed()) << result.branch.message;
  EXPECT_TRUE(result.parts[0].joined);
  EXPECT_EQ(result.parts[0].kept, result.parts[0].points);
  EXPECT_EQ(result.parts[1].kept, result.parts[1].points);
  const auto& pts = result.branch.points;
  for (std::size_t i = 1; i < pts.size(); ++i) EXPECT_GT(pts[i].parameter, pts[i - 1].parameter);
  expect_no_gap_at_the_joins(result);
  expect_receptance(systems[0], pts);
}

// Two parts over [0.91, 1.15], cut at 1.03 between the folds (1.026 and 1.035 by the balance:
// three orbits there). Part 1's
// start orbit is picked by its guess, taken from the serial branch's point nearest the cut on each
// of the three sheets (nearest 1.03): on the lower or the upper (stable) sheet, part 0's branch runs into it
// (after both folds, or before the first) and the parts join; on the middle (unstable) sheet
// part 0 crosses 1.03 there going down in frequency, against part 1's direction, so it does
// not join, runs to the end alone and part 1 is dropped. Every time the joined branch is the
// serial one: both folds at the balance's frequencies, the stability pattern, Liouville.
TEST(SplitContinuation, DuffingBranchCutBetweenTheFoldsJoinsOnlyWhereTheBranchRunsOnInOneDirection) {
  using Sys = ForcedOscillator<1>;
  double hb_min = 0, hb_max = 0;
  balance_folds(hb_min, hb_max);
  const double cut = 1.03;
  ASSERT_TRUE(hb_min < cut && cut < hb_max) << hb_min << " " << hb_max;
  Sys serial_sys = duffing_scene();
  const auto serial = frequency_continuation(serial_sys, 0.91, 1.15, 0.05).run(0, 0.0, Sys::State::Zero(), 0.91);
  ASSERT_TRUE(serial.completed()) << serial.message;
  const std::vector<std::size_t> turns = turning_points(serial.points);
  ASSERT_EQ(turns.size(), 2u);
  // The serial branch's point nearest the cut on sheet s (0 upper, 1 middle, 2 lower).
  auto nearest_on_sheet = [&](int s) {
    const std::size_t lo = s == 0 ? 0 : turns[static_cast<std::size_t>(s - 1)];
    const std::size_t hi = s == 2 ? serial.points.size() : turns[static_cast<std::size_t>(s)] + 1;
    std::size_t best = lo;
    for (std::size_t i = lo; i < hi; ++i)
      if (std::abs(serial.points[i].parameter - cut) < std::abs(serial.points[best].parameter - cut)) best = i;
    return serial.points[best].orbit.x0;
  };
  for (int sheet = 0; sheet < 3; ++sheet) {
    SCOPED_TRACE(::testing::Message() << "part 1 starts on sheet " << sheet << " (0 upper, 1 middle, 2 lower)");
    const Sys::State guess = nearest_on_sheet(sheet);
    std::vector<Sys> systems(2, duffing_scene());
    auto split = split_frequency_continuation(systems, 0.91, 1.15, 0.05);
    std::vector<int> first_stable(2, -1);  // each part writes its own entry (own thread)
    split.on_point([&](std::size_t k, const stickslip::ContinuationPoint<Sys>& pt) {
      if (first_stable[k] < 0) first_stable[k] = pt.orbit.floquet.stable ? 1 : 0;
    });
    const auto result = split.run([&](Sys&, double w) {
      return stickslip::SplitContinuation<Sys>::Guess{0, 0.0, w == 0.91 ? Sys::State::Zero() : guess};
    });
    ASSERT_TRUE(result.completed()) << result.branch.message;
    ASSERT_EQ(result.parts.size(), 2u);
    EXPECT_NEAR(result.parts[1].start_parameter, cut, 1e-12);
    EXPECT_EQ(result.parts[1].status, stickslip::ContinuationStatus::Completed);
    const bool joins = sheet != 1;
    EXPECT_EQ(result.parts[0].joined, joins);
    EXPECT_EQ(result.parts[0].status,
              joins ? stickslip::ContinuationStatus::Stopped : stickslip::ContinuationStatus::Completed);
    EXPECT_EQ(result.parts[1].kept, joins ? result.parts[1].points : 0u);
    ASSERT_EQ(result.dropped.size(), 2u);
    EXPECT_TRUE(result.dropped[0].points.empty());
    EXPECT_EQ(result.dropped[1].points.size(), joins ? 0u : result.parts[1].points);  // kept aside
    EXPECT_EQ(first_stable[1], sheet == 1 ? 0 : 1);  // part 1 started on the sheet asked for
    expect_no_gap_at_the_joins(result);
    expect_duffing_branch(result.branch.points);
  }
}

}  // namespace
}  // namespace steady_state_continuation_test

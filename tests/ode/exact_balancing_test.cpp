// AugmentedFlow (internal to ExactLinearStepper): exponentials of a badly scaled generator by
// balancing, exp(A tau) = D exp(B tau) D^-1, against the closed form of a damped oscillator;
// short hops of either sign on it; a nilpotent generator against its polynomial.

#include <stickslip/ode/detail/augmented_flow.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace ode_exact_balancing_test {  // named: the exact-stepper tests share a TU
namespace {

// q'' + 2 z w q' + w^2 q = 0 at the blade's top mode (w = 2 pi 2561 rad/s, ||A||_1 = w^2 = 2.6e8
// against |lambda| = w): exp(A t) = e^(-z w t) [[c + (z w / wd) s, s / wd], [-(w^2 / wd) s,
// c - (z w / wd) s]], c = cos(wd t), s = sin(wd t), wd = w sqrt(1 - z^2).
Eigen::Matrix2d damped_oscillator_exp(double w, double z, double t) {
  const double wd = w * std::sqrt(1 - z * z), c = std::cos(wd * t), s = std::sin(wd * t);
  Eigen::Matrix2d e;
  e << c + z * w / wd * s, s / wd, -w * w / wd * s, c - z * w / wd * s;
  return std::exp(-z * w * t) * e;
}

// The linear part of that oscillator (state (q, q')).
stickslip::LinearPart<double> oscillator_part(double w, double z) {
  stickslip::LinearPart<double> lp;
  lp.A.resize(2, 2);
  lp.A << 0, 1, -w * w, -2 * z * w;
  lp.b0.setZero(2);
  lp.version = 1;
  return lp;
}

// Forward (grid step and an odd fraction of it, as stage propagators) and backward (the dense
// output's exp(-h A)): the 2 x 2 block of the augmented propagator equals the closed form to 1e-13
// in the oscillator's own scale (q and q' / w: the entries differ by w^2 = 2.6e8 in size; Padé on
// ||B tau|| < 1 with a few products leaves a few ulps, 1e-13 is ~500 of them). One Padé each (no
// squarings to count, but one exponential per call). The ladder's walk with its Taylor tail on B
// (expv) gives the same propagation of a vector.
TEST(AugmentedFlowBalancing, ExponentialOfABadlyScaledOscillatorMatchesTheClosedForm) {
  const double w = 2 * 3.14159265358979323846 * 2561, z = 0.01;
  const stickslip::LinearPart<double> lp = oscillator_part(w, z);
  stickslip::detail::AugmentedFlow<double> flow;
  stickslip::ExactStepperStats st;
  flow.assign(lp, 2, st);
  const double delta = 2 * 3.14159265358979323846 / (8 * w);
  flow.prepare(delta, st);
  const Eigen::Matrix2d scale = Eigen::Vector2d(w, 1.0).asDiagonal();
  for (double tau : {delta, 0.3 * delta, -delta, 7.3 * delta}) {
    Eigen::MatrixXd e;
    const long before = st.propagator_exponentials;
    flow.expm(tau, e, st);
    EXPECT_EQ(st.propagator_exponentials, before + 1);
    const Eigen::Matrix2d ref = damped_oscillator_exp(w, z, tau);
    const Eigen::Matrix2d got = e.topLeftCorner(2, 2);
    EXPECT_LT((scale * (got - ref) * scale.inverse()).cwiseAbs().maxCoeff(), 1e-13) << "tau " << tau;
    EXPECT_DOUBLE_EQ(e(2, 2), 1.0);  // the clock component
    if (tau > 0) {
      Eigen::VectorXd v(3);
      v << 1e-3, 2.0, 1.0;
      Eigen::VectorXd u = v;
      flow.expv(tau, u, st);
      const Eigen::Vector2d vref = ref * v.head<2>();
      EXPECT_LT((scale * (u.head<2>() - vref)).cwiseAbs().maxCoeff(),
                1e-13 * (scale * v.head<2>()).cwiseAbs().maxCoeff())
          << "tau " << tau;
    }
  }
}

// Van Loan's block exponential with a quadrature form (the energy audit's kind: x_Q' = q'^2) on
// the same oscillator: its Phi block is the same exp(A tau), to 1e-13 in the oscillator's scale.
// The block [[-A^T, Q], [0, A]] is as badly scaled as A; unbalanced (before the fix), its Phi
// block was off by 4.3e-9 and 3.2e-9 here, and the blade's stick run, whose samples chain
// Phi(h_out) 5000 times over 0.5 s, drifted to 1.5e-8 of the tip amplitude (2.6e-10 balanced).
TEST(AugmentedFlowBalancing, VanLoanBlockOfABadlyScaledOscillatorMatchesTheClosedForm) {
  const double w = 2 * 3.14159265358979323846 * 2561, z = 0.01;
  const stickslip::LinearPart<double> lp = oscillator_part(w, z);
  stickslip::detail::AugmentedFlow<double> flow;
  stickslip::ExactStepperStats st;
  flow.assign(lp, 3, st);  // (q, q', x_Q) and the clock
  std::vector<Eigen::MatrixXd> forms(1, Eigen::MatrixXd::Zero(3, 3));  // z = (q, q', 1)
  forms[0](1, 1) = 1.0;
  const Eigen::Matrix2d scale = Eigen::Vector2d(w, 1.0).asDiagonal();
  for (double tau : {1e-4, 4.9e-5}) {
    Eigen::MatrixXd phi, wq;
    flow.van_loan(tau, forms, phi, wq, st);
    const Eigen::Matrix2d ref = damped_oscillator_exp(w, z, tau);
    const Eigen::Matrix2d got = phi.topLeftCorner(2, 2);
    EXPECT_LT((scale * (got - ref) * scale.inverse()).cwiseAbs().maxCoeff(), 1e-13) << "tau " << tau;
  }
}

// Short hops of either sign (the points of a root search, moved from one to the next): the same
// closed form to 1e-13 in the oscillator's scale (one Taylor series on ||B dt|| <= 1/2: a few
// ulps per term, as the test above); a hop longer than that is refused and leaves v as it was.
TEST(AugmentedFlowHop, ShortHopsEitherWayMatchTheClosedFormAndLongOnesAreRefused) {
  const double w = 2 * 3.14159265358979323846 * 2561, z = 0.01;
  const stickslip::LinearPart<double> lp = oscillator_part(w, z);
  stickslip::detail::AugmentedFlow<double> flow;
  stickslip::ExactStepperStats st;
  flow.assign(lp, 2, st);
  const Eigen::Matrix2d scale = Eigen::Vector2d(w, 1.0).asDiagonal();
  Eigen::VectorXd v(3);
  v << 1e-3, 2.0, 1.0;
  const double short_hop = 0.4 / w;  // ||B||_1 is of the order of w after balancing
  for (double dt : {short_hop, -short_hop, 1e-3 * short_hop, -1e-9 * short_hop}) {
    Eigen::VectorXd u = v;
    ASSERT_TRUE(flow.hop(dt, u, st)) << "dt " << dt;
    const Eigen::Vector2d vref = damped_oscillator_exp(w, z, dt) * v.head<2>();
    EXPECT_LT((scale * (u.head<2>() - vref)).cwiseAbs().maxCoeff(),
              1e-13 * (scale * v.head<2>()).cwiseAbs().maxCoeff())
        << "dt " << dt;
  }
  Eigen::VectorXd u = v;
  EXPECT_FALSE(flow.hop(100.0 / w, u, st));
  EXPECT_EQ(u, v);
}

// A stick phase without forcing (x' = v, v' = a: Â nilpotent, Â^3 = 0) has no rate and so no
// ladder; its exponential is the polynomial x0 + v0 t + a t^2 / 2 for any t. expv sums it at once
// (3 products: the third term is exactly zero) instead of ceil(||B|| t) Taylor sub-steps, and the
// values are the polynomial's to round-off (1e-15 relative: a handful of operations).
TEST(AugmentedFlowNilpotent, ForceFreeStickPhaseIsOneExactSumAtAnyLength) {
  stickslip::LinearPart<double> lp;
  lp.A.resize(2, 2);
  lp.A << 0, 1, 0, 0;
  lp.b0.resize(2);
  lp.b0 << 0, -0.3;
  lp.version = 1;
  stickslip::detail::AugmentedFlow<double> flow;
  stickslip::ExactStepperStats st;
  flow.assign(lp, 2, st);
  flow.prepare(0.0, st);  // no rate: no ladder (as the stepper does for such a mode)
  ASSERT_FALSE(flow.has_ladder());
  for (double t : {0.25, 3.0, 1e4}) {
    Eigen::VectorXd u(3);
    u << 0.5, 0.1, 1.0;
    const long before = st.matvecs;
    flow.expv(t, u, st);
    EXPECT_LE(st.matvecs - before, 3) << "t " << t;
    const double x = 0.5 + 0.1 * t - 0.15 * t * t, v = 0.1 - 0.3 * t;
    EXPECT_NEAR(u[0], x, 1e-15 * (0.5 + 0.1 * t + 0.15 * t * t)) << "t " << t;
    EXPECT_NEAR(u[1], v, 1e-15 * (0.1 + 0.3 * t)) << "t " << t;
    EXPECT_EQ(u[2], 1.0);
  }
}

}  // namespace
}  // namespace ode_exact_balancing_test

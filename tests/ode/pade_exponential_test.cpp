// PadeExponential (internal to AugmentedFlow): exp(A) by Padé approximants of degree 3 .. 13 with
// scaling and squaring, against closed forms across every degree's norm range.

#include <stickslip/ode/detail/pade_exponential.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace ode_pade_exponential_test {  // named: the exact-stepper tests share a TU
namespace {

// Higham's theta_m (the 1-norms up to which degree m is used; beyond theta_13 squarings).
constexpr double kTheta[] = {1.495585217958292e-2, 2.539398330063230e-1, 9.504178996162932e-1,
                             2.097847961257068e0, 5.371920351148152e0};

// Norms just below and above each theta_m, and far beyond the last (1, 4 and 10 squarings).
std::vector<double> norms_over_every_degree() {
  std::vector<double> out{1e-6};
  for (double t : kTheta) {
    out.push_back(0.98 * t);
    out.push_back(1.02 * t);
  }
  for (double f : {8.0, 12.0, 1000.0}) out.push_back(f * kTheta[4]);
  return out;
}

// A rotation generator [[0, -phi], [phi, 0]] (1-norm phi): exp = [[cos, -sin], [sin, cos]] of
// phi. Padé's backward error at theta_m is the unit round-off, the solve and the s squarings add
// a few ulps each (the squarings double the error of an orthogonal matrix at most per step:
// 2^s eps relative: phi = 5372 has s = 10, measured 3.4e-13, the others <= 7e-15); asserted
// 50e-15 (1 + 2^s) entrywise.
TEST(PadeExponential, RotationMatchesTheClosedFormAtEveryDegree) {
  stickslip::detail::PadeExponential<double> pade;
  Eigen::MatrixXd a(2, 2), e;
  for (double phi : norms_over_every_degree()) {
    a << 0, -phi, phi, 0;
    pade.compute(a, e);
    Eigen::Matrix2d ref;
    ref << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    int s = 0;
    if (phi > kTheta[4]) std::frexp(phi / kTheta[4], &s);
    const double err = (e - ref).cwiseAbs().maxCoeff();
    std::printf("rotation phi %.4g (%d squarings): error %.2e\n", phi, s, err);
    EXPECT_LT(err, 50e-15 * (1 + std::ldexp(1.0, s))) << "phi " << phi;
  }
}

// A = V diag(lambda) V^-1 with a random V (fixed seed 19, condition ~10) and real lambda of both
// signs, scaled to each norm: exp(A) = V diag(e^lambda) V^-1. Relative to ||exp(A)||, the error
// of a backward-stable method is ~cond(V) (||A|| + 1) eps per squaring level; asserted 1e-12 for
// norms up to 12 theta_13 (measured <= 1.1e-14).
TEST(PadeExponential, DiagonalisableMatrixMatchesItsEigenDecomposition) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 7;
  Eigen::MatrixXd v(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) v(i, j) = (i == j ? 3.0 : 0.0) + u(rng);
  Eigen::VectorXd lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = u(rng);
  const Eigen::MatrixXd vinv = v.inverse();
  const Eigen::MatrixXd a1 = v * lambda.asDiagonal() * vinv;
  const double norm1 = a1.cwiseAbs().colwise().sum().maxCoeff();
  stickslip::detail::PadeExponential<double> pade;
  Eigen::MatrixXd e;
  for (double target : norms_over_every_degree()) {
    if (target > 12 * kTheta[4]) continue;  // e^(12 theta) ~ 1e28 spread: the reference's own error
    const double f = target / norm1;
    pade.compute(f * a1, e);
    const Eigen::MatrixXd ref = v * (f * lambda).array().exp().matrix().asDiagonal() * vinv;
    const double err = (e - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    std::printf("diagonalisable, norm %.4g: relative error %.2e\n", target, err);
    EXPECT_LT(err, 1e-12) << "norm " << target;
  }
}

// A nilpotent Jordan part: t (lambda I + N), N the 4 x 4 shift, exp = e^(lambda t) sum_k (t N)^k
// / k! (k < 4), a defective matrix as the friction model's A_m often is. Relative error asserted
// 1e-13: a few ulps per product, the solve and the one squaring at t = 4 (norm 6.8).
TEST(PadeExponential, JordanBlockMatchesTheClosedForm) {
  const int n = 4;
  Eigen::MatrixXd nil = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) nil(i, i + 1) = 1;
  stickslip::detail::PadeExponential<double> pade;
  Eigen::MatrixXd e;
  for (double t : {1e-3, 0.1, 0.5, 1.5, 4.0}) {
    const double lambda = -0.7;
    const Eigen::MatrixXd a = t * (lambda * Eigen::MatrixXd::Identity(n, n) + nil);
    pade.compute(a, e);
    const Eigen::MatrixXd tn = t * nil;
    const Eigen::MatrixXd ref = std::exp(lambda * t) * (Eigen::MatrixXd::Identity(n, n) + tn +
                                                        tn * tn / 2 + tn * tn * tn / 6);
    const double err = (e - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    EXPECT_LT(err, 1e-13) << "t " << t;
  }
}

}  // namespace
}  // namespace ode_pade_exponential_test

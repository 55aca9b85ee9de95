// Symmetry breaking under a symmetry with a half-period shift (SymmetricBranches::
// half_period_shift): two masses forced in antiphase, whose swap maps a solution x(t) onto
// S x(t + T/2). The symmetric orbits' loss of stability is a parametric (Mathieu) resonance that
// an independent integration of a 2 x 2 Hill equation locates; the asymmetric orbits born there
// are checked against long transients of the test's own integrator.

#include "steady_state/smooth_forced_systems.hpp"

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/pitchfork.hpp>

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace steady_state_pitchfork_half_period_test {  // named: the steady-state tests share one unity TU
namespace {

constexpr double kPi = 3.14159265358979323846;

// Two unit masses q1, q2, forced in antiphase (f cos(w t) on q1, -f cos(w t) on q2). In
// s = (q1 + q2) / 2, a = (q1 - q2) / 2:
//
//     a'' + c a' + wa^2 a = f cos(w t),
//     s'' + c s' + (ws^2 + gamma a^2) s + s^3 = 0.
//
// Swapping the masses (s -> s, a -> -a) maps the forcing onto its negative, the forcing half a
// period later: x(t) is a solution iff S x(t + T/2) is. The symmetric orbit has s = 0 and the
// linear response a = Re(F e^{i w t}), F = f / (wa^2 - w^2 + i c w), which satisfies
// a(t + T/2) = -a(t). A perturbation of s obeys the Hill equation
// s'' + c s' + (ws^2 + gamma a(t)^2) s = 0, whose stiffness is modulated at 2 w: near w ~ ws its
// principal (Mathieu) instability grows an s that repeats with period T and changes sign every
// half period (odd harmonics): S v(t0 + T/2) = -v(t0), the half-period map's eigenvalue -1, a
// symmetry-breaking pitchfork. The cubic term saturates the asymmetric orbits born there.
class AntiphasePair : public steady_state_test::WithoutEvents<Eigen::Matrix<double, 4, 1>> {
 public:
  using Scalar = double;
  using State = Eigen::Matrix<double, 4, 1>;  // (q1, q2, q1', q2')
  using Mode = int;
  double c = 0.02, f = 0.625, wa = 1.5, ws = 1.0, gamma = 0.8, omega = 1;

  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    const double s = (x[0] + x[1]) / 2, a = (x[0] - x[1]) / 2, sd = (x[2] + x[3]) / 2, ad = (x[2] - x[3]) / 2;
    const double add = f * std::cos(omega * t) - c * ad - wa * wa * a;
    const double sdd = -c * sd - (ws * ws + gamma * a * a) * s - s * s * s;
    dxdt << x[2], x[3], sdd + add, sdd - add;
  }
  std::complex<double> amplitude(double w) const { return f / std::complex<double>(wa * wa - w * w, c * w); }
  // The symmetric orbit's state at t = 0 (s = 0).
  State symmetric_start(double w) const {
    const std::complex<double> F = amplitude(w);
    const double a0 = F.real(), ad0 = -w * F.imag();
    return State(a0, -a0, ad0, -ad0);
  }
};

Eigen::MatrixXd swap_masses() {
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(4, 4);
  S(0, 1) = S(1, 0) = S(2, 3) = S(3, 2) = 1;
  return S;
}

// Classical fourth-order Runge-Kutta with a fixed step, the test's own integrator (not the
// library's): y' = g(t, y) over [t0, t1] in n steps.
template <class Y, class G>
Y rk4(G&& g, double t0, double t1, Y y, int n) {
  const double h = (t1 - t0) / n;
  for (int k = 0; k < n; ++k) {
    const double t = t0 + k * h;
    const Y k1 = g(t, y), k2 = g(t + h / 2, Y(y + h / 2 * k1)), k3 = g(t + h / 2, Y(y + h / 2 * k2)),
            k4 = g(t + h, Y(y + h * k3));
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return y;
}

// det(Phi_s(T/2) + I) of the Hill equation on the closed-form symmetric orbit: zero where the
// half-period map's eigenvalue on the s-block is -1. The a-block's eigenvalues,
// -exp(lambda T/2) with Re lambda = -c/2, stay off +-1.
double hill_det(const AntiphasePair& sys, double w) {
  const std::complex<double> F = sys.amplitude(w);
  const auto g = [&](double t, const Eigen::Vector4d& y) {
    const double a = (F * std::exp(std::complex<double>(0, w * t))).real();
    const double k = sys.ws * sys.ws + sys.gamma * a * a;
    // Two columns of the 2 x 2 fundamental matrix, (s, s') each.
    return Eigen::Vector4d(y[1], -sys.c * y[1] - k * y[0], y[3], -sys.c * y[3] - k * y[2]);
  };
  // 4000 steps over T/2 ~ 3: h ~ 7.5e-4, RK4's error ~ h^4 ~ 1e-12 on O(1) solutions.
  const Eigen::Vector4d y = rk4(g, 0.0, kPi / w, Eigen::Vector4d(1, 0, 0, 1), 4000);
  Eigen::Matrix2d Phi;
  Phi << y[0], y[2], y[1], y[3];
  return (Phi + Eigen::Matrix2d::Identity()).determinant();
}

// The tongue's edges: the sign changes of hill_det on a grid, refined by bisection.
std::vector<double> hill_edges(const AntiphasePair& sys, double lo, double hi) {
  std::vector<double> edges;
  const int n = 200;
  double w0 = lo, g0 = hill_det(sys, lo);
  for (int k = 1; k <= n; ++k) {
    const double w1 = lo + (hi - lo) * k / n, g1 = hill_det(sys, w1);
    if (g0 * g1 <= 0) {
      double a = w0, b = w1, ga = g0;
      for (int it = 0; it < 60; ++it) {
        const double m = (a + b) / 2, gm = hill_det(sys, m);
        if ((gm <= 0) == (ga <= 0)) {
          a = m;
          ga = gm;
        } else {
          b = m;
        }
      }
      edges.push_back((a + b) / 2);
    }
    w0 = w1;
    g0 = g1;
  }
  return edges;
}

const auto set_w = [](AntiphasePair& s, double w) { s.omega = w; };
const auto period_of = [](double w) { return 2 * kPi / w; };

TEST(SteadyStatePitchforkHalfPeriod, AntiphasePairBreaksSymmetryAtTheHillEquationsEdgesAndItsAsymmetricOrbitsAreTheTransients) {
  AntiphasePair sys;
  const std::vector<double> edges = hill_edges(sys, 0.95, 1.15);
  ASSERT_EQ(edges.size(), 2u) << "the Hill equation's principal tongue lies inside [0.95, 1.15]";
  std::printf("Hill equation's tongue: w = %.10f .. %.10f\n", edges[0], edges[1]);

  stickslip::ShootingOptions<double> so;
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = 0.95;
  co.parameter_max = 1.15;
  co.initial_step = 0.01;
  co.max_step = 0.02;
  co.max_points = 200;
  const double w0 = 0.96;
  sys.omega = w0;
  stickslip::Continuation<AntiphasePair> cont(sys, set_w, period_of, so, co);
  const auto branch = cont.run(0, 0.0, sys.symmetric_start(w0), w0);
  ASSERT_TRUE(branch.completed()) << branch.message;
  stickslip::SymmetricBranches<AntiphasePair> sb(sys, set_w, period_of, swap_masses(), so, co);
  // Without the shift the symmetric orbits are not S-symmetric (a != 0): no classification.
  ASSERT_FALSE(branch.bifurcations.empty());
  {
    const auto& b = branch.bifurcations.front();
    const auto c = sb.classify(branch.points[b.before], branch.points[b.before + 1]);
    EXPECT_FALSE(c.ok);
    EXPECT_NE(c.message.find("not symmetric"), std::string::npos) << c.message;
    EXPECT_THROW(sb.half_period_multipliers(branch.points[b.before]), std::invalid_argument);
  }
  // An affine symmetry about a centre c: x -> c + S (x - c).
  {
    stickslip::SymmetricBranches<AntiphasePair> sc(sys, set_w, period_of, swap_masses(), so, co);
    EXPECT_THROW(sc.symmetry_centre(AntiphasePair::State(0, std::nan(""), 0, 0)), std::invalid_argument);
    sc.symmetry_centre(AntiphasePair::State(1, 3, 0, 0));
    const AntiphasePair::State y = sc.mirror(AntiphasePair::State(2, 5, 7, 11));
    EXPECT_EQ(y, AntiphasePair::State(1 + (5 - 3), 3 + (2 - 1), 11, 7));
  }
  sb.half_period_shift(true);
  EXPECT_THROW(sb.multipliers_by_symmetry(branch.points[0].orbit.monodromy, 4), std::invalid_argument);
  std::vector<stickslip::SymmetryBreakingPoint<AntiphasePair>> found;
  for (const auto& b : branch.bifurcations) {
    const auto c = sb.locate(branch.points[b.before], branch.points[b.before + 1], 1e-7);
    ASSERT_TRUE(c.ok) << c.message;
    std::printf("%s at w = %.10f, mu = %.12f\n", stickslip::to_string(c.kind), c.parameter, c.multiplier);
    found.push_back(c);
  }
  ASSERT_EQ(found.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(found[k].kind, stickslip::BifurcationKind::Pitchfork);
    EXPECT_TRUE(found[k].located);
    // 1e-7: the multiplier is 1 to 1e-7 (locate's tolerance); mu = h^2 moves with w at
    // |dmu/dw| ~ T |d lambda/dw| ~ 6 x (tongue slope ~ 1..10): w to ~1e-8; the monodromy of the
    // runs (rtol 1e-10 by default) adds ~1e-9, the reference's RK4 ~1e-12.
    EXPECT_NEAR(found[k].parameter, edges[k], 1e-7);
    // The Floquet vector is along s: q1 = q2, q1' = q2'.
    EXPECT_NEAR(found[k].eigenvector[0] - found[k].eigenvector[1], 0, 1e-8);
    EXPECT_NEAR(found[k].eigenvector[2] - found[k].eigenvector[3], 0, 1e-8);
    // The symmetric orbit's half-period map there has an eigenvalue -1.
    stickslip::ContinuationPoint<AntiphasePair> at;
    at.parameter = found[k].parameter;
    at.orbit = found[k].orbit;
    const auto hm = sb.half_period_multipliers(at);
    ASSERT_TRUE(hm.ok) << hm.message;
    double nearest = 1e9;
    for (const auto& h : hm.eigenvalues) nearest = std::min(nearest, std::abs(h + 1.0));
    EXPECT_LT(nearest, 1e-6);
    EXPECT_LT(hm.asymmetry, 1e-8);
  }
  std::printf("located - Hill equation: %.2e, %.2e\n", found[0].parameter - edges[0], found[1].parameter - edges[1]);

  // The asymmetric branch from the lower edge into the tongue.
  stickslip::ContinuationOptions<double> ca = co;
  ca.initial_step = 0.002;
  ca.max_step = 0.01;
  ca.max_points = 60;
  stickslip::SymmetricBranches<AntiphasePair> sa(sys, set_w, period_of, swap_masses(), so, ca);
  sa.half_period_shift(true);
  const auto asym = sa.asymmetric_branch(found[0], 0.02);
  std::printf("asymmetric branch: %zu points, %s\n", asym.points.size(), stickslip::to_string(asym.status));
  ASSERT_GE(asym.points.size(), 10u) << stickslip::to_string(asym.status) << ": " << asym.message;
  // The point nearest the tongue's middle, where s is large and the transient settles quickly.
  const double w_mid = (edges[0] + edges[1]) / 2;
  const stickslip::ContinuationPoint<AntiphasePair>* mid = nullptr;
  for (const auto& pt : asym.points) {
    const auto& x = pt.orbit.x0;
    // a does not feel s: the closed-form a to the Newton tolerance (1e-9, amplified by
    // 1 / |1 - mu_a| ~ 1 for the a-block's damped multipliers).
    const AntiphasePair::State s = sys.symmetric_start(pt.parameter);
    EXPECT_NEAR((x[0] - x[1]) / 2, s[0], 1e-8) << "w = " << pt.parameter;
    EXPECT_NEAR((x[2] - x[3]) / 2, s[2], 1e-8) << "w = " << pt.parameter;
    if (!mid || std::abs(pt.parameter - w_mid) < std::abs(mid->parameter - w_mid)) mid = &pt;
  }
  ASSERT_NE(mid, nullptr);
  const double w = mid->parameter;
  const double s0 = (mid->orbit.x0[0] + mid->orbit.x0[1]) / 2, sd0 = (mid->orbit.x0[2] + mid->orbit.x0[3]) / 2;
  std::printf("asymmetric orbit at w = %.6f: s0 = %.6e, s0' = %.6e\n", w, s0, sd0);
  ASSERT_GT(std::hypot(s0, sd0), 1e-2) << "the point lies inside the tongue, away from the symmetric orbit";
  // A long transient from the symmetric orbit with s perturbed, by the test's own RK4: after
  // 400 periods (the asymmetric orbits attract at a rate of order c / 2 = 0.01 per unit time:
  // e^-25) it lies on the asymmetric orbit or on its image (s of the other sign).
  AntiphasePair at = sys;
  at.omega = w;
  const auto g = [&](double t, const AntiphasePair::State& x) {
    AntiphasePair::State d;
    at.rhs(0, t, x, d);
    return d;
  };
  AntiphasePair::State x = sys.symmetric_start(w);
  x[0] += 1e-3;
  x[1] += 1e-3;
  const double T = 2 * kPi / w;
  x = rk4(g, 0.0, 400 * T, x, 400 * 400);  // 400 steps per period: RK4's error ~1e-9 per period
  const double st = (x[0] + x[1]) / 2, sdt = (x[2] + x[3]) / 2;
  const double sign = st * s0 >= 0 ? 1 : -1;
  // 1e-6: the transient's RK4 error (~1e-9 per period, not accumulating on an attracting
  // orbit), its remaining decay (e^-25 of 1e-1) and the orbit's Newton tolerance (1e-9).
  EXPECT_NEAR(st, sign * s0, 1e-6);
  EXPECT_NEAR(sdt, sign * sd0, 1e-6);
  EXPECT_TRUE(mid->orbit.floquet.stable);

  // The image S x(t0 + T/2): the same orbit a half period on, s of the other sign at t0.
  const auto im = sa.image(*mid);
  ASSERT_TRUE(im.orbit.ok()) << im.orbit.message;
  EXPECT_NEAR((im.orbit.x0[0] + im.orbit.x0[1]) / 2, -s0, 1e-7);
  EXPECT_NEAR((im.orbit.x0[0] - im.orbit.x0[1]) / 2, (mid->orbit.x0[0] - mid->orbit.x0[1]) / 2, 1e-7);
}

}  // namespace
}  // namespace steady_state_pitchfork_half_period_test

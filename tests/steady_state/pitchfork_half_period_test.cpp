// Symmetry breaking under a symmetry with a half-period shift (SymmetricBranches::
// half_period_shift): two masses forced in antiphase, whose swap maps a solution x(t) onto
// S x(t + T/2). The symmetric orbits' loss of stability is a parametric (Mathieu) resonance that
// an independent integration of a 2 x 2 Hill equation locates; the asymmetric orbits born there
// are checked against long transients of the test's own integrator.

#include "steady_state/smooth_forced_systems.hpp"

#include <stickslip/contact.hpp>
#include <stickslip/ode.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/half_period_symmetry.hpp>
#include <stickslip/steady_state/period_run.hpp>
#include <stickslip/steady_state/shooting.hpp>
#include <stickslip/steady_state/pitchfork.hpp>

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>
#include <utility>
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

// Phi_s(T/2), the Hill equation's fundamental matrix in (s, s') over half a period on the
// closed-form symmetric orbit (its coefficient a^2 has period T/2): the s-block of the
// half-period map (the swap leaves s alone).
Eigen::Matrix2d hill_half_map(const AntiphasePair& sys, double w) {
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
  return Phi;
}

// det(Phi_s(T/2) + I) of the Hill equation on the closed-form symmetric orbit: zero where the
// half-period map's eigenvalue on the s-block is -1. The a-block's eigenvalues,
// -exp(lambda T/2) with Re lambda = -c/2, stay off +-1.
double hill_det(const AntiphasePair& sys, double w) {
  return (hill_half_map(sys, w) + Eigen::Matrix2d::Identity()).determinant();
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

stickslip::HalfPeriodSymmetry<AntiphasePair> swap_in_antiphase() {
  stickslip::HalfPeriodSymmetry<AntiphasePair> sym;
  sym.S = swap_masses();
  return sym;
}

// Continuation across the tongue, w in [0.95, 1.15].
stickslip::ContinuationOptions<double> across_the_tongue() {
  stickslip::ContinuationOptions<double> co;
  co.parameter_min = 0.95;
  co.parameter_max = 1.15;
  co.initial_step = 0.01;
  co.max_step = 0.02;
  co.max_points = 200;
  return co;
}

// SymmetricBranches under the swap with a half-period shift, its asymmetric branches started at
// step 0.002 (up to max_step, max_points points).
stickslip::SymmetricBranches<AntiphasePair> half_shifted_branches(AntiphasePair& sys, double max_step, int max_points) {
  stickslip::ContinuationOptions<double> ca = across_the_tongue();
  ca.initial_step = 0.002;
  ca.max_step = max_step;
  ca.max_points = max_points;
  stickslip::SymmetricBranches<AntiphasePair> sa(sys, set_w, period_of, swap_masses(), {}, ca);
  sa.half_period_shift(true);
  return sa;
}

// The symmetric branch from w = 0.96 up, shot on the full period or (half) on the half period.
stickslip::ContinuationResult<AntiphasePair> symmetric_branch(AntiphasePair& sys, bool half) {
  const double w0 = 0.96;
  sys.omega = w0;
  stickslip::Continuation<AntiphasePair> cont(sys, set_w, period_of, {}, across_the_tongue());
  if (half) cont.half_period_symmetry(swap_in_antiphase());
  return cont.run(0, 0.0, sys.symmetric_start(w0), w0);
}

TEST(SteadyStatePitchforkHalfPeriod, AntiphasePairBreaksSymmetryAtTheHillEquationsEdgesAndItsAsymmetricOrbitsAreTheTransients) {
  AntiphasePair sys;
  const std::vector<double> edges = hill_edges(sys, 0.95, 1.15);
  ASSERT_EQ(edges.size(), 2u) << "the Hill equation's principal tongue lies inside [0.95, 1.15]";
  std::printf("Hill equation's tongue: w = %.10f .. %.10f\n", edges[0], edges[1]);

  const stickslip::ShootingOptions<double> so;
  const stickslip::ContinuationOptions<double> co = across_the_tongue();
  const auto branch = symmetric_branch(sys, false);
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
  stickslip::SymmetricBranches<AntiphasePair> sa = half_shifted_branches(sys, 0.01, 60);
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

// max |c + S (x(t0 + T/2) - c) - x0| and max |x(t0 + T) - x0| of runs of the library's
// integrator from x0 (no Newton: the orbit's end conditions checked directly).
std::pair<double, double> symmetry_and_period_defects(AntiphasePair& sys, double w, const AntiphasePair::State& x0) {
  sys.omega = w;
  const stickslip::ShootingOptions<double> so;
  const double T = 2 * kPi / w;
  const auto half = stickslip::run_period(sys, 0, 0.0, x0, T / 2, so, false);
  const auto full = stickslip::run_period(sys, 0, 0.0, x0, T, so, false);
  EXPECT_TRUE(half.ok() && full.ok());
  return {(swap_masses() * half.x_end - x0).cwiseAbs().maxCoeff(), (full.x_end - x0).cwiseAbs().maxCoeff()};
}

TEST(SteadyStatePitchforkHalfPeriod, ShootingOnTheHalfPeriodConvergesToTheUnstableSymmetricOrbitWithTheHillEquationsMultipliers) {
  AntiphasePair sys;
  const std::vector<double> edges = hill_edges(sys, 0.95, 1.15);
  ASSERT_EQ(edges.size(), 2u);
  const double w = (edges[0] + edges[1]) / 2;  // inside the tongue: the symmetric orbit is unstable
  sys.omega = w;
  stickslip::Shooting<AntiphasePair> shooting(sys);
  shooting.half_period_symmetry(swap_in_antiphase());
  ASSERT_NE(shooting.half_period_symmetry(), nullptr);
  AntiphasePair::State guess = sys.symmetric_start(w);
  guess[0] += 0.05;  // s(0) = 0.05, s'(0) = -0.03: off the symmetric orbit
  guess[1] += 0.05;
  guess[2] -= 0.03;
  guess[3] -= 0.03;
  const auto orbit = shooting.forced(0, 0.0, guess, 2 * kPi / w);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  const AntiphasePair::State ref = sys.symmetric_start(w);
  std::printf("half-period shooting at w = %.6f: %d runs, s0 = %.2e, s0' = %.2e, |a0 - closed form| = %.2e\n", w,
              orbit.iterations, (orbit.x0[0] + orbit.x0[1]) / 2, (orbit.x0[2] + orbit.x0[3]) / 2,
              std::abs((orbit.x0[0] - orbit.x0[1]) / 2 - ref[0]));
  // 1e-8: Newton's tolerance is 1e-9 max(1, |x0|) on the residual; H - I is regular here
  // (|1 / (h + 1)| of order 1), so the state's error is of the same order.
  EXPECT_NEAR((orbit.x0[0] + orbit.x0[1]) / 2, 0, 1e-8);
  EXPECT_NEAR((orbit.x0[2] + orbit.x0[3]) / 2, 0, 1e-8);
  EXPECT_NEAR((orbit.x0[0] - orbit.x0[1]) / 2, ref[0], 1e-8);
  EXPECT_NEAR((orbit.x0[2] - orbit.x0[3]) / 2, ref[2], 1e-8);
  // The monodromy is the full period's: that of an independent full-period variational run
  // (1e-7: two integrations at rtol 1e-10 of a map with entries of order 1..10).
  ASSERT_EQ(orbit.half_period_map.rows(), 4);
  const auto full = stickslip::run_period(sys, 0, 0.0, orbit.x0, 2 * kPi / w, shooting.options(), true);
  ASSERT_TRUE(full.ok());
  EXPECT_LT((orbit.monodromy - full.monodromy).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((orbit.monodromy - orbit.half_period_map * orbit.half_period_map).cwiseAbs().maxCoeff(), 1e-12);
  // The multipliers: the s-block's are the squares of the Hill equation's half-period
  // eigenvalues (test's RK4), the a-block's exp(lambda T) with lambda = -c/2 +- i sqrt(wa^2 - c^2/4)
  // (closed form). 1e-7: the RK4 reference ~1e-12, the variational run ~1e-9 on entries ~10.
  const Eigen::Vector2cd hs = Eigen::EigenSolver<Eigen::Matrix2d>(hill_half_map(sys, w)).eigenvalues();
  const double T = 2 * kPi / w;
  const std::complex<double> la(-sys.c / 2, std::sqrt(sys.wa * sys.wa - sys.c * sys.c / 4));
  const std::complex<double> refs[4] = {hs[0] * hs[0], hs[1] * hs[1], std::exp(la * T), std::exp(std::conj(la) * T)};
  ASSERT_EQ(orbit.floquet.multipliers.size(), 4);
  for (const auto& r : refs) {
    double nearest = 1e9;
    for (Eigen::Index i = 0; i < 4; ++i) nearest = std::min(nearest, std::abs(orbit.floquet.multipliers[i] - r));
    EXPECT_LT(nearest, 1e-7) << "reference multiplier " << r;
  }
  EXPECT_FALSE(orbit.floquet.stable);
  std::printf("Hill half-period eigenvalues %.8f, %.8f; largest multiplier %.8f\n", hs[0].real(), hs[1].real(),
              orbit.floquet.multipliers.cwiseAbs().maxCoeff());
  shooting.clear_half_period_symmetry();
  EXPECT_EQ(shooting.half_period_symmetry(), nullptr);
}

TEST(SteadyStatePitchforkHalfPeriod, ContinuationOnTheHalfPeriodStaysSymmetricAndFlagsThePitchforkAtTheHillEquationsEdge) {
  AntiphasePair sys;
  const std::vector<double> edges = hill_edges(sys, 0.95, 1.15);
  ASSERT_EQ(edges.size(), 2u);
  const stickslip::ShootingOptions<double> so;
  const stickslip::ContinuationOptions<double> co = across_the_tongue();
  const auto branch = symmetric_branch(sys, true);
  ASSERT_TRUE(branch.completed()) << branch.message;
  ASSERT_GE(branch.points.size(), 5u);
  double worst_half = 0, worst_full = 0, worst_s = 0;
  for (const auto& pt : branch.points) {
    const auto d = symmetry_and_period_defects(sys, pt.parameter, pt.orbit.x0);
    worst_half = std::max(worst_half, d.first);
    worst_full = std::max(worst_full, d.second);
    worst_s = std::max({worst_s, std::abs(pt.orbit.x0[0] + pt.orbit.x0[1]), std::abs(pt.orbit.x0[2] + pt.orbit.x0[3])});
    ASSERT_EQ(pt.orbit.half_period_map.rows(), 4);
  }
  std::printf("symmetric branch: %zu points; max |S x(T/2) - x0| = %.2e, |x(T) - x0| = %.2e, |s| = %.2e\n",
              branch.points.size(), worst_half, worst_full, worst_s);
  // 1e-8: Newton's tolerance 1e-9 max(1, |x0|) (|x0| ~ 1..2) on the half-period condition; the
  // full period's defect is (I + H) times it, |H| of order 1..3 (a multiplier up to ~2 inside the tongue).
  EXPECT_LT(worst_half, 1e-8);
  EXPECT_LT(worst_full, 1e-8);
  EXPECT_LT(worst_s, 1e-8);
  for (const auto& b : branch.bifurcations)
    std::printf("flagged %s between w = %.6f and %.6f\n", stickslip::to_string(b.kind),
                branch.points[b.before].parameter, branch.points[b.before + 1].parameter);
  // Each edge is flagged as a pitchfork between two points that bracket it.
  stickslip::SymmetricBranches<AntiphasePair> sb(sys, set_w, period_of, swap_masses(), so, co);
  sb.half_period_shift(true);
  for (const double edge : edges) {
    const stickslip::BifurcationPoint<double>* hit = nullptr;
    for (const auto& b : branch.bifurcations) {
      const double pa = branch.points[b.before].parameter, pb = branch.points[b.before + 1].parameter;
      if (std::min(pa, pb) <= edge && edge <= std::max(pa, pb)) hit = &b;
    }
    ASSERT_NE(hit, nullptr) << "no crossing flagged around the Hill equation's edge w = " << edge;
    EXPECT_EQ(hit->kind, stickslip::BifurcationKind::Pitchfork);
    const auto& pa = branch.points[hit->before];
    const auto& pb = branch.points[hit->before + 1];
    const auto c = sb.classify(pa, pb);
    ASSERT_TRUE(c.ok) << c.message;
    EXPECT_EQ(c.kind, stickslip::BifurcationKind::Pitchfork);
    // Linear interpolation of det(H + I) between the points: inside their bracket.
    EXPECT_LE(std::abs(c.parameter - edge), std::abs(pb.parameter - pa.parameter));
    const auto l = sb.locate(pa, pb, 1e-7);
    ASSERT_TRUE(l.ok) << l.message;
    EXPECT_EQ(l.kind, stickslip::BifurcationKind::Pitchfork);
    // 1e-7: as in the test above (locate's multiplier tolerance 1e-7, |dmu/dw| of order 10).
    EXPECT_NEAR(l.parameter, edge, 1e-7);
    std::printf("classified at w = %.8f, located at w = %.10f (Hill: %.10f)\n", c.parameter, l.parameter, edge);
    if (edge != edges[0]) continue;
    // The asymmetric branch born at the lower edge: its first points have s != 0.
    const auto asym = half_shifted_branches(sys, 0.005, 4).asymmetric_branch(l, 0.02);
    ASSERT_GE(asym.points.size(), 3u) << asym.message;
    for (const auto& pt : asym.points) {
      const double s0 = (pt.orbit.x0[0] + pt.orbit.x0[1]) / 2, sd0 = (pt.orbit.x0[2] + pt.orbit.x0[3]) / 2;
      // 1e-3: the first orbit lies at arclength 0.02 from the pitchfork along the s-direction
      // Floquet vector, and s grows further away from the edge (|s| ~ sqrt(w - edge)): far above
      // the symmetric orbit's s (<= 1e-8).
      EXPECT_GT(std::hypot(s0, sd0), 1e-3) << "w = " << pt.parameter;
    }
  }
}

TEST(SteadyStatePitchforkHalfPeriod, HalfPeriodSymmetryRejectsBadInputNamingTheParameter) {
  AntiphasePair sys;
  stickslip::Shooting<AntiphasePair> shooting(sys);
  const auto message = [&](const stickslip::HalfPeriodSymmetry<AntiphasePair>& sym) {
    try {
      shooting.half_period_symmetry(sym);  // checks S and the centre
      shooting.forced(0, 0.0, sys.symmetric_start(1.0), 2 * kPi);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no throw");
  };
  auto sym = swap_in_antiphase();
  sym.S = Eigen::MatrixXd::Identity(3, 3);
  EXPECT_NE(message(sym).find("S must have the state size"), std::string::npos) << message(sym);
  sym.S = 2 * Eigen::MatrixXd::Identity(4, 4);
  EXPECT_NE(message(sym).find("S must be an involution"), std::string::npos) << message(sym);
  sym.S = Eigen::MatrixXd::Identity(4, 3);
  EXPECT_NE(message(sym).find("S must be a non-empty square matrix"), std::string::npos) << message(sym);
  sym = swap_in_antiphase();
  sym.centre[1] = std::nan("");
  EXPECT_NE(message(sym).find("centre must be finite"), std::string::npos) << message(sym);
  // A dynamic-size state: a centre of the wrong size.
  struct DynamicTypes {
    using Scalar = double;
    using State = Eigen::VectorXd;
    using Mode = int;
  };
  stickslip::HalfPeriodSymmetry<DynamicTypes> dyn;
  dyn.S = swap_masses();
  EXPECT_NO_THROW(dyn.validate("test", 4));
  dyn.centre = Eigen::VectorXd::Zero(3);
  try {
    dyn.validate("test", 4);
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("centre must be empty or have the state size"), std::string::npos) << e.what();
  }
  // The autonomous problem with a half-period symmetry is not supported.
  shooting.half_period_symmetry(swap_in_antiphase());
  EXPECT_THROW(shooting.autonomous(0, sys.symmetric_start(1.0), 2 * kPi), std::invalid_argument);
  // The affine map about a centre: c + S (x - c).
  sym = swap_in_antiphase();
  sym.centre = AntiphasePair::State(1, 3, 0, 0);
  EXPECT_EQ(sym.mirror(AntiphasePair::State(2, 5, 7, 11)), AntiphasePair::State(1 + (5 - 3), 3 + (2 - 1), 11, 7));
}

}  // namespace
}  // namespace steady_state_pitchfork_half_period_test

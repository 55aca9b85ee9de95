// Den Hartog (1931): steady state of a harmonically forced oscillator with Coulomb friction and
// continuous sliding (two stops per period, no stick), against CoulombContact + HybridStepper.
//
// Reference: J. P. Den Hartog, "Forced vibrations with combined Coulomb and viscous friction",
// Trans. ASME APM-53-9 (1931) 107-115; the Coulomb-only result is reproduced e.g. in S. S. Rao,
// Mechanical Vibrations, Sec. "Response under Coulomb damping". Derived here independently from
// the piecewise-linear ODE (test comment below), not from the code under test.

#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace contact_coulomb_contact_den_hartog_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;
constexpr double kPi = 3.14159265358979323846;

// m x'' + k x = F0 cos(w t) - mu_k N sgn(x'). Symmetric orbit x(t + T/2) = -x(t) with one
// positive half-period [t1, t1 + pi/w] where x' >= 0, x(t1) = -X, x'(t1) = 0, x(t1 + pi/w) = X.
// With tau = t - t1, theta = w t1, beta = w/wn, P = F0/(k (1 - beta^2)), a = mu_k N / k:
//   x(tau) = C cos(wn tau) + D sin(wn tau) + P cos(w tau + theta) - a
// x'(0) = 0 gives D = P beta sin(theta); x(0) = -X gives C = -X - P cos(theta) + a. The two end
// conditions x(pi/w) = X, x'(pi/w) = 0 reduce (with c = cos(pi/beta), s = sin(pi/beta),
// (1+c)^2 + s^2 = 2(1+c)) to
//   sin(theta) = (a / P) U,   X = -P cos(theta),   U = s / (beta (1 + c)) = tan(pi/(2 beta))/beta,
// i.e. X^2 = P^2 - a^2 U^2: Den Hartog's X/(F0/k) = sqrt(1/(1-beta^2)^2 - (mu_k N/F0)^2 U^2).
// The displacement peak (x = X) lags the force peak by phi = theta + pi (mod 2 pi).
struct DenHartogOrbit {
  double m, k, F0, w, a, muS_N;
  double wn, beta, P, X, theta, C, D, t1, T;
  bool valid = false;

  DenHartogOrbit(double mass, double stiffness, double force, double omega, double mu_k_N,
                 double mu_s_N)
      : m(mass), k(stiffness), F0(force), w(omega), a(mu_k_N / stiffness), muS_N(mu_s_N) {
    wn = std::sqrt(k / m);
    beta = w / wn;
    P = F0 / (k * (1 - beta * beta));
    const double U = std::tan(kPi / (2 * beta)) / beta;
    const double sin_theta = a * U / P;
    if (std::abs(sin_theta) >= 1) return;
    const double cos_theta = (P > 0 ? -1.0 : 1.0) * std::sqrt(1 - sin_theta * sin_theta);
    theta = std::atan2(sin_theta, cos_theta);
    X = -P * cos_theta;
    C = -X - P * cos_theta + a;
    D = P * beta * sin_theta;
    T = 2 * kPi / w;
    t1 = std::fmod(theta / w + 2 * T, T);  // w tau + theta = w t
    valid = check();
  }
  double x_half(double tau) const {
    return C * std::cos(wn * tau) + D * std::sin(wn * tau) + P * std::cos(w * tau + theta) - a;
  }
  double v_half(double tau) const {
    return wn * (-C * std::sin(wn * tau) + D * std::cos(wn * tau)) -
           P * w * std::sin(w * tau + theta);
  }
  // Position and velocity at time t (any t), by the half-period symmetry.
  void state(double t, double& x, double& v) const {
    double tau = std::fmod(t - t1, T);
    if (tau < 0) tau += T;
    const double sign = tau < T / 2 ? 1.0 : -1.0;
    if (tau >= T / 2) tau -= T / 2;
    x = sign * x_half(tau);
    v = sign * v_half(tau);
  }
  double phase_lag() const { return std::fmod(theta + kPi + 4 * kPi, 2 * kPi); }

  // The orbit is the physical one only if x' > 0 inside the half period (no extra stop) and the
  // body cannot stick at the reversal: |k X - F(t1 + T/2)| > mu_s N.
  bool check() const {
    const int n = 4000;
    for (int i = 1; i < n; ++i)
      if (!(v_half(kPi / w * i / n) > 0)) return false;
    const double f_required_at_peak = k * X - F0 * std::cos(w * (t1 + T / 2));
    return X > 0 && std::abs(f_required_at_peak) > muS_N;
  }
};

struct Case {
  double beta;
  double friction_ratio;  // mu_k N / F0
  double mu_s_over_mu_k;
};

class DenHartog : public ::testing::TestWithParam<Case> {};

// Start ON the closed-form orbit (mid positive half-period): with Coulomb friction alone the
// free-vibration part of a transient is not damped exponentially, so we do not wait for it.
// Tolerance: the issue asks 1e-4 relative. DP54 at rtol = 1e-11 with event location to 1e-12 s
// gives measured errors below 1e-9 on every case, so we assert 1e-6: a margin of 1000 over the
// integration error, and tight enough to catch any wrong force sign, reversal rule, missed event
// or velocity projection error (each changes X or the phase at order mu_k N / F0 or v_tol / v).
TEST_P(DenHartog, AmplitudeAndPhaseOfContinuousSlidingMatchTheClosedForm) {
  constexpr double kTol = 1e-6;
  const Case c = GetParam();
  const double m = 2.0, k = 50.0, F0 = 10.0, muk = 0.25;
  const double wn = std::sqrt(k / m), w = c.beta * wn;
  const double N = c.friction_ratio * F0 / muk;
  const DenHartogOrbit ref(m, k, F0, w, muk * N, c.mu_s_over_mu_k * muk * N);
  ASSERT_TRUE(ref.valid) << "parameters outside continuous sliding: beta " << c.beta;

  SingleDofParameters p;
  p.mass = m;
  p.stiffness = k;
  p.force_amplitude = F0;
  p.force_frequency = w;
  p.normal_force = N;
  using Law = stickslip::CoulombLaw<double>;
  SingleDofOscillator<Law> sys(p, stickslip::CoulombContact<Law>(Law(c.mu_s_over_mu_k * muk, muk)));

  const double t0 = ref.t1 + ref.T / 4;
  Eigen::Vector4d x0;
  ref.state(t0, x0[0], x0[1]);
  x0[2] = x0[3] = 0;
  ASSERT_GT(x0[1], 0);

  stickslip::StepperOptions<double> opt;
  opt.rtol = 1e-11;
  opt.atol = 1e-13;
  opt.output_interval = ref.T / 64;
  struct Log : EventLog {
    const DenHartogOrbit* ref;
    double max_waveform_error = 0;
    bool on_sample(double t, const Eigen::Vector4d& x, const S&) {
      double xr, vr;
      ref->state(t, xr, vr);
      max_waveform_error = std::max(max_waveform_error, std::abs(x[0] - xr) / ref->X);
      return true;
    }
  } log;
  log.ref = &ref;
  const int periods = 12;
  stickslip::HybridStepper<SingleDofOscillator<Law>, stickslip::DormandPrince54> stepper(sys, opt);
  const auto r = stepper.integrate(S::SlipPositive, t0, x0, t0 + periods * ref.T, log);
  ASSERT_TRUE(r.ok()) << r.message;

  ASSERT_EQ(log.events.size(), static_cast<std::size_t>(2 * periods));
  for (const auto& e : log.events) {
    ASSERT_NE(e.to, S::Stick) << "stuck at t = " << e.t;
    const bool peak = e.from == S::SlipPositive;  // x' fell through 0 at x = +X
    EXPECT_EQ(e.to, peak ? S::SlipNegative : S::SlipPositive);
    EXPECT_NEAR(std::abs(e.x[0]) / ref.X, 1.0, kTol) << "t = " << e.t;
    EXPECT_GT(peak ? e.x[0] : -e.x[0], 0.0);
    // Phase lag of the displacement peak behind the force peak (the trough is half a period on).
    const double phase = std::fmod(w * (peak ? e.t : e.t - ref.T / 2) + 100 * kPi, 2 * kPi);
    double diff = phase - ref.phase_lag();
    diff -= 2 * kPi * std::round(diff / (2 * kPi));
    EXPECT_LE(std::abs(diff), kTol * ref.phase_lag()) << "t = " << e.t << " phase " << phase;
  }
  EXPECT_LT(log.max_waveform_error, kTol);
}

// beta below and above resonance, friction ratios from light to heavy; mu_s = mu_k and
// mu_s > mu_k (continuous sliding never tests mu_s beyond the no-stick check at the reversals).
INSTANTIATE_TEST_SUITE_P(FrequencyAndFrictionRatios, DenHartog,
                         ::testing::Values(Case{0.7, 0.1, 1.0}, Case{0.7, 0.3, 1.2},
                                           Case{1.3, 0.1, 1.0}, Case{1.3, 0.4, 1.5},
                                           Case{2.0, 0.2, 1.0}, Case{2.0, 0.5, 1.2},
                                           Case{3.0, 0.3, 1.0}, Case{3.0, 0.45, 1.1}));

// The closed form itself against Den Hartog's published amplitude formula (as quoted by Rao),
// X/(F0/k) = sqrt(1/(1-beta^2)^2 - (mu N/F0)^2 U^2), U = sin(pi/beta)/(beta (1 + cos(pi/beta))).
TEST(DenHartogReference, MatchesThePublishedAmplitudeFormula) {
  for (double beta : {0.7, 1.3, 2.0, 3.0})
    for (double ratio : {0.1, 0.3}) {
      const DenHartogOrbit ref(1.0, 1.0, 1.0, beta, ratio, ratio);
      const double U = std::sin(kPi / beta) / (beta * (1 + std::cos(kPi / beta)));
      const double published =
          std::sqrt(1 / std::pow(1 - beta * beta, 2) - ratio * ratio * U * U);
      EXPECT_NEAR(ref.X, published, 1e-12 * published) << "beta " << beta;
    }
}

}  // namespace
}  // namespace contact_coulomb_contact_den_hartog_test

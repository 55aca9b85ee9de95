// Den Hartog (1931): steady state of a harmonically forced oscillator with Coulomb friction and
// continuous sliding (two stops per period, no stick), against CoulombContact + HybridStepper.
//
// Reference: J. P. Den Hartog, "Forced vibrations with combined Coulomb and viscous friction",
// Trans. ASME APM-53-9 (1931) 107-115; the Coulomb-only result is reproduced e.g. in S. S. Rao,
// Mechanical Vibrations, Sec. "Response under Coulomb damping". Derived here independently from
// the piecewise-linear ODE (test comment below), not from the code under test.

#include "contact/den_hartog_orbit.hpp"
#include "contact/single_dof_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace contact_coulomb_contact_den_hartog_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::DenHartogOrbit;
using contact_test::EventLog;
using contact_test::SingleDofOscillator;
using contact_test::SingleDofParameters;
using S = stickslip::ContactState;
constexpr double kPi = 3.14159265358979323846;

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

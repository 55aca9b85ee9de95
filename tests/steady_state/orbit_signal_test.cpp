// An orbit's outputs (ShootingOptions::outputs: extremes, mean, harmonics of y = c^T x) come from
// the orbit's own period, the run that closed it. Checked on the unstable middle orbit of a
// hardening Duffing oscillator's hysteresis, x'' + 0.1 x' + x + x^3 = 0.5 cos(1.5 t) (the
// one-harmonic balance has three orbits there, amplitudes 0.45, 1.02 and 1.44; the middle one is
// a saddle, multiplier > 1): its outputs against an independent Fourier-collocation solution
// (duffing_reference.hpp), and a long separate run from the orbit's state, which leaves it for a
// stable orbit and would report another amplitude.

#include "steady_state/duffing_reference.hpp"
#include "steady_state/smooth_forced_systems.hpp"

#include <stickslip/steady_state/shooting.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace steady_state_orbit_signal_test {  // named: the steady-state test files share one unity TU
namespace {

using Duffing = steady_state_test::ForcedOscillator<1>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 0.1, kK3 = 1, kF = 0.5, kW = 1.5;

Duffing duffing() {
  Duffing d;
  d.C(0, 0) = kC;
  d.k3 = kK3;
  d.f(0) = kF;
  d.omega = kW;
  return d;
}

// One-harmonic balance guess x = a cos(w t) + b sin(w t) for the orbit of amplitude A:
// (1 - w^2 + 3/4 k3 A^2) a + c w b = F, -c w a + (1 - w^2 + 3/4 k3 A^2) b = 0.
Eigen::Vector2d harmonic_guess(double A) {
  const double K = 1 - kW * kW + 0.75 * kK3 * A * A, d = K * K + kC * kC * kW * kW;
  return {kF * K / d, kF * kC * kW / d};
}

stickslip::ShootingOptions<double> options_with_output(int harmonics) {
  stickslip::ShootingOptions<double> o;
  o.outputs = Eigen::RowVector2d(1, 0);  // y = x
  o.output_harmonics = harmonics;
  return o;
}

// Extremes of the max over the period of a trigonometric polynomial, by 20000 phases.
std::pair<double, double> extremes(const steady_state_test::Fourier& f) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int j = 0; j < 20000; ++j) {
    const double v = f.at(2 * kPi * j / 20000);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return {lo, hi};
}

struct PeakObserver : stickslip::NullObserver {
  double t_from = 0, lo = HUGE_VAL, hi = -HUGE_VAL;
  template <class X, class M>
  bool on_step(double t, const X& x, const M&) {
    if (t >= t_from) {
      lo = std::min(lo, x[0]);
      hi = std::max(hi, x[0]);
    }
    return true;
  }
  template <class X, class M>
  bool on_sample(double t, const X& x, const M& m) { return on_step(t, x, m); }
};

TEST(SteadyStateOrbitSignal, UnstableOrbitReportsItsOwnHarmonicsAndExtremesNotWhereALaterRunDrifts) {
  Duffing sys = duffing();
  const int H = 5;
  stickslip::Shooting<Duffing> shooting(sys, options_with_output(H));
  const Eigen::Vector2d ab = harmonic_guess(1.02);
  const double T = 2 * kPi / kW;
  const auto orbit = shooting.forced(0, 0.0, Eigen::Vector2d(ab[0], kW * ab[1]), T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  ASSERT_LE(orbit.residual, shooting.tolerance_at(orbit.x0));
  ASSERT_FALSE(orbit.floquet.stable);  // the saddle of the hysteresis
  EXPECT_EQ(orbit.floquet.instability, stickslip::Instability::Fold);
  ASSERT_EQ(orbit.outputs.size(), 1u);
  const stickslip::OrbitSignal<double>& y = orbit.outputs[0];
  ASSERT_EQ(y.cosines.size(), H);

  // The reference: collocation on 63 points (harmonics up to 31; the orbit's harmonic 2h+1
  // falls by ~k3 A^2 / (4 (2h+1)^2 w^2) per odd order, below 1e-16 long before 31).
  steady_state_test::DuffingParameters p{kC, 1, kK3, kF, kW};
  const int N = 63;
  Eigen::VectorXd xc(N);
  for (int j = 0; j < N; ++j) xc[j] = ab[0] * std::cos(2 * kPi * j / N) + ab[1] * std::sin(2 * kPi * j / N);
  ASSERT_LT(steady_state_test::duffing_collocation(p, N, xc), 1e-10);
  const steady_state_test::Fourier ref = steady_state_test::fourier(xc, 30);
  // The collocation found the middle orbit: first harmonic near the balance's 1.02, not 0.45 or 1.44.
  ASSERT_NEAR(std::hypot(ref.a[0], ref.b[0]), 1.02, 0.05);

  // Mean and harmonics: the run's trapezoidal sums over 256 uniform samples are exact up to
  // aliasing from harmonics >= 251 (nil); what is left is the orbit's own error: the Newton
  // tolerance 1e-9 on x0, amplified by at most |mu| ~ 2 over the period, plus the run's global
  // error (~1e-9 at rtol 1e-10). 2e-8 allowed.
  const double tol = 2e-8;
  EXPECT_NEAR(y.mean, ref.mean, tol);
  for (int h = 1; h <= H; ++h) {
    EXPECT_NEAR(y.cosines[h - 1], ref.a[h - 1], tol) << "h = " << h;
    EXPECT_NEAR(y.sines[h - 1], ref.b[h - 1], tol) << "h = " << h;
  }
  EXPECT_NEAR(y.harmonic(1), std::hypot(ref.a[0], ref.b[0]), tol);
  // Extremes over steps, events and 256 samples: short of the true peak by at most
  // A (1 - cos(pi / 256)) = 7.5e-5 A, never beyond it (by more than the orbit's error).
  const auto [lo, hi] = extremes(ref);
  const double sampling = (hi - lo) / 2 * (1 - std::cos(kPi / 256));
  EXPECT_LE(y.max, hi + tol);
  EXPECT_GE(y.max, hi - sampling - tol);
  EXPECT_GE(y.min, lo - tol);
  EXPECT_LE(y.min, lo + sampling + tol);

  // A separate long run from the orbit's own state (what a measurement by a later run does):
  // the saddle's unstable direction grows by |mu| per period from the orbit's 1e-9 error, and
  // after 150 periods (the stable orbits' transients decay by exp(-c/2 150 T) = e^-31) the run
  // sits on another orbit, whose peak differs from the saddle's by O(0.1) or more.
  stickslip::StepperOptions<double> so = shooting.options().stepper;
  so.output_interval = T / 256;
  stickslip::HybridStepper<Duffing, stickslip::DormandPrince54> stepper(sys, so);
  PeakObserver late;
  late.t_from = 149 * T;
  const auto r = stepper.integrate(0, 0.0, orbit.x0, 150 * T, late);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_GT(std::abs(late.hi - y.max), 0.2) << "late peak " << late.hi << ", orbit's " << y.max;
}

// The orbit's outputs are refused when they do not fit the state, naming the option.
TEST(SteadyStateOrbitSignal, BadOutputOptionsAreRefusedNamingTheOption) {
  Duffing sys = duffing();
  auto expect_refused = [&](const stickslip::ShootingOptions<double>& o, const std::string& name) {
    stickslip::Shooting<Duffing> shooting(sys, o);
    try {
      (void)shooting.forced(0, 0.0, Eigen::Vector2d(0.1, 0), 2 * kPi / kW);
      ADD_FAILURE() << "no exception for " << name;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  auto o = options_with_output(0);
  o.outputs = Eigen::RowVector3d(1, 0, 0);  // 3 columns, state size 2
  expect_refused(o, "options.outputs");
  o = options_with_output(0);
  o.outputs(0, 1) = NAN;
  expect_refused(o, "options.outputs");
  o = options_with_output(200);  // 256 samples cannot resolve 200 harmonics
  expect_refused(o, "options.samples_per_period");
  o = options_with_output(-1);
  expect_refused(o, "options.output_harmonics");
}

}  // namespace
}  // namespace steady_state_orbit_signal_test

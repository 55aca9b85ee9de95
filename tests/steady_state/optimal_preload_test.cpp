// The optimal-preload search of the blade example (examples/blade_damper/resonance_search.hpp:
// min over a parameter of the resonant amplitude max over omega, each amplitude a periodic orbit
// found by Shooting) on a system with an exact min-max: a mass on a spring k with a Maxwell
// element (spring k_d in series with a dashpot c) to ground, the dry-friction damper's linear
// twin (the Jenkins element is k_d in series with a slider). Closed form:
//   X(omega) = F (k_d + i omega c) / ((k - m omega^2)(k_d + i omega c) + i omega c k_d).
// |X| does not depend on c where |k - m omega^2| = |k + k_d - m omega^2|, i.e. at
// omega_P^2 = (k + k_d / 2) / m, with |X_P| = 2F / k_d: every curve passes through P, so
// max_omega |X| >= 2F / k_d for every c, with equality for the c whose peak is at P
// (c* = k_d / omega_P; checked on a 1e-3 grid of the closed form: 0.4474 vs 0.44721).

#include "blade_damper/resonance_search.hpp"

#include <stickslip/steady_state.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace optimal_preload_test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// m x'' = F cos(omega t) - k x - k_d (x - z),  c z' = k_d (x - z); state (x, x', z).
struct MaxwellOscillator {
  using Scalar = double;
  using State = Eigen::Vector3d;
  using Mode = int;
  double m = 1, k = 1, kd = 0.5, F = 1, c = 0.5, omega = 1;

  void rhs(const Mode&, double t, const State& x, State& dxdt) const {
    const double element = kd * (x[0] - x[2]);
    dxdt << x[1], (F * std::cos(omega * t) - k * x[0] - element) / m, element / c;
  }
  Eigen::Index num_guards(const Mode&) const { return 0; }
  void guards(const Mode&, double, const State&, Eigen::VectorXd&) const {}
  stickslip::CrossingDirection guard_direction(const Mode&, Eigen::Index) const {
    return stickslip::CrossingDirection::Either;
  }
  stickslip::TransitionAction transition(Mode&, const stickslip::TriggeredGuards&, double, State&) const {
    return stickslip::TransitionAction::proceed();
  }
};

// Under the sanitizers (STICKSLIP_SANITIZED: -O0 with ASan + UBSan) the full search took 189 s:
// there a coarse one (the brackets to 2 %, runs at rtol 1e-8; ~80 orbits) with the value's
// tolerance widened accordingly (12.5 (0.02 x 0.8)^2 = 3.2e-3, plus the frequency's ~1e-4).
#if defined(STICKSLIP_SANITIZED)
constexpr double kSearchTol = 2e-2, kValueTol = 4e-3, kOmegaTol = 5e-2, kCTol = 2e-2, kRtol = 1e-8;
#else
constexpr double kSearchTol = 1e-3, kValueTol = 3e-5, kOmegaTol = 5e-3, kCTol = 2e-3, kRtol = 1e-10;
#endif

TEST(OptimalPreload, MinMaxAmplitudeOfAMaxwellDamperIsTheFixedPoint) {
  MaxwellOscillator sys;
  stickslip::ShootingOptions<double> opt;
  opt.stepper.rtol = kRtol;
  opt.tolerance = 10 * kRtol;  // Newton's residual cannot go below the runs' error
  opt.amplitude_components = {0};
  opt.samples_per_period = 1024;  // a sampled sine is short of its peak by <= 1 - cos(pi/1024) = 4.7e-6
  stickslip::Shooting<MaxwellOscillator> shooting(sys, opt);
  MaxwellOscillator::State guess = MaxwellOscillator::State::Zero();
  int orbits = 0;
  auto amplitude = [&](double c, double omega) {
    sys.c = c;
    sys.omega = omega;
    const auto orbit = shooting.forced(0, 0.0, guess, 2 * kPi / omega);
    ++orbits;
    if (!orbit.ok()) return std::numeric_limits<double>::quiet_NaN();
    guess = orbit.x0;  // the next orbit is shot from the last one
    return orbit.amplitudes[0];
  };
  // A coarse grid of 5 values of c, then golden sections. Both brackets hold one peak (the
  // closed form has one local maximum in omega for c in [0.2, 1]; the free and stuck resonances
  // are 1 and 1.22 rad/s).
  const auto found = blade::min_max_amplitude(
      amplitude, [](double) { return std::make_pair(0.9, 1.35); }, 0.2, 1.0, kSearchTol, kSearchTol, 5);
  ASSERT_TRUE(found.parameter.ok) << found.parameter.message;
  const double omega_P = std::sqrt((sys.k + sys.kd / 2) / sys.m);
  // The min-max value 2F/k_d = 4. Errors: c within 1e-3 x 0.8 of c* costs <= 12.5 dc^2 = 8e-6
  // (A(c) - 4 ~ 12.5 (c - c*)^2 from the closed form); omega within 1e-3 x 0.45 of the peak
  // costs ~1e-6; sampling <= 4.7e-6 relative (2e-5); the orbits (Newton to 1e-9, runs at rtol
  // 1e-10) ~1e-9: 3e-5 (measured 2e-8).
  EXPECT_NEAR(found.parameter.value, 2 * sys.F / sys.kd, kValueTol);
  // The peak sits at omega_P, where the optimal curve is flat: its position is known to
  // ~5e-3 (measured 2e-5); c* to sqrt(3e-5 / 12.5) ~ 1.5e-3 (measured 4e-5).
  EXPECT_NEAR(found.omega, omega_P, kOmegaTol);
  EXPECT_NEAR(found.parameter.x, sys.kd / omega_P, kCTol);
  EXPECT_LT(orbits, 400);  // 20 peaks of ~17 warm-started shootings (measured 340, 0.3-0.5 s at -O1)
}

TEST(OptimalPreload, GoldenMinimumStopsAtANonFiniteValue) {
  const auto e = blade::golden_minimum(
      [](double x) { return x > 0.5 ? std::numeric_limits<double>::quiet_NaN() : (x - 0.2) * (x - 0.2); }, 0, 1, 1e-6);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("non-finite"), std::string::npos);
  const auto q = blade::golden_minimum([](double x) { return (x - 0.3) * (x - 0.3); }, 0, 1, 1e-8);
  EXPECT_TRUE(q.ok);
  EXPECT_NEAR(q.x, 0.3, 1e-8);  // the bracket's width
}

// A response with two peaks (closed form): a(p, omega) = (1 + p) g(omega; 0.2, 0.1) +
// (2 - p) g(omega; 0.85, 0.05), g a Gaussian bump of height 1. The bumps are so far apart (the
// other's tail is below e^-42 at each top) that max over omega a = max(1 + p, 2 - p), whose
// minimum over p in [0, 1] is 1.5 at p = 0.5. A golden section over omega in [0, 1] compares
// a(0.382) (the wide bump's flank, ~0.04) with a(0.618) (~e^-17) and climbs the wide, lower
// bump: it reports A(p) = 1 + p and p* = 0. The coarse frequency grid (7 points: 0.833 lies
// on the narrow bump) finds the higher one.
double two_peaks(double p, double omega) {
  const auto bump = [](double w, double centre, double width) {
    return std::exp(-((w - centre) / width) * ((w - centre) / width));
  };
  return (1 + p) * bump(omega, 0.2, 0.1) + (2 - p) * bump(omega, 0.85, 0.05);
}

TEST(OptimalPreload, CoarseFrequencyGridFindsTheHigherOfTwoPeaks) {
  const auto bracket = [](double) { return std::make_pair(0.0, 1.0); };
  const auto amplitude = [](double p, double omega) { return two_peaks(p, omega); };
  // Brackets to 1e-4 of their width: the peak value to 2 (1e-4 / 0.05)^2 ~ 1e-5 (the narrow
  // bump's curvature), p* to the golden section's 1e-4 (A is V-shaped with slopes +-1 there).
  const blade::MinMax found = blade::min_max_amplitude(amplitude, bracket, 0.0, 1.0, 1e-4, 1e-4, 5, {}, 7);
  ASSERT_TRUE(found.parameter.ok);
  EXPECT_NEAR(found.parameter.x, 0.5, 2e-4);
  EXPECT_NEAR(found.parameter.value, 1.5, 1e-3);
  EXPECT_NEAR(found.omega, 0.85, 1e-3);
  // The search without the frequency grid (the old one) is fooled: it never sees the narrow peak.
  const blade::MinMax fooled = blade::min_max_amplitude(amplitude, bracket, 0.0, 1.0, 1e-4, 1e-4, 5, {}, 0);
  EXPECT_LT(fooled.parameter.x, 0.01);
  EXPECT_NEAR(fooled.omega, 0.2, 1e-3);
}

TEST(OptimalPreload, GridGoldenMinimumReportsANonFiniteGridValue) {
  const auto e = blade::grid_golden_minimum(
      [](double x) { return x > 0.6 ? std::numeric_limits<double>::infinity() : x; }, 0, 1, 1e-6, 6);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("non-finite"), std::string::npos);
}

}  // namespace
}  // namespace optimal_preload_test

// The landing band of a separated damper (docs/model_separation.md "Separation", "The landing
// band"): a bounce whose rebound would not rise above 1e-8 L is a landing. Without it a
// bounce sequence under a strong pull never reached the landing speed: each impact is located
// where the gap guard, restarted at zero after the previous bounce and so disarmed, has sunk by
// the stepper's guard_zero_tolerance z below it, which feeds sqrt(2 a z) of speed back into every
// impact; the impact speeds then tend to v* = sqrt(2 a z / (1 - e^2)) instead of 0 (the blade
// example at 0.5 and 1 N with --restitution 0.5: ~1e-4 m/s, just above its landing speed, and a
// Zeno stop after 101 bounces 4e-8 s apart).
//
// The reference is the ball on a rigid plate: a damper at the clamped root of a cantilever
// (psi_w = psi_u = 0 there: the member does not move under the contact, W = 1/m exactly) let
// fall from a height h with y_d'' = N0/m = a. Its impacts come at speeds v_k = e^k v0,
// v0 = sqrt(2 a h), at times t0 = sqrt(2 h / a), t_{k+1} = t_k + 2 e v_k / a, and it lands at the
// first impact K whose rebound rises (e v_K)^2 / (2 a) <= 1e-8 L; the impacts' kinetic energy
// losses are m (1 - e^2) v_k^2 / 2 and m v_K^2 / 2 for the landing.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace landing_band_test {

using namespace model_test;

// e = 1/2, a = N0/m = 1000 m/s^2 (the blade's order at low preload: 1150 m/s^2), h = 1 mm,
// landing speed 1e-6 m/s (far below the fixed point v* = 5.2e-5 m/s of the sinking guard, so
// the landing speed alone would never end the sequence: before the band, a Zeno stop).
TEST(LandingBand, BouncesOnARigidPlateEndInALandingAtTheBand) {
  const Cantilever plate;  // the damper at its clamped root
  const double m = 1e-3, N0 = 1.0, e = 0.5, h = 1e-3, a = N0 / m;
  PointDamper<double> d(plate.member, 0.0, m, 10.0, N0, CoulombLaw<double>(0.3, 0.3));
  d.separation = Separation::Separate;
  d.restitution = e;
  d.landing_speed = 1e-6;
  ModelOptions<double> opt;
  opt.moving_contact = false;
  System sys(plate.frame, plate.basis, {d}, {}, opt);
  // The premise: the member does not move at the contact.
  ASSERT_EQ(sys.point_shape(plate.member, 0.0, LoadDirection::Transverse).cwiseAbs().maxCoeff(), 0.0);
  System::State x = sys.initial_state();
  x[sys.flight_offset()] = -h;  // gap = a^T q - y_d = h
  DamperStates mode(1, ContactState::Separated);
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x));
  const double E0 = sys.mechanical_energy(mode, 0.0, x);
  const auto r = simulate(sys, mode, 0.0, x, 0.05, closed_form_run_options(1e-2));
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.mode[0], ContactState::Stick);

  const double band = 1e-8 * plate.length, v0 = std::sqrt(2 * a * h);
  int K = 0;  // the landing impact: the first whose rebound stays within the band
  while (std::pow(e * v0 * std::pow(e, K), 2) > 2 * a * band) ++K;
  ASSERT_EQ(K, 9);  // (e v_8)^2 / 2a = 3.8e-9 m, (e v_9)^2 / 2a = 0.95e-9 m against 2e-9 m
  const auto& hits = sys.impacts();
  ASSERT_EQ(static_cast<int>(hits.size()), K + 1);
  double t_k = std::sqrt(2 * h / a), loss = 0;
  // Each located impact lies up to z = 1e-12 m (the guard zero tolerance) deeper than the last,
  // which adds at most 2 a z to v^2 per impact: |dv| <= (k + 1) a z / v_k; the times carry that
  // and the 1e-12 s event tolerance, summed over the flights.
  const double z = 1e-12;
  double t_tol = 0;
  for (int k = 0; k <= K; ++k) {
    const double v = v0 * std::pow(e, k), v_tol = 2 * (k + 1) * a * z / v + 1e-9;
    if (k > 0) t_k += 2 * e * v0 * std::pow(e, k - 1) / a;
    t_tol += 4 * z / v + 1e-11;
    const auto& hit = hits[static_cast<std::size_t>(k)];
    EXPECT_FALSE(hit.wall);
    EXPECT_NEAR(hit.normal_velocity, -v, v_tol) << "impact " << k;
    EXPECT_NEAR(hit.t, t_k, t_tol) << "impact " << k;
    if (k < K) {
      EXPECT_EQ(hit.to, ContactState::Separated) << "impact " << k;
      EXPECT_NEAR(hit.normal_velocity_after, e * v, e * v_tol) << "impact " << k;
      loss += 0.5 * m * (1 - e * e) * v * v;
    } else {
      EXPECT_EQ(hit.to, ContactState::Stick);
      EXPECT_EQ(hit.normal_velocity_after, 0.0);
      loss += 0.5 * m * v * v;
    }
  }
  // All the potential energy N0 h is lost in the impacts (the damper ends at rest on the plate).
  // The sinking guard adds up to N0 z per impact to what falls (10 impacts: 1e-11 J) and to the
  // closed-form losses through v_k^2 (sum of N0 k z: 5e-11 J): bound 1e-7 N0 h = 1e-10 J.
  const auto b = sys.energy_balance(r.mode, r.t, r.x, E0);
  const double e_tol = 1e-7 * N0 * h;
  EXPECT_NEAR(b.impact_loss, loss, e_tol);
  EXPECT_NEAR(b.impact_loss, N0 * h, e_tol);
  EXPECT_NEAR(b.residual, 0.0, e_tol);
  EXPECT_NEAR(sys.evaluate(r.mode, r.t, r.x).N[0], N0, 1e-9 * N0);  // resting on a rigid plate
}

}  // namespace landing_band_test

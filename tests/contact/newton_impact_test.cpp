// NewtonImpact and coulomb_impulse on their own (closed forms of one impact), and the Separated
// state with the gap guard in a complete hybrid run (tests/contact/impact_systems.hpp): a ball on
// a rigid plate, a mass on a harmonically vibrating table, e = 1 and e = 0, oblique impacts with
// friction. References are closed forms of free flight and of Newton's law, and a bisection on the
// closed-form flight; none comes from the code under test.

#include "contact/contact_test_util.hpp"
#include "contact/impact_systems.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace contact_newton_impact_test {  // named: the contact test files share one (unity) translation unit
namespace {

using contact_test::BouncingMass;
using contact_test::BouncingMassParameters;
using contact_test::expect_invalid_argument;
using stickslip::ContactState;
using stickslip::CoulombLaw;
using stickslip::NewtonImpact;
using Law = CoulombLaw<double>;
using Ball = BouncingMass<Law>;
using Contact = stickslip::CoulombContact<Law>;

constexpr double kPi = 3.14159265358979323846;

// Flight is a quadratic in t: Dormand-Prince integrates it exactly up to round-off, so the event
// times carry the event location error only (event_time_tolerance 1e-12 per event).
stickslip::StepperOptions<double> flight_options(double max_step) {
  stickslip::StepperOptions<double> o;
  o.rtol = 1e-11;
  o.atol = 1e-12;
  o.max_step = max_step;
  return o;
}

template <class System>
stickslip::HybridResult<double, typename System::State, ContactState> run(
    System& sys, ContactState m0, double t0, const typename System::State& x0, double t_end,
    double max_step) {
  stickslip::HybridStepper<System> stepper(sys, flight_options(max_step));
  return stepper.integrate(m0, t0, x0, t_end);
}

// ---------------------------------------------------------------- one impact, closed forms

TEST(NewtonImpact, RejectsRestitutionOutsideTheUnitIntervalAndNegativeLandingSpeed) {
  expect_invalid_argument([] { NewtonImpact<double>(-0.1, 0.0); }, {"NewtonImpact", "restitution"});
  expect_invalid_argument([] { NewtonImpact<double>(1.5, 0.0); }, {"NewtonImpact", "restitution", "1.5"});
  expect_invalid_argument([] { NewtonImpact<double>(std::nan(""), 0.0); }, {"restitution"});
  expect_invalid_argument([] { NewtonImpact<double>(0.5, -1e-3); }, {"landing_speed"});
  expect_invalid_argument(
      [] { NewtonImpact<double>(0.5, std::numeric_limits<double>::infinity()); }, {"landing_speed"});
  const NewtonImpact<double> law(0.5, 0.0);
  expect_invalid_argument([&] { law.impact(-1.0, 0.0); }, {"impact", "inverse_mass"});
  expect_invalid_argument([&] { law.impact(std::nan(""), 1.0); }, {"impact", "v_n"});
  expect_invalid_argument([] { stickslip::coulomb_impulse(Law(0.3, 0.3), 1.0, 1.0, -1.0); },
                          {"coulomb_impulse", "normal_impulse"});
  expect_invalid_argument([] { stickslip::coulomb_impulse(Law(0.3, 0.3), 1.0, -1.0, 1.0); },
                          {"coulomb_impulse", "inverse_mass_t"});
}

TEST(NewtonImpact, BounceReversesTheRelativeVelocityTimesE) {
  // v_n = -2, W = 0.5, e = 0.6: v_after = 1.2, L = (1.2 + 2) / 0.5 = 6.4,
  // loss = (4 - 1.44) / (2 * 0.5) = 2.56 (by hand).
  const auto r = NewtonImpact<double>(0.6, 1e-3).impact(-2.0, 0.5);
  EXPECT_FALSE(r.lands);
  EXPECT_DOUBLE_EQ(r.velocity_after, 1.2);
  EXPECT_DOUBLE_EQ(r.impulse, 6.4);
  EXPECT_DOUBLE_EQ(r.energy_loss, 2.56);
}

TEST(NewtonImpact, LandsPlasticallyBelowTheLandingSpeedWithEZeroAndWhenGrazing) {
  const NewtonImpact<double> law(0.8, 0.1);
  const auto slow = law.impact(-0.1, 2.0);  // at the landing speed: lands (closed rule)
  EXPECT_TRUE(slow.lands);
  EXPECT_EQ(slow.velocity_after, 0.0);
  EXPECT_DOUBLE_EQ(slow.impulse, 0.05);
  EXPECT_DOUBLE_EQ(slow.energy_loss, 0.0025);  // all the relative kinetic energy 0.01 / (2 * 2)
  EXPECT_FALSE(law.impact(-0.1000001, 2.0).lands);
  const auto plastic = NewtonImpact<double>(0.0, 0.0).impact(-3.0, 1.0);
  EXPECT_TRUE(plastic.lands);
  EXPECT_EQ(plastic.velocity_after, 0.0);
  EXPECT_DOUBLE_EQ(plastic.impulse, 3.0);
  const auto grazing = law.impact(0.25, 1.0);  // already separating: no impulse
  EXPECT_TRUE(grazing.lands);
  EXPECT_EQ(grazing.impulse, 0.0);
  EXPECT_EQ(grazing.velocity_after, 0.25);
  EXPECT_EQ(grazing.energy_loss, 0.0);
}

TEST(NewtonImpact, TwoFreeMassesMatchTheTextbookCollision) {
  // Central collision of m1 (velocity u1, below) and m2 (u2, above, u2 < u1 approaching):
  // u1' = (m1 u1 + m2 u2 - m2 e (u1 - u2)) / (m1 + m2), u2' = (m1 u1 + m2 u2 + m1 e (u1 - u2)) /
  // (m1 + m2) (e.g. Goldsmith, Impact, 1960, ch. 2). The contact is mass 2 on mass 1 with normal
  // up: v_n = u2 - u1, W = 1/m1 + 1/m2, the impulse pushes m2 up and m1 down.
  const double m1 = 3.0, m2 = 0.7, u1 = 1.5, u2 = -2.0, e = 0.4;
  const auto r = NewtonImpact<double>(e, 0.0).impact(u2 - u1, 1.0 / m1 + 1.0 / m2);
  const double u1p = u1 - r.impulse / m1, u2p = u2 + r.impulse / m2;
  EXPECT_NEAR(u1p, (m1 * u1 + m2 * u2 - m2 * e * (u1 - u2)) / (m1 + m2), 1e-14);
  EXPECT_NEAR(u2p, (m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / (m1 + m2), 1e-14);
  // Momentum conserved, and the loss is the kinetic energy lost by the pair.
  EXPECT_NEAR(m1 * u1p + m2 * u2p, m1 * u1 + m2 * u2, 1e-14);
  const double T0 = 0.5 * (m1 * u1 * u1 + m2 * u2 * u2), T1 = 0.5 * (m1 * u1p * u1p + m2 * u2p * u2p);
  EXPECT_NEAR(T0 - T1, r.energy_loss, 1e-13);
}

TEST(CoulombImpulse, SticksWhenTheStickImpulseIsWithinTheCapacityAndSlidesOtherwise) {
  const Law law(0.4, 0.25);
  const double m = 2.0;
  // v_t = 1: stopping needs |L| = m v_t = 2; capacity mu_s L_n = 0.4 * 5 = 2: sticks (closed set).
  const auto stick = stickslip::coulomb_impulse(law, 1.0, 1.0 / m, 5.0);
  EXPECT_EQ(stick.state, ContactState::Stick);
  EXPECT_DOUBLE_EQ(stick.impulse, -2.0);
  EXPECT_EQ(stick.velocity_after, 0.0);
  EXPECT_DOUBLE_EQ(stick.energy_loss, 1.0);  // m v^2 / 2
  // L_n = 4.9: capacity 1.96 < 2: slides with L = -mu_k L_n = -1.225, v after = 1 - 1.225 / 2.
  const auto slip = stickslip::coulomb_impulse(law, 1.0, 1.0 / m, 4.9);
  EXPECT_EQ(slip.state, ContactState::SlipPositive);
  EXPECT_DOUBLE_EQ(slip.impulse, -1.225);
  EXPECT_DOUBLE_EQ(slip.velocity_after, 1.0 - 1.225 / m);
  EXPECT_DOUBLE_EQ(slip.energy_loss, 0.5 * m * (1.0 - slip.velocity_after * slip.velocity_after));
  const auto back = stickslip::coulomb_impulse(law, -1.0, 1.0 / m, 4.9);  // mirror image
  EXPECT_EQ(back.state, ContactState::SlipNegative);
  EXPECT_DOUBLE_EQ(back.impulse, 1.225);
}

// A point mass m (velocity u = (u_x, u_y)) lands on the flat top of a cart of mass M that slides
// without friction along an incline a = (cos th, sin th): the contact's normal is y, its tangent x,
// and the cart's inertia couples them: W = I/m + b b^T / M with b = (sin th, cos th) in (n, t)
// order, W_nt = sin th cos th / M. The outcome is checked on the bodies' own velocities, updated
// by the impulses (u += L/m, s -= (L_t cos th + L_n sin th)/M): Newton's law on the relative
// normal velocity, Coulomb's law, momentum along the incline and the kinetic energy lost.
struct MassOnCart {
  double m = 1.0, M = 2.0, th = 0.5;
  Eigen::Matrix2d W() const {
    const Eigen::Vector2d b(std::sin(th), std::cos(th));
    return Eigen::Matrix2d::Identity() / m + b * b.transpose() / M;
  }
  // Relative (normal, tangential) velocity of the mass with respect to the cart.
  Eigen::Vector2d relative(const Eigen::Vector2d& u, double s) const {
    return {u.y() - s * std::sin(th), u.x() - s * std::cos(th)};
  }
  double momentum_along_incline(const Eigen::Vector2d& u, double s) const {
    return m * (u.x() * std::cos(th) + u.y() * std::sin(th)) + M * s;
  }
  double kinetic_energy(const Eigen::Vector2d& u, double s) const {
    return 0.5 * m * u.squaredNorm() + 0.5 * M * s * s;
  }
};

struct CartImpactCase {
  double mu, e, u_x, u_y, s;
  ContactState expected;
};

TEST(FrictionalImpact, CoupledDirectionsSatisfyNewtonCoulombMomentumAndEnergyOnTheBodies) {
  const MassOnCart cart;
  ASSERT_GT(std::abs(cart.W()(0, 1)), 0.1);  // really coupled
  for (const CartImpactCase& c : {CartImpactCase{1.0, 0.6, 0.3, -2.0, 0.5, ContactState::Stick},
                                  CartImpactCase{0.1, 0.6, 3.0, -2.0, 0.5, ContactState::SlipPositive},
                                  CartImpactCase{0.1, 0.3, -3.0, -1.0, -0.2, ContactState::SlipNegative},
                                  CartImpactCase{0.4, 0.0, 0.2, -1.5, 0.1, ContactState::Stick},
                                  // v_t = -0.01: the normal impulse drives the sliding forward
                                  // (W_tn L_n > mu W_tt L_n): slip reverses through the impact.
                                  CartImpactCase{0.1, 0.6, 0.5 * std::cos(0.5) - 0.01, -2.0, 0.5,
                                                 ContactState::SlipPositive}}) {
    SCOPED_TRACE("mu " + std::to_string(c.mu) + " u_x " + std::to_string(c.u_x));
    const Eigen::Vector2d u(c.u_x, c.u_y);
    const Eigen::Vector2d v = cart.relative(u, c.s);
    ASSERT_LT(v[0], 0.0);
    const auto r = stickslip::frictional_impact(NewtonImpact<double>(c.e, 1e-6), Law(c.mu, c.mu),
                                                cart.W(), v);
    ASSERT_TRUE(r.resolved);
    EXPECT_EQ(r.state, c.expected);
    EXPECT_EQ(r.lands, c.e == 0.0);
    // The bodies after the impulses (the cart receives -L).
    const Eigen::Vector2d L_xy(r.impulse[1], r.impulse[0]);
    const Eigen::Vector2d u_after = u + L_xy / cart.m;
    const double s_after =
        c.s - (L_xy.x() * std::cos(cart.th) + L_xy.y() * std::sin(cart.th)) / cart.M;
    const Eigen::Vector2d v_after = cart.relative(u_after, s_after);
    // Velocities O(1), masses O(1): round-off of a few operations, 1e-14.
    EXPECT_NEAR(v_after[0], -c.e * v[0], 1e-14);
    EXPECT_NEAR(v_after[0], r.velocity_after[0], 1e-14);
    EXPECT_NEAR(v_after[1], r.velocity_after[1], 1e-14);
    EXPECT_GT(r.impulse[0], 0.0);
    if (c.expected == ContactState::Stick) {
      EXPECT_NEAR(v_after[1], 0.0, 1e-14);
      EXPECT_LE(std::abs(r.impulse[1]), c.mu * r.impulse[0]);
    } else {
      const double sigma = stickslip::slip_sign(c.expected);
      EXPECT_NEAR(r.impulse[1], -sigma * c.mu * r.impulse[0], 1e-14);
      EXPECT_GE(sigma * v_after[1], 0.0);  // no reversal
    }
    EXPECT_NEAR(cart.momentum_along_incline(u_after, s_after), cart.momentum_along_incline(u, c.s),
                1e-14);
    EXPECT_NEAR(cart.kinetic_energy(u, c.s) - cart.kinetic_energy(u_after, s_after),
                r.energy_loss, 1e-13);
    EXPECT_GE(r.energy_loss, 0.0);
  }
}

TEST(FrictionalImpact, DecoupledDirectionsAreNewtonThenCoulombImpulse) {
  const Eigen::Matrix2d W = Eigen::Vector2d(0.5, 0.5).asDiagonal();
  const NewtonImpact<double> newton(0.7, 1e-3);
  const Law law(0.35, 0.25);
  for (double v_t : {-2.0, -0.4, 0.0, 0.1, 3.0}) {
    const auto r = stickslip::frictional_impact(newton, law, W, Eigen::Vector2d(-1.5, v_t));
    const auto n = newton.impact(-1.5, 0.5);
    const auto t = stickslip::coulomb_impulse(law, v_t, 0.5, n.impulse);
    EXPECT_DOUBLE_EQ(r.impulse[0], n.impulse) << v_t;
    EXPECT_DOUBLE_EQ(r.impulse[1], t.impulse) << v_t;
    EXPECT_EQ(r.state, t.state) << v_t;
    EXPECT_NEAR(r.energy_loss, n.energy_loss + t.energy_loss, 1e-14) << v_t;
  }
}

TEST(FrictionalImpact, NoImpulseWithoutApproachAndBadInverseMassThrows) {
  const Law law(0.3, 0.3);
  const NewtonImpact<double> newton(0.5, 0.0);
  const auto r = stickslip::frictional_impact(newton, law, Eigen::Matrix2d::Identity(),
                                              Eigen::Vector2d(0.2, -1.0));
  EXPECT_EQ(r.impulse, Eigen::Vector2d::Zero());
  EXPECT_EQ(r.velocity_after, Eigen::Vector2d(0.2, -1.0));
  EXPECT_EQ(r.state, ContactState::SlipNegative);
  Eigen::Matrix2d bad;
  bad << 1.0, 2.0, 2.0, 1.0;  // indefinite
  expect_invalid_argument([&] { stickslip::frictional_impact(newton, law, bad, Eigen::Vector2d(-1, 0)); },
                          {"frictional_impact", "positive definite"});
  bad << 1.0, 0.1, 0.2, 1.0;
  expect_invalid_argument([&] { stickslip::frictional_impact(newton, law, bad, Eigen::Vector2d(-1, 0)); },
                          {"frictional_impact", "symmetric"});
  expect_invalid_argument(
      [&] {
        stickslip::frictional_impact(newton, law, Eigen::Matrix2d::Identity(),
                                     Eigen::Vector2d(std::nan(""), 0));
      },
      {"frictional_impact", "v_n"});
}

TEST(CoulombContactSeparated, NoForceOneGapGuardFallingAndItsName) {
  const Contact contact(Law(0.5, 0.3));
  EXPECT_EQ(contact.friction_force(ContactState::Separated, 0.7, 2.0, 1.0), 0.0);
  EXPECT_EQ(Contact::num_guards(ContactState::Separated, true), 1);
  EXPECT_EQ(Contact::num_guards(ContactState::Separated, false), 1);
  EXPECT_EQ(Contact::guard_direction(ContactState::Separated, 0, true),
            stickslip::CrossingDirection::Falling);
  double g = -1.0;
  Contact::gap_guard(0.25, &g);
  EXPECT_EQ(g, 0.25);
  EXPECT_FALSE(Contact::velocity_guard_fired(ContactState::Separated, {0}));
  EXPECT_STREQ(stickslip::to_string(ContactState::Separated), "separated");
  EXPECT_FALSE(stickslip::is_in_contact(ContactState::Separated));
  EXPECT_FALSE(stickslip::is_in_contact(ContactState::LiftOff));
  EXPECT_TRUE(stickslip::is_in_contact(ContactState::SlipNegative));
  EXPECT_EQ(stickslip::slip_sign(ContactState::Separated), 0);
}

// ---------------------------------------------------------------- ball on a rigid plate

// Dropped from rest at height h: impact k (1-based) at t_k, t_1 = sqrt(2h/g), t_{k+1} = t_k +
// 2 e^k v_1 / g, at speed e^{k-1} v_1 (v_1 = g t_1); apex k at t_k + e^k v_1 / g, height
// e^{2k} h; accumulation time t_inf = t_1 (1 + e) / (1 - e).
struct DroppedBall {
  double h, g, e;
  double t1() const { return std::sqrt(2.0 * h / g); }
  double v1() const { return g * t1(); }
  double impact_time(int k) const {
    double t = t1();
    for (int j = 1; j < k; ++j) t += 2.0 * std::pow(e, j) * v1() / g;
    return t;
  }
  double impact_speed(int k) const { return std::pow(e, k - 1) * v1(); }
  double t_inf() const { return t1() * (1.0 + e) / (1.0 - e); }
};

// The ball rising for `lead` seconds before its apex (h, t = 0): started at t = -lead, so that the
// apex guard (y' Falling) does not start at zero (it would fire at once, every time).
Ball::State rising_to_apex(const DroppedBall& ref, double lead) {
  Ball::State x = Ball::State::Zero();
  x[2] = ref.h - 0.5 * ref.g * lead * lead;
  x[3] = ref.g * lead;
  return x;
}

TEST(BallOnPlate, ImpactTimesApexHeightsAndTheLandingBeforeTheAccumulationTime) {
  BouncingMassParameters p;
  p.mass = 0.3;
  p.record_apex = true;
  const DroppedBall ref{1.0, p.gravity, 0.5};
  const double landing_speed = 1e-3;
  Ball ball(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(ref.e, landing_speed));
  const auto r = run(ball, ContactState::Separated, -0.1, rising_to_apex(ref, 0.1), 3.0, 0.05);
  ASSERT_TRUE(r.ok()) << r.message;  // an ordinary landing: no ZenoGuard stop
  EXPECT_EQ(r.mode, ContactState::Stick);

  // The stated rule on the closed-form speeds: landing at the first impact K with speed <= 1e-3.
  int K = 1;
  while (ref.impact_speed(K) > landing_speed) ++K;
  ASSERT_EQ(ball.impacts.size(), static_cast<std::size_t>(K));
  EXPECT_EQ(ball.bounces, K - 1);
  EXPECT_EQ(ball.landings, 1);
  for (int k = 1; k <= K; ++k) {
    const auto& hit = ball.impacts[static_cast<std::size_t>(k - 1)];
    // Event times: 1e-12 per event, accumulated over <= 14 events and the round-off of t.
    EXPECT_NEAR(hit.t, ref.impact_time(k), 1e-10) << "impact " << k;
    // Speed error g * (time error) plus round-off of the state.
    EXPECT_NEAR(-hit.v_n, ref.impact_speed(k), 1e-9) << "impact " << k;
    EXPECT_EQ(hit.lands, k == K);
  }
  // The apex of the drop at t = 0, then one apex per bounce.
  ASSERT_EQ(ball.apexes.size(), static_cast<std::size_t>(K));
  for (int k = 0; k < K; ++k) {
    const auto& apex = ball.apexes[static_cast<std::size_t>(k)];
    const double t_ref =
        k == 0 ? 0.0 : ref.impact_time(k) + std::pow(ref.e, k) * ref.v1() / p.gravity;
    EXPECT_NEAR(apex.t, t_ref, 1e-10) << "apex " << k;
    // Height u^2 / (2 g) from the launch speed u, whose error is g times the impact time error
    // (1e-12 s): dh = u * 1e-12 s <= 4.4e-12 m (measured 1.7e-12 at apex 1).
    EXPECT_NEAR(apex.y, std::pow(ref.e, 2 * k) * ref.h, 1e-11) << "apex " << k;
  }
  // Landing cuts the Zeno tail: it lands before t_inf by at most the remaining flights,
  // sum_{j >= K} 2 e^j v_1 / g = 2 e v_K / (g (1 - e)) with v_K <= landing_speed.
  const double t_land = ball.impacts.back().t;
  EXPECT_LT(t_land, ref.t_inf());
  EXPECT_LE(ref.t_inf() - t_land, 2.0 * ref.e * landing_speed / (p.gravity * (1.0 - ref.e)) + 1e-10);
  // At rest on the plate: y = 0, all of m g h lost in impacts (no friction work: x' = 0).
  EXPECT_NEAR(r.x[2], 0.0, 1e-12);
  EXPECT_EQ(r.x[3], 0.0);
  EXPECT_NEAR(r.x[4], p.mass * p.gravity * ref.h, 1e-9);
}

TEST(BallOnPlate, RestitutionOneConservesEnergyOverManyImpacts) {
  BouncingMassParameters p;
  p.record_apex = true;
  const DroppedBall ref{0.5, p.gravity, 1.0};
  Ball ball(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(1.0, 0.0));
  const Ball::State x0 = rising_to_apex(ref, 0.1);
  const int n = 200;
  const auto r = run(ball, ContactState::Separated, -0.1, x0, (2 * n) * ref.t1(), 0.05);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(ball.impacts.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(ball.landings, 0);
  for (std::size_t k = 0; k < ball.impacts.size(); ++k) {
    const auto& hit = ball.impacts[k];
    // Impact k + 1 at (2k + 1) t_1; the event error (1e-12 per event) accumulates linearly.
    EXPECT_NEAR(hit.t, (2.0 * static_cast<double>(k) + 1.0) * ref.t1(), 1e-9) << "impact " << k;
    EXPECT_NEAR(-hit.v_n, ref.v1(), 1e-9) << "impact " << k;
  }
  for (const auto& apex : ball.apexes) EXPECT_NEAR(apex.y, ref.h, 1e-10) << "apex at " << apex.t;
  EXPECT_EQ(r.x[4], 0.0);  // e = 1: no impact loss at all
  // Energy m g h + 0: the state after 200 impacts, to the accumulated round-off.
  EXPECT_NEAR(ball.energy(r.x), p.mass * p.gravity * ref.h, 1e-9);
}

TEST(BallOnPlate, RestitutionZeroLandsPlasticallyAtTheFirstImpact) {
  BouncingMassParameters p;
  p.mass = 2.0;
  const DroppedBall ref{0.8, p.gravity, 0.0};
  // landing_speed 0: e = 0 lands by itself, not by the speed rule.
  Ball ball(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(0.0, 0.0));
  Ball::State x0 = Ball::State::Zero();
  x0[2] = ref.h;
  x0[1] = 1.0;  // sliding at 1 m/s: stopping needs m * 1 = 2 N s <= mu_s L_n = 0.3 m v_1: sticks
  const auto r = run(ball, ContactState::Separated, 0.0, x0, 5.0, 0.05);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(ball.impacts.size(), 1u);
  EXPECT_TRUE(ball.impacts[0].lands);
  EXPECT_EQ(ball.bounces, 0);
  EXPECT_NEAR(ball.impacts[0].t, ref.t1(), 1e-11);
  EXPECT_NEAR(ball.impacts[0].impulse, p.mass * ref.v1(), 1e-9);  // L = m v_1 (e = 0)
  EXPECT_EQ(r.mode, ContactState::Stick);
  EXPECT_EQ(r.x[1], 0.0);
  // Everything lost in the impact: m g h (normal) + m 1^2 / 2 (the tangential impulse).
  EXPECT_NEAR(r.x[4], p.mass * p.gravity * ref.h + 0.5 * p.mass, 1e-9);
  EXPECT_EQ(r.stats.events, 1);
}

TEST(BallOnPlate, ObliqueImpactsSlideThenStickByCoulombsLawForImpulses) {
  // Each impact k has L_n = m (1 + e) v_k; the tangential speed drops by mu (1 + e) v_k while
  // that is below it (slip), and the impact that could stop it sticks it (closed form below).
  BouncingMassParameters p;
  const double mu = 0.3, e = 0.5, u0 = 3.0;
  const DroppedBall ref{1.0, p.gravity, e};
  Ball ball(p, Contact(Law(mu, mu)), NewtonImpact<double>(e, 1e-3));
  Ball::State x0 = Ball::State::Zero();
  x0[2] = ref.h;
  x0[1] = u0;
  const auto r = run(ball, ContactState::Separated, 0.0, x0, 3.0, 0.05);
  ASSERT_TRUE(r.ok()) << r.message;
  double u = u0;
  int stick_at = 0;
  for (int k = 1; u > 0.0; ++k) {
    const double drop = mu * (1.0 + e) * ref.impact_speed(k);
    u = drop >= u ? 0.0 : u - drop;
    stick_at = k;
  }
  ASSERT_GE(ball.impacts.size(), static_cast<std::size_t>(stick_at));
  // The tangential position at the stick impact: x = sum of (speed after impact j) * flight j.
  double x_ref = u0 * ref.t1();
  u = u0;
  for (int k = 1; k < stick_at; ++k) {
    u -= mu * (1.0 + e) * ref.impact_speed(k);
    x_ref += u * (ref.impact_time(k + 1) - ref.impact_time(k));
  }
  EXPECT_EQ(r.x[1], 0.0);
  // x ~ 3 m: the impact times' error (1e-10) times the speeds (3 m/s) plus round-off.
  EXPECT_NEAR(r.x[0], x_ref, 1e-9);
  // The energy balance closes through the impact losses (no surface motion: W_surface = 0).
  EXPECT_NEAR(ball.balance(r.x), ball.balance(x0), 1e-9);
  EXPECT_GT(r.x[4], p.mass * p.gravity * ref.h);  // normal plus tangential impact losses
}

TEST(BallOnPlate, WithoutTheLandingRuleTheBouncesAccumulateIntoAZenoStop) {
  // The counter-test of the landing rule: landing_speed 0 lets the Zeno sequence run; the stepper
  // stops it with ZenoGuard at (just before) the accumulation time t_inf = 3 t_1 (e = 0.5).
  BouncingMassParameters p;
  const DroppedBall ref{1.0, p.gravity, 0.5};
  Ball ball(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(ref.e, 0.0));
  Ball::State x0 = Ball::State::Zero();
  x0[2] = ref.h;
  const auto r = run(ball, ContactState::Separated, 0.0, x0, 3.0, 0.05);
  EXPECT_EQ(r.status, stickslip::Status::ZenoGuard) << r.message;
  EXPECT_EQ(ball.landings, 0);
  // The bounces run on until their height falls below the guard zero tolerance (1e-12 m); then
  // the gap guard starts disarmed after each impact, and the chain of 101 immediate events, each
  // a fall of 1e-12 m (sqrt(2e-12 / g) ~ 4.5e-7 s), stops the run ~5e-5 s after t_inf.
  EXPECT_GT(ball.bounces, 30);
  EXPECT_GT(r.t, ref.t_inf() - 1e-9);
  EXPECT_LT(r.t, ref.t_inf() + 1e-4);
}

// ---------------------------------------------------------------- vibrating table

// The table w = A sin(Omega t): a mass resting on it has N = m (g - A Omega^2 sin(Omega t)), zero
// first at t_lift = asin(g / (A Omega^2)) / Omega (Gamma = A Omega^2 / g > 1).
TEST(VibratingTable, LiftsOffWhereTheTablesAccelerationExceedsGAndLandsOnTheClosedFormFlight) {
  BouncingMassParameters p;
  p.amplitude = 0.012;
  p.frequency = 10.0 * kPi;
  const double gamma = p.amplitude * p.frequency * p.frequency / p.gravity;
  ASSERT_GT(gamma, 1.0);
  Ball table(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(0.5, 1e-4));
  const double t_lift = std::asin(1.0 / gamma) / p.frequency;
  const double T = 2.0 * kPi / p.frequency;
  const auto r = run(table, ContactState::Stick, 0.0, table.on_surface(0.0), T, T / 100);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_GE(table.lift_offs.size(), 1u);
  // N falls through zero with slope m A Omega^3 cos(Omega t) ~ 70 N/s: the event time (1e-12)
  // and the integration error of (y, y') in contact (rtol 1e-11) bound the error.
  EXPECT_NEAR(table.lift_offs[0], t_lift, 1e-10);
  ASSERT_GE(table.impacts.size(), 1u);
  // The first impact: the root of the closed-form flight minus the table, by bisection.
  const double y0 = table.w(t_lift), v0 = table.w_dot(t_lift);
  auto gap = [&](double t) {
    const double s = t - t_lift;
    return y0 + v0 * s - 0.5 * p.gravity * s * s - table.w(t);
  };
  double a = t_lift + 1e-3, b = a;  // the gap grows like (t - t_lift)^3 first
  while (gap(b) > 0.0) b += T / 1000;
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) (gap(0.5 * (a + b)) > 0.0 ? a : b) = 0.5 * (a + b);
  // The lift-off time error (1e-10) moves the flight; the crossing angle is large (~1 m/s).
  EXPECT_NEAR(table.impacts[0].t, b, 1e-9);
  const double s = b - t_lift;
  EXPECT_NEAR(table.impacts[0].v_n, v0 - p.gravity * s - table.w_dot(b), 1e-8);
  // The energy balance closes with the surface's work (continuous and impulsive).
  EXPECT_NEAR(table.balance(r.x), table.balance(table.on_surface(0.0)), 1e-8);
}

TEST(VibratingTable, PeriodOneBounceOrbitHasTheClosedFormImpactVelocity) {
  // Period-1 orbit (one impact per table period T, Holmes 1982, J. Sound Vib. 84): the ball
  // leaves each impact at absolute speed g T / 2 and returns at -g T / 2; Newton's law
  // g T/2 - w' = -e (-g T/2 - w') gives the table speed w' = (1 - e)/(1 + e) g T / 2 at impact and
  // the relative impact velocity v_n = -g T / (1 + e). Started 1e-3 m/s off the orbit, the run
  // must converge onto it (the orbit with the table decelerating at impact is stable here: the
  // perturbation decays by ~0.6 per period).
  BouncingMassParameters p;
  p.amplitude = 0.012;
  p.frequency = 10.0 * kPi;
  const double e = 0.5, T = 2.0 * kPi / p.frequency;
  const double w_dot_star = (1.0 - e) / (1.0 + e) * p.gravity * T / 2.0;
  const double phase = std::acos(w_dot_star / (p.amplitude * p.frequency));  // sin > 0: w'' < 0
  Ball table(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(e, 1e-4));
  const double t0 = phase / p.frequency;
  Ball::State x0 = table.on_surface(t0);
  x0[3] = p.gravity * T / 2.0 + 1e-3;
  const int periods = 60;
  const auto r = run(table, ContactState::Separated, t0, x0, t0 + (periods + 0.5) * T, T / 50);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(table.impacts.size(), static_cast<std::size_t>(periods));
  EXPECT_EQ(table.landings, 0);
  for (std::size_t k = table.impacts.size() - 10; k < table.impacts.size(); ++k) {
    const auto& hit = table.impacts[k];
    // Converged to 0.6^50 ~ 1e-11 of the perturbation; the event error is 1e-12 per impact.
    EXPECT_NEAR(hit.v_n, -p.gravity * T / (1.0 + e), 1e-8) << "impact " << k;
    EXPECT_NEAR(hit.t - table.impacts[k - 1].t, T, 1e-9) << "impact " << k;
    EXPECT_NEAR(table.w_dot(hit.t), w_dot_star, 1e-8) << "impact " << k;
  }
}

TEST(VibratingTable, LiftOffBouncesAndLandingsRepeatEveryPeriodAndTheEnergyBalanceCloses) {
  // Gamma = 1.2 with e = 0.3: each period the mass lifts off, bounces a few times with falling
  // speeds, lands by the rule and rides the table until the next lift-off (a chattering orbit).
  // Every landing ends a Zeno sequence; 40 periods must run without a ZenoGuard stop.
  BouncingMassParameters p;
  p.frequency = 10.0 * kPi;
  p.amplitude = 1.2 * p.gravity / (p.frequency * p.frequency);
  p.mass = 0.5;
  Ball table(p, Contact(Law(0.3, 0.3)), NewtonImpact<double>(0.3, 1e-5));
  const double T = 2.0 * kPi / p.frequency;
  const int periods = 40;
  const Ball::State x0 = table.on_surface(0.0);
  const auto r = run(table, ContactState::Stick, 0.0, x0, periods * T, T / 100);
  ASSERT_TRUE(r.ok()) << r.message;
  // One lift-off per period where N = m (g - A Omega^2 sin(Omega t)) first falls through 0,
  // t = (asin(1/Gamma) + 2 pi k) / Omega, once the mass rides the table at that time.
  ASSERT_GE(table.lift_offs.size(), static_cast<std::size_t>(periods - 1));
  EXPECT_GE(table.landings, periods - 1);
  EXPECT_GT(table.bounces, 0);
  const double phase = std::asin(1.0 / 1.2);
  for (double t : table.lift_offs) {
    const double k = std::round((p.frequency * t - phase) / (2.0 * kPi));
    EXPECT_NEAR(t, (phase + 2.0 * kPi * k) / p.frequency, 1e-9) << "lift-off at " << t;
  }
  // Balance: kinetic + potential + impact losses - surface work, constant; the mass stays stuck
  // tangentially (x' = 0), so no friction term. Terms ~ 1e-2 J; the integration error of the work
  // integral (rtol 1e-11) over 40 periods and their lift-offs and impacts; measured 1.4e-9.
  EXPECT_NEAR(table.balance(r.x), table.balance(x0), 5e-9);
  EXPECT_GT(r.x[4], 0.0);
}

}  // namespace
}  // namespace contact_newton_impact_test

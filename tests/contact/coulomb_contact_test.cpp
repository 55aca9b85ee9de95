// CoulombContact: the decision table of docs/contact.md (exhaustively), guards and their
// directions, and the friction force in every state.

#include <stickslip/contact/coulomb_contact.hpp>

#include <stickslip/contact/coulomb_law.hpp>
#include <stickslip/contact/regularised_law.hpp>
#include <stickslip/contact/stribeck_law.hpp>

#include "contact/contact_test_util.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>

namespace contact_coulomb_contact_test {  // named: the contact test files share one (unity) translation unit
namespace {

using stickslip::CoulombContact;
using stickslip::CoulombLaw;
using stickslip::CrossingDirection;
using stickslip::RegularisedLaw;
using stickslip::RegularisedShape;
using stickslip::StribeckLaw;
using S = stickslip::ContactState;
using contact_test::expect_invalid_argument;

constexpr std::array<S, 4> kAllStates = {S::Stick, S::SlipPositive, S::SlipNegative, S::LiftOff};

// Inputs of the table. mu_s = 0.5, N = 2 for the positive-N rows, so the capacity is 1.
constexpr double kMuS = 0.5;
constexpr double kMuK = 0.3;
constexpr double kTol = 1e-8;  // the contact's velocity tolerance in these tests

// Sliding velocity classes: clearly negative, at and inside the tolerance, zero, clearly positive.
constexpr std::array<double, 7> kVelocities = {-1.0, -kTol, -0.5 * kTol, 0.0,
                                               0.5 * kTol, kTol, 1.0};
// f_required classes: inside the capacity (both signs and 0), exactly at it, above it.
constexpr std::array<double, 7> kForces = {0.0, 0.4, -0.4, 1.0, -1.0, 1.5, -1.5};
// Normal force classes: in contact, zero, tension, and the N -> 0 limit (capacity 5e-301).
constexpr std::array<double, 4> kNormals = {2.0, 0.0, -2.0, 1e-300};

// Expected decision for N = 2 (docs/contact.md, "Decision rules", written out, not computed):
// rows = kVelocities, columns = kForces. Identical for every `from` state.
constexpr S P = S::SlipPositive, Q = S::SlipNegative, K = S::Stick;
constexpr std::array<std::array<S, 7>, 7> kExpectedExact = {{
    //  0  0.4 -0.4  1.0 -1.0  1.5 -1.5      f_required
    {{Q, Q, Q, Q, Q, Q, Q}},  // v = -1        rule 2: slip in sgn(v)
    {{K, K, K, K, K, Q, P}},  // v = -tol      rules 3/4
    {{K, K, K, K, K, Q, P}},  // v = -tol/2
    {{K, K, K, K, K, Q, P}},  // v = 0
    {{K, K, K, K, K, Q, P}},  // v = +tol/2
    {{K, K, K, K, K, Q, P}},  // v = +tol
    {{P, P, P, P, P, P, P}},  // v = +1        rule 2
}};
// Regularised laws: no stick state; "Stick" labels |v| <= tol.
constexpr std::array<S, 7> kExpectedRegularised = {Q, K, K, K, K, K, P};
// N = 1e-300: capacity 5e-301, so every non-zero f_required exceeds it.
constexpr std::array<S, 7> kExpectedTinyNormalAtRest = {K, Q, P, Q, P, Q, P};

template <class Law>
void check_exact_table(const Law& law) {
  const CoulombContact<Law> contact(law, kTol);
  int checked = 0;
  for (S from : kAllStates)
    for (std::size_t iv = 0; iv < kVelocities.size(); ++iv)
      for (std::size_t jf = 0; jf < kForces.size(); ++jf)
        for (double N : kNormals) {
          const double v = kVelocities[iv];
          const double f = kForces[jf];
          S expected;
          if (N <= 0.0)
            expected = S::LiftOff;  // rule 1
          else if (N == 2.0)
            expected = kExpectedExact[iv][jf];
          else
            expected = std::abs(v) > kTol ? kExpectedExact[iv][jf] : kExpectedTinyNormalAtRest[jf];
          EXPECT_EQ(contact.decide(from, v, N, f), expected)
              << "from " << from << ", v = " << v << ", N = " << N << ", f_required = " << f;
          ++checked;
        }
  EXPECT_EQ(checked, 4 * 7 * 7 * 4);
}

TEST(CoulombContactDecide, ExhaustiveTableCoulomb) { check_exact_table(CoulombLaw<double>(kMuS, kMuK)); }

// The decision uses only mu_s, so a Stribeck law must give the same table.
TEST(CoulombContactDecide, ExhaustiveTableStribeck) {
  check_exact_table(StribeckLaw<double>(kMuS, kMuK, 1e-3, 1.0));
}

TEST(CoulombContactDecide, ExhaustiveTableRegularised) {
  for (RegularisedShape shape : {RegularisedShape::Tanh, RegularisedShape::LinearSaturated}) {
    const CoulombContact<RegularisedLaw<double>> contact(RegularisedLaw<double>(kMuS, 1e-3, shape),
                                                         kTol);
    for (S from : kAllStates)
      for (std::size_t iv = 0; iv < kVelocities.size(); ++iv)
        for (double f : kForces)
          for (double N : kNormals) {
            const S expected = N <= 0.0 ? S::LiftOff : kExpectedRegularised[iv];
            EXPECT_EQ(contact.decide(from, kVelocities[iv], N, f), expected)
                << "from " << from << ", v = " << kVelocities[iv] << ", N = " << N;
          }
  }
}

// mu_s = mu_k = 0: the capacity is zero; only f_required = 0 exactly can stick.
TEST(CoulombContactDecide, FrictionlessContactSticksOnlyWithoutLoad) {
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(0.0, 0.0), kTol);
  EXPECT_EQ(contact.decide(S::SlipPositive, 0.0, 1.0, 0.0), S::Stick);
  EXPECT_EQ(contact.decide(S::Stick, 0.0, 1.0, 1e-300), S::SlipNegative);
  EXPECT_EQ(contact.decide(S::Stick, 0.0, 1.0, -1e-300), S::SlipPositive);
}

// A huge normal force never lets a finite load slip (no overflow in mu_s N).
TEST(CoulombContactDecide, HugeNormalForceNeverSlips) {
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  EXPECT_EQ(contact.decide(S::Stick, 0.0, 1e300, 1e299), S::Stick);
  EXPECT_EQ(contact.decide(S::Stick, 0.0, 1e300, -1e299), S::Stick);
}

TEST(CoulombContactDecide, RejectsNonFiniteInputsNamingThem) {
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid_argument([&] { contact.decide(S::Stick, nan, 1.0, 0.0); }, {"decide", "v"});
  expect_invalid_argument([&] { contact.decide(S::Stick, 0.0, inf, 0.0); }, {"decide", "N", "inf"});
  expect_invalid_argument([&] { contact.decide(S::Stick, 0.0, 1.0, -inf); },
                          {"decide", "f_stick_required"});
}

TEST(CoulombContact, RejectsNegativeVelocityTolerance) {
  expect_invalid_argument(
      [] { CoulombContact<CoulombLaw<double>>(CoulombLaw<double>(kMuS, kMuK), -1e-9); },
      {"CoulombContact", "velocity_tolerance"});
  EXPECT_NO_THROW(CoulombContact<CoulombLaw<double>>(CoulombLaw<double>(kMuS, kMuK), 0.0));
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(kMuS, kMuK));
  EXPECT_EQ(contact.velocity_tolerance(), std::sqrt(std::numeric_limits<double>::epsilon()));
}

// Guard counts, values and directions per state, written out from docs/contact.md.
TEST(CoulombContactGuards, ExactLawCountsValuesAndDirections) {
  using C = CoulombContact<CoulombLaw<double>>;
  const C contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  const double v = 0.25, N = 2.0, f = 0.4;  // capacity 1
  std::array<double, C::max_guards> g{};
  constexpr auto F = CrossingDirection::Falling, R = CrossingDirection::Rising;

  struct Row {
    S state;
    bool watch;
    Eigen::Index count;
    std::array<double, 3> values;
    std::array<CrossingDirection, 3> directions;
  };
  const std::array<Row, 8> rows = {{
      {S::Stick, false, 2, {0.6, 1.4, 0}, {F, F, F}},
      {S::Stick, true, 3, {0.6, 1.4, 2.0}, {F, F, F}},
      {S::SlipPositive, false, 1, {0.25, 0, 0}, {F, F, F}},
      {S::SlipPositive, true, 2, {0.25, 2.0, 0}, {F, F, F}},
      {S::SlipNegative, false, 1, {0.25, 0, 0}, {R, F, F}},
      {S::SlipNegative, true, 2, {0.25, 2.0, 0}, {R, F, F}},
      {S::LiftOff, false, 1, {2.0, 0, 0}, {R, F, F}},
      {S::LiftOff, true, 1, {2.0, 0, 0}, {R, F, F}},
  }};
  for (const Row& row : rows) {
    ASSERT_EQ(C::num_guards(row.state, row.watch), row.count) << row.state << " " << row.watch;
    ASSERT_LE(row.count, C::max_guards);
    g.fill(-99.0);
    contact.guards(row.state, v, N, f, row.watch, g.data());
    for (Eigen::Index i = 0; i < row.count; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_DOUBLE_EQ(g[k], row.values[k]) << row.state << " guard " << i;
      EXPECT_EQ(C::guard_direction(row.state, i, row.watch), row.directions[k])
          << row.state << " guard " << i;
    }
    for (auto k = static_cast<std::size_t>(row.count); k < g.size(); ++k)
      EXPECT_EQ(g[k], -99.0) << "guards() wrote past num_guards in " << row.state;
  }
}

TEST(CoulombContactGuards, RegularisedLawWatchesOnlyTheNormalForce) {
  using C = CoulombContact<RegularisedLaw<double>>;
  const C contact(RegularisedLaw<double>(kMuS, 1e-3), kTol);
  for (S s : {S::Stick, S::SlipPositive, S::SlipNegative}) {
    EXPECT_EQ(C::num_guards(s, false), 0);
    ASSERT_EQ(C::num_guards(s, true), 1);
    double g = 0.0;
    contact.guards(s, 0.1, 3.0, 0.2, true, &g);
    EXPECT_EQ(g, 3.0);
    EXPECT_EQ(C::guard_direction(s, 0, true), CrossingDirection::Falling);
  }
  EXPECT_EQ(C::num_guards(S::LiftOff, false), 1);
  EXPECT_EQ(C::guard_direction(S::LiftOff, 0, false), CrossingDirection::Rising);
}

// Each guard crossing, evaluated just past the crossing, leads decide() to the state the guard
// stands for: stick g0 -> slip negative, stick g1 -> slip positive, slip v -> stick (force inside
// the capacity) or reversal (force outside), N -> lift-off. Random normal forces and loads,
// fixed seed.
TEST(CoulombContactGuards, EveryCrossingLeadsToTheDocumentedState) {
  using C = CoulombContact<CoulombLaw<double>>;
  const C contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  const unsigned seed = 20240531u;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> normal(1e-3, 1e3), fraction(0.0, 0.999);
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::array<double, C::max_guards> g{};
  for (int trial = 0; trial < 200; ++trial) {
    const double N = normal(rng);
    const double cap = kMuS * N;
    const double past = cap * (1 + 1e-12);  // just beyond the capacity
    contact.guards(S::Stick, 0.0, N, past, true, g.data());
    ASSERT_LT(g[0], 0.0);
    EXPECT_EQ(contact.decide(S::Stick, 0.0, N, past), S::SlipNegative);
    contact.guards(S::Stick, 0.0, N, -past, true, g.data());
    ASSERT_LT(g[1], 0.0);
    EXPECT_EQ(contact.decide(S::Stick, 0.0, N, -past), S::SlipPositive);

    const double inside = (2 * fraction(rng) - 1) * cap;
    EXPECT_EQ(contact.decide(S::SlipPositive, -0.1 * kTol, N, inside), S::Stick);
    EXPECT_EQ(contact.decide(S::SlipNegative, 0.1 * kTol, N, inside), S::Stick);
    EXPECT_EQ(contact.decide(S::SlipPositive, -0.1 * kTol, N, past), S::SlipNegative);
    EXPECT_EQ(contact.decide(S::SlipNegative, 0.1 * kTol, N, -past), S::SlipPositive);
    EXPECT_EQ(contact.decide(S::SlipPositive, 0.5, -1e-12 * N, inside), S::LiftOff);
  }
}

TEST(CoulombContactForce, ExactLawsGiveKineticForceInSlipAndConstraintForceInStick) {
  const CoulombContact<CoulombLaw<double>> coulomb(CoulombLaw<double>(kMuS, kMuK), kTol);
  const double N = 2.0, f_req = 0.7;
  EXPECT_DOUBLE_EQ(coulomb.friction_force(S::SlipPositive, 0.3, N, f_req), -0.6);
  EXPECT_DOUBLE_EQ(coulomb.friction_force(S::SlipNegative, -0.3, N, f_req), 0.6);
  // The state, not the sign of v, sets the direction (v may overshoot at an event).
  EXPECT_DOUBLE_EQ(coulomb.friction_force(S::SlipPositive, -1e-12, N, f_req), -0.6);
  EXPECT_EQ(coulomb.friction_force(S::Stick, 0.0, N, f_req), f_req);
  EXPECT_EQ(coulomb.friction_force(S::LiftOff, 0.3, N, f_req), 0.0);
  EXPECT_DOUBLE_EQ(coulomb.stick_capacity(N), 1.0);

  const CoulombContact<StribeckLaw<double>> stribeck(StribeckLaw<double>(kMuS, kMuK, 0.1), kTol);
  const double mu = kMuK + (kMuS - kMuK) * std::exp(-1.0);  // |v| = v_s
  EXPECT_NEAR(stribeck.friction_force(S::SlipNegative, -0.1, N, f_req), mu * N, 1e-15);
  EXPECT_NEAR(stribeck.friction_force(S::SlipPositive, 0.1, N, f_req), -mu * N, 1e-15);
  EXPECT_EQ(stribeck.friction_force(S::Stick, 0.0, N, f_req), f_req);
}

TEST(CoulombContactForce, RegularisedLawIgnoresTheStateButLiftOff) {
  const RegularisedLaw<double> law(kMuS, 1e-3, RegularisedShape::Tanh);
  const CoulombContact<RegularisedLaw<double>> contact(law, kTol);
  for (S s : {S::Stick, S::SlipPositive, S::SlipNegative})
    for (double v : {-0.01, -2e-4, 0.0, 5e-4, 0.2})
      EXPECT_EQ(contact.friction_force(s, v, 2.0, 0.7), -law.coefficient(v) * 2.0);
  EXPECT_EQ(contact.friction_force(S::LiftOff, 0.2, 2.0, 0.7), 0.0);
}

// A slip state whose velocity guard fired is at v = 0 as located. decide() reads a
// leftover v above its tolerance as motion; decide_at_rest() applies rules 1, 3, 4 only.
TEST(CoulombContactDecide, AtRestIgnoresTheLeftoverVelocityOfAStop) {
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  const double N = 2.0, leftover = 10 * kTol;
  EXPECT_EQ(contact.decide(S::SlipNegative, leftover, N, 0.4), S::SlipPositive);  // the old misread
  EXPECT_EQ(contact.decide_at_rest(N, 0.4), S::Stick);
  EXPECT_EQ(contact.decide_at_rest(N, 1.0), S::Stick);           // closed set: at mu_s N
  EXPECT_EQ(contact.decide_at_rest(N, 1.5), S::SlipNegative);    // reversal: -sgn f
  EXPECT_EQ(contact.decide_at_rest(N, -1.5), S::SlipPositive);
  EXPECT_EQ(contact.decide_at_rest(0.0, 0.4), S::LiftOff);
  // decide(from, v, N, f) with |v| <= tol is decide_at_rest(N, f) on the whole table's f and N.
  for (double n : {2.0, 0.0, -1.0, 1e-300})
    for (double f : {0.0, 0.4, -0.4, 1.0, -1.0, 1.5, -1.5})
      EXPECT_EQ(contact.decide(S::SlipPositive, 0.5 * kTol, n, f), contact.decide_at_rest(n, f));
  const double inf = std::numeric_limits<double>::infinity();
  expect_invalid_argument([&] { contact.decide_at_rest(inf, 0.0); }, {"decide_at_rest", "N"});
  expect_invalid_argument([&] { contact.decide_at_rest(1.0, -inf); },
                          {"decide_at_rest", "f_stick_required"});
  const CoulombContact<RegularisedLaw<double>> smooth(
      RegularisedLaw<double>(kMuS, 1e-3, RegularisedShape::Tanh), kTol);
  EXPECT_EQ(smooth.decide_at_rest(N, 5.0), S::Stick);  // a label: no stick state to leave
}

TEST(CoulombContactDecide, VelocityGuardFiredOnlyForTheSlipVelocityGuard) {
  using C = CoulombContact<CoulombLaw<double>>;
  const stickslip::TriggeredGuards v_guard{0}, n_guard{1}, both{0, 1}, other_contact{3, 4};
  EXPECT_TRUE(C::velocity_guard_fired(S::SlipPositive, v_guard));
  EXPECT_TRUE(C::velocity_guard_fired(S::SlipNegative, both));
  EXPECT_FALSE(C::velocity_guard_fired(S::SlipNegative, n_guard));  // lift-off guard only
  EXPECT_FALSE(C::velocity_guard_fired(S::Stick, v_guard));         // stick: capacity guard 0
  EXPECT_FALSE(C::velocity_guard_fired(S::LiftOff, v_guard));
  // A contact whose guards start at index 3 of the system's guard vector.
  EXPECT_TRUE(C::velocity_guard_fired(S::SlipPositive, other_contact, 3));
  EXPECT_FALSE(C::velocity_guard_fired(S::SlipPositive, v_guard, 3));
  using R = CoulombContact<RegularisedLaw<double>>;  // no velocity guard at all
  EXPECT_FALSE(R::velocity_guard_fired(S::SlipPositive, v_guard));
}

// Guards() with a callable evaluates the stick force required in stick only, and
// gives the values of the scalar form.
TEST(CoulombContactGuards, RequiredForceIsEvaluatedInStickOnly) {
  const CoulombContact<CoulombLaw<double>> contact(CoulombLaw<double>(kMuS, kMuK), kTol);
  const double v = 0.3, N = 2.0, f_req = 0.7;
  int calls = 0;
  auto required = [&] {
    ++calls;
    return f_req;
  };
  for (S s : kAllStates)
    for (bool watch : {false, true}) {
      std::array<double, 3> lazy{}, eager{};
      calls = 0;
      contact.guards(s, v, N, required, watch, lazy.data());
      EXPECT_EQ(calls, s == S::Stick ? 1 : 0) << s;
      contact.guards(s, v, N, f_req, watch, eager.data());
      const auto n = static_cast<std::size_t>(CoulombContact<CoulombLaw<double>>::num_guards(s, watch));
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(lazy[i], eager[i]) << s << ", guard " << i;
    }
}

}  // namespace
}  // namespace contact_coulomb_contact_test

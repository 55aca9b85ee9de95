// orbit_contact_statistics: stick fraction and switches per contact of one period, on an orbit
// whose events are written by hand (the reference is the interval arithmetic of that timeline).

#include <stickslip/model/friction_damped_system.hpp>
#include <stickslip/steady_state.hpp>

#include <gtest/gtest.h>

namespace contact_statistics_test {
namespace {

using System = stickslip::FrictionDampedSystem<double>;
using stickslip::ContactState;

System::Mode mode_of(ContactState a, ContactState b) {
  System::Mode m(2);
  m[0] = a;
  m[1] = b;
  return m;
}

TEST(OrbitContactStatistics, StuckTimeAndSwitchesFollowTheEvents) {
  // t0 = 1, T = 2. Damper 0: Stick [1, 1.5], slip + (1.5, 2), slip - (2, 2.5), Stick [2.5, 3]:
  // stuck 1 of 2 s, three switches. Damper 1: slip until 2, Stick [2, 2.5], slip again: stuck
  // 0.5 of 2 s, two switches (the event at 1.5 does not change it). Sums and quotients of binary
  // fractions: exact.
  stickslip::PeriodicOrbit<System> orbit;
  orbit.t0 = 1;
  orbit.period = 2;
  const auto S = ContactState::Stick, P = ContactState::SlipPositive, N = ContactState::SlipNegative;
  orbit.mode = mode_of(S, P);
  orbit.events = {{1.5, mode_of(S, P), mode_of(P, P)},
                  {2.0, mode_of(P, P), mode_of(N, S)},
                  {2.5, mode_of(N, S), mode_of(S, P)}};
  const auto d0 = stickslip::orbit_contact_statistics(orbit, 0);
  const auto d1 = stickslip::orbit_contact_statistics(orbit, 1);
  EXPECT_EQ(d0.stick_fraction, 0.5);
  EXPECT_EQ(d0.switches, 3);  // S -> P -> N -> S
  EXPECT_EQ(d1.stick_fraction, 0.25);
  EXPECT_EQ(d1.switches, 2);
  // No event: the start state all period.
  orbit.events.clear();
  EXPECT_EQ(stickslip::orbit_contact_statistics(orbit, 0).stick_fraction, 1.0);
  EXPECT_EQ(stickslip::orbit_contact_statistics(orbit, 1).stick_fraction, 0.0);
  EXPECT_EQ(stickslip::orbit_contact_statistics(orbit, 1).switches, 0);
}

}  // namespace
}  // namespace contact_statistics_test

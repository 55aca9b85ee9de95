#include <stickslip/contact/contact_state.hpp>

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace contact_contact_state_test {  // named: the contact test files share one (unity) translation unit
namespace {

using stickslip::ContactState;

TEST(ContactState, NamesAreDistinctAndReadable) {
  EXPECT_STREQ(stickslip::to_string(ContactState::Stick), "stick");
  EXPECT_STREQ(stickslip::to_string(ContactState::SlipPositive), "slip_positive");
  EXPECT_STREQ(stickslip::to_string(ContactState::SlipNegative), "slip_negative");
  EXPECT_STREQ(stickslip::to_string(ContactState::LiftOff), "lift_off");
  std::ostringstream os;
  os << ContactState::SlipNegative;
  EXPECT_EQ(os.str(), "slip_negative");
}

TEST(ContactState, SlipSignIsTheSignOfTheSlidingVelocity) {
  EXPECT_EQ(stickslip::slip_sign(ContactState::SlipPositive), 1);
  EXPECT_EQ(stickslip::slip_sign(ContactState::SlipNegative), -1);
  EXPECT_EQ(stickslip::slip_sign(ContactState::Stick), 0);
  EXPECT_EQ(stickslip::slip_sign(ContactState::LiftOff), 0);
  EXPECT_TRUE(stickslip::is_slipping(ContactState::SlipPositive));
  EXPECT_FALSE(stickslip::is_slipping(ContactState::LiftOff));
  EXPECT_EQ(stickslip::slip_state(0.5), ContactState::SlipPositive);
  EXPECT_EQ(stickslip::slip_state(-1e-300), ContactState::SlipNegative);
  static_assert(stickslip::slip_sign(ContactState::SlipNegative) == -1, "constexpr");
}

}  // namespace
}  // namespace contact_contact_state_test

// blade_damper --compare: each variant spec changes exactly what it names in the base scene and
// run options, and a bad spec is refused naming it.
#include "blade_damper/blade_compare.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace blade_compare_test {

using namespace stickslip;

stickslip::RunOptions<double> base_run() {
  RunOptions<double> r;
  r.stepper.rtol = 1e-7;
  r.stepper.atol = 1e-10;
  return r;
}

TEST(BladeCompare, EachSpecChangesWhatItNames) {
  const blade::BladeParameters base;
  const auto run = base_run();
  const auto v = blade::parse_compare_list(
      "modes=3,rtol=1e-4,regularised=1e-3,constant-normal-load,fixed-contact,integrator=rk4:1e-4,"
      "integrator=exponential:1e-6,events=bisection,elements=10:4,damping=0.01",
      base, run);
  ASSERT_EQ(v.size(), 10u);
  EXPECT_EQ(v[0].params.modes, 3);
  EXPECT_EQ(v[0].run.stepper.rtol, run.stepper.rtol);  // nothing else changed
  EXPECT_EQ(v[1].run.stepper.rtol, 1e-4);
  EXPECT_DOUBLE_EQ(v[1].run.stepper.atol, 1e-7);
  EXPECT_EQ(v[1].params.modes, base.modes);
  EXPECT_EQ(v[2].params.regularised_v_eps, 1e-3);
  EXPECT_EQ(v[3].params.model.normal_load, NormalLoad::Constant);
  EXPECT_TRUE(v[3].params.model.moving_contact);
  EXPECT_FALSE(v[4].params.model.moving_contact);
  EXPECT_EQ(v[5].run.integrator, Integrator::RungeKutta4);
  EXPECT_EQ(v[5].run.stepper.fixed_step, 1e-4);
  EXPECT_EQ(v[5].run.stepper.rtol, run.stepper.rtol);
  EXPECT_EQ(v[6].run.integrator, Integrator::Exponential);
  EXPECT_EQ(v[6].run.stepper.rtol, 1e-6);
  EXPECT_EQ(v[7].run.stepper.event_location, EventLocation::Bisection);
  EXPECT_EQ(v[8].params.blade_elements, 10);
  EXPECT_EQ(v[8].params.platform_elements, 4);
  EXPECT_EQ(v[9].params.damping_ratio, 0.01);
  EXPECT_EQ(v[5].name, "integrator=rk4:1e-4");
}

TEST(BladeCompare, BadSpecsAreRefusedNamingThem) {
  const blade::BladeParameters base;
  const auto run = base_run();
  for (const std::string spec : {"modes", "rtol=abc", "rtol=1e-4x", "unknown=3", "fixed-contact=1",
                                 "elements=10:3", "elements=10", "events=never", "integrator=euler"}) {
    try {
      blade::parse_compare_variant(spec, base, run);
      ADD_FAILURE() << spec << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      // parse_integrator names its own parameter; every other message quotes the spec.
      if (spec != "integrator=euler") {
        EXPECT_NE(what.find(spec), std::string::npos) << what;
      }
    }
  }
  EXPECT_THROW(blade::parse_compare_list(",", base, run), std::invalid_argument);
}

}  // namespace blade_compare_test

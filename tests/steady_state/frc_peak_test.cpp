// The blade example's frc.json reports as a branch's peak the largest tip amplitude over its
// stable orbits: an unstable orbit of larger amplitude on the same branch (a point the structure
// leaves) does not set it.

#include "blade_damper/blade_frc.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace steady_state_frc_peak_test {  // named: the steady-state test files share one unity TU
namespace {

TEST(BladeFrcPeak, FrcJsonPeakIsTheLargestStableAmplitude) {
  blade::FrcBranch b;
  b.preload = 1;
  const double amplitude[3] = {1e-4, 5e-4, 2e-4};
  const bool stable[3] = {true, false, true};
  for (int k = 0; k < 3; ++k) {
    blade::FrcPoint pt;
    pt.preload = 1;
    pt.omega = 2 * M_PI * (30 + k);
    pt.tip_amplitude = amplitude[k];
    pt.stable = stable[k];
    b.points.push_back(pt);
  }
  const auto dir = std::filesystem::temp_directory_path() / "stickslip_frc_peak_test";
  std::filesystem::create_directories(dir);
  blade::write_frc(dir, blade::BladeParameters{}, blade::FrcSettings{}, {b});
  std::ifstream in(dir / "frc.json");
  std::stringstream text;
  text << in.rdbuf();
  const std::string json = text.str();
  const auto at = json.find("\"peak_tip_m\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_DOUBLE_EQ(std::stod(json.substr(at + 14)), 2e-4) << json;  // the stable point at 32 Hz
  const auto hz = json.find("\"peak_frequency_hz\": ");
  ASSERT_NE(hz, std::string::npos);
  EXPECT_NEAR(std::stod(json.substr(hz + 21)), 32, 1e-9);
  // No stable point: no peak reported.
  for (auto& pt : b.points) pt.stable = false;
  blade::write_frc(dir, blade::BladeParameters{}, blade::FrcSettings{}, {b});
  std::ifstream in2(dir / "frc.json");
  std::stringstream text2;
  text2 << in2.rdbuf();
  EXPECT_EQ(text2.str().find("peak_tip_m"), std::string::npos) << text2.str();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace steady_state_frc_peak_test

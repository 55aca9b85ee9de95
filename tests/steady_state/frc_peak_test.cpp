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

/// frc.json as write_frc writes it for the one branch `b` (in a temporary folder, removed after).
std::string frc_json(const blade::FrcBranch& b) {
  const auto dir = std::filesystem::temp_directory_path() / "stickslip_frc_peak_test";
  std::filesystem::create_directories(dir);
  blade::write_frc(dir, blade::BladeParameters{}, blade::FrcSettings{}, {b});
  std::ifstream in(dir / "frc.json");
  std::stringstream text;
  text << in.rdbuf();
  in.close();
  std::filesystem::remove_all(dir);
  return text.str();
}

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
  const std::string json = frc_json(b);
  const auto at = json.find("\"peak_tip_m\": ");
  ASSERT_NE(at, std::string::npos) << json;
  EXPECT_DOUBLE_EQ(std::stod(json.substr(at + 14)), 2e-4) << json;  // the stable point at 32 Hz
  const auto hz = json.find("\"peak_frequency_hz\": ");
  ASSERT_NE(hz, std::string::npos);
  EXPECT_NEAR(std::stod(json.substr(hz + 21)), 32, 1e-9);
  // No stable point: no peak reported.
  for (auto& pt : b.points) pt.stable = false;
  const std::string none = frc_json(b);
  EXPECT_EQ(none.find("peak_tip_m"), std::string::npos) << none;
}

// Every branch counts: a stable point of a subharmonic segment (period 2 T) above the period-1
// branch's stable points sets the peak, and frc.json says which kind and period it is and
// lists each segment with its own largest stable amplitude.
TEST(BladeFrcPeak, PeakOverEverySegmentNamesItsKindAndPeriod) {
  blade::FrcBranch b;
  b.preload = 26;
  const struct { double hz, tip; bool stable; int segment, period; const char* kind; } pts[] = {
      {58.40, 4.5e-3, true, 0, 1, "period_1"},        {58.46, 4.6e-3, false, 0, 1, "period_1"},
      {58.48, 4.7e-3, true, 1, 2, "subharmonic"},     {58.50, 4.68e-3, true, 1, 2, "subharmonic"},
      {58.52, 4.9e-3, false, 2, 2, "period_doubled"}};
  for (const auto& q : pts) {
    blade::FrcPoint pt;
    pt.preload = 26;
    pt.omega = 2 * M_PI * q.hz;
    pt.tip_amplitude = q.tip;
    pt.stable = q.stable;
    pt.segment = q.segment;
    pt.period = q.period;
    pt.kind = q.kind;
    b.points.push_back(pt);
  }
  const std::string json = frc_json(b);
  const auto number_after = [&json](const std::string& key, std::size_t from = 0) {
    const auto at = json.find("\"" + key + "\": ", from);
    EXPECT_NE(at, std::string::npos) << key << " in " << json;
    return at == std::string::npos ? -1.0 : std::stod(json.substr(at + key.size() + 4));
  };
  EXPECT_DOUBLE_EQ(number_after("peak_tip_m"), 4.7e-3) << json;  // the stable 2T point, not the unstable 4.9e-3
  EXPECT_NEAR(number_after("peak_frequency_hz"), 58.48, 1e-9);
  EXPECT_EQ(number_after("peak_period_T"), 2);
  EXPECT_NE(json.find("\"peak_kind\": \"subharmonic\""), std::string::npos) << json;
  // Per segment: kind, period, span and its largest stable amplitude (none for segment 2).
  const auto s1 = json.find("{\"segment\": 1, \"kind\": \"subharmonic\", \"period_T\": 2");
  ASSERT_NE(s1, std::string::npos) << json;
  EXPECT_DOUBLE_EQ(number_after("peak_stable_tip_m", s1), 4.7e-3);
  const auto s0 = json.find("{\"segment\": 0, \"kind\": \"period_1\", \"period_T\": 1");
  ASSERT_NE(s0, std::string::npos) << json;
  EXPECT_DOUBLE_EQ(number_after("peak_stable_tip_m", s0), 4.5e-3);
  const auto s2 = json.find("{\"segment\": 2, \"kind\": \"period_doubled\", \"period_T\": 2");
  ASSERT_NE(s2, std::string::npos) << json;
  const auto s2_end = json.find('}', s2);
  EXPECT_EQ(json.substr(s2, s2_end - s2).find("peak_stable_tip_m"), std::string::npos) << json;
  EXPECT_NE(json.substr(s2, s2_end - s2).find("\"stable_points\": 0"), std::string::npos) << json;
}

}  // namespace
}  // namespace steady_state_frc_peak_test

// Issue 37: the shipped trajectories, published as setpoints at 100 Hz
// (birotor-sim --publish-setpoints), pass the setpoint input untouched: the
// reference flown every control period (500 Hz cascade, 200 Hz mpc) equals
// the unshaped one bit for bit, and no period is limited. aggressive (0.94
// m/s per axis) and the identification figure-8 (1.71 m/s^2) are the fastest
// legitimate references.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "controller/setpoint_input.h"
#include "evaluation/control_cases.h"
#include "params/scenario_yaml.h"
#include "simulator/trajectory.h"

namespace birotor {
namespace {

std::string ConfigFile(const std::string& name) { return std::string(BIROTOR_SOURCE_DIR) + "/config/" + name; }

// Periods where the flown reference differs from the unshaped one.
// The figure-8 of the identification flights (tests/identification/
// flight_coverage_test.cc): 0.5 m legs in 1.3 s, 0.72 m/s and 1.71 m/s^2.
const char* kFigureEight =
    "trajectory.waypoints=[{start_s: 0.0, duration_s: 1.3, x_m: 0.5, z_m: 0.5}, "
    "{start_s: 1.3, duration_s: 1.3, x_m: 0.0, z_m: 0.75}, {start_s: 2.6, duration_s: 1.3, x_m: -0.5, z_m: 1.0}, "
    "{start_s: 3.9, duration_s: 1.3, x_m: -0.5, z_m: 0.5}, {start_s: 5.2, duration_s: 1.3, x_m: 0.0, z_m: 0.75}, "
    "{start_s: 6.5, duration_s: 1.3, x_m: 0.5, z_m: 1.0}]";

Scenario Named(const std::string& name) {
  if (name == "figure8") return LoadScenario(ConfigFile("scenarios/gentle.yaml"), {kFigureEight});
  return LoadScenario(ConfigFile("scenarios/" + name + ".yaml"));
}

int64_t ShapedPeriods(const Scenario& scenario, int64_t period_us, SetpointInput* input) {
  const std::string& scenario_name = scenario.name;
  const Trajectory trajectory(scenario);
  const SetpointParams params;
  input->SetStart(Eigen::Vector2d(scenario.start_position_m[0], scenario.start_position_m[1]));
  const int64_t end_us = std::llround(scenario.duration_s * 1e6);
  Setpoint newest;
  bool any = false;
  int64_t differing = 0;
  int32_t seq = 0;
  for (int64_t t = 0; t < end_us; t += 1000) {
    if (t % 10000 == 0) {
      newest = SetpointFromReference(trajectory.At(1e-6 * static_cast<double>(t)), t, seq++);
      EXPECT_TRUE(input->Offer(newest, t)) << scenario_name << " at " << t;
      any = true;
    }
    if (t % period_us != 0 || !any) continue;
    const double age_s = 1e-6 * static_cast<double>(t - newest.utime);
    const ReferencePoint unshaped = ReferenceFromSetpoint(newest, std::clamp(age_s, 0.0, params.max_extrapolation_s));
    const ReferencePoint flown = input->At(t, Eigen::Vector2d::Zero());
    if (flown.position_m != unshaped.position_m || flown.velocity_m_s != unshaped.velocity_m_s ||
        flown.acceleration_m_s2 != unshaped.acceleration_m_s2)
      ++differing;
  }
  return differing;
}

TEST(SetpointLegitTest, ShippedTrajectoriesPassUnshaped) {
  for (const char* name : {"gentle", "aggressive", "figure8", "gauge_drift", "flight_id", "density"}) {
    for (const int64_t period_us : {2000, 5000}) {
      SetpointInput input{SetpointParams()};
      EXPECT_EQ(ShapedPeriods(Named(name), period_us, &input), 0) << name << " every " << period_us << " us";
      EXPECT_EQ(input.counters().limited_periods, 0) << name;
      EXPECT_EQ(input.counters().accepted, input.counters().received) << name;
    }
  }
}

TEST(SetpointLegitTest, AggressiveLimitPassesUnshapedWithItsOwnLimits) {
  // Case aggressive_limit (10 m/s^2, 2.47 m/s per axis) flies with its
  // shaping opened to 3 m/s, 10.5 m/s^2 (evaluation/control_cases.cc).
  const ControlCase* c = FindControlCase("aggressive_limit");
  ASSERT_NE(c, nullptr);
  const ControllerConfig config = ControllerForCase(*c, ControllerConfig());
  const Scenario scenario = LoadScenario(ConfigFile("scenarios/" + c->scenario + ".yaml"), c->overrides);
  for (const int64_t period_us : {2000, 5000}) {
    SetpointInput input{config.setpoint};
    EXPECT_EQ(ShapedPeriods(scenario, period_us, &input), 0) << period_us;
    EXPECT_EQ(input.counters().limited_periods, 0) << period_us;
    EXPECT_EQ(input.counters().accepted, input.counters().received);
  }
}

}  // namespace
}  // namespace birotor

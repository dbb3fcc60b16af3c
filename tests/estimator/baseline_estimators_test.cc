// The baselines: the thesis's open-loop inversion reproduces its 0.017 N on
// noise-free data; the motor map is exact when the map is right.
#include "estimator/baseline_estimators.h"

#include <gtest/gtest.h>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

using testing_support::ForceMae;
using testing_support::ReferenceConfig;
using testing_support::RunScenario;
using testing_support::ScenarioFile;
using testing_support::ScenarioRun;

const std::vector<std::string> kNoiseFree = {"sensors.strain.noise_rad=0",      "sensors.motor.speed_noise_rad_s=0",
                                             "sensors.imu.gyro_noise_rad_s=0",  "sensors.imu.accel_noise_m_s2=0",
                                             "sensors.pose.position_noise_m=0", "sensors.pose.angle_noise_rad=0",
                                             "vehicle.turbulence_std=0"};

std::vector<std::string> With(std::vector<std::string> overrides, const std::string& extra) {
  overrides.push_back(extra);
  return overrides;
}

EstimatorConfig NoiseFreeInversion() {
  EstimatorConfig config = ReferenceConfig("inversion");
  config.inversion.window_samples = 3;
  return config;
}

TEST(InversionEstimatorTest, NoiseFreeHoverMatchesTheThesis) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("hover"), With(kNoiseFree, "scenario.duration_s=2")), NoiseFreeInversion());
  RecordProperty("mae_f1_n", std::to_string(ForceMae(run, 0, 10000)));
  EXPECT_LE(ForceMae(run, 0, 10000), 0.017);
  EXPECT_LE(ForceMae(run, 1, 10000), 0.017);
}

TEST(InversionEstimatorTest, NoiseFreeQuinticManoeuvreMatchesTheThesis) {
  // gentle (thesis test 2: a quintic to (0.5, 0.5)), made 3 s long.
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("gentle"),
                               With(With(kNoiseFree, "scenario.duration_s=4"),
                                    "trajectory.waypoints=[{start_s: 0.5, duration_s: 3.0, x_m: 0.5, z_m: 0.5}]")),
                  NoiseFreeInversion());
  RecordProperty("mae_f1_n", std::to_string(ForceMae(run, 0, 10000)));
  EXPECT_LE(ForceMae(run, 0, 10000), 0.017);
  EXPECT_LE(ForceMae(run, 1, 10000), 0.017);
}

TEST(MotorMapEstimatorTest, ExactWhenTheMapIsRight) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("hover"), With(kNoiseFree, "scenario.duration_s=2")),
                                      ReferenceConfig("motor_map"));
  // Telemetry is up to 2 ms older than the strain sample it is used for.
  EXPECT_LE(ForceMae(run, 0), 0.01);
  EXPECT_LE(ForceMae(run, 1), 0.01);
}

TEST(MotorMapEstimatorTest, FallsBackToTheMotorModelWithoutTelemetry) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("hover"),
                               With(With(kNoiseFree, "scenario.duration_s=2"), "sensors.motor.telemetry=false")),
                  ReferenceConfig("motor_map"));
  EXPECT_LE(ForceMae(run, 0, 100000), 0.02);
  EXPECT_LE(ForceMae(run, 1, 100000), 0.02);
}

}  // namespace
}  // namespace birotor

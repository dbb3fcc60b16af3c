// Tests of params/scenario_yaml.h: every reference scenario loads, bad
// files are refused with the file and the key named, overrides apply.
#include "params/scenario_yaml.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include "tests/simulator/test_support.h"

namespace birotor {
namespace {

// Message of the ParamError thrown by loading text (with overrides), or "".
std::string LoadError(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    LoadScenarioFromString(text, "bad.yaml", overrides);
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(ScenarioYamlTest, EveryReferenceScenarioLoads) {
  for (const char* name : {"hover", "gentle", "aggressive", "thrust_loss", "thrust_loss_severe", "density",
                           "sensor_faults", "bench", "flight_id"}) {
    const Scenario scenario = LoadScenario(ScenarioPath(name));
    EXPECT_EQ(scenario.name, name);
  }
  EXPECT_EQ(LoadScenario(ScenarioPath("bench")).mode, "bench");
  EXPECT_TRUE(LoadScenario(ScenarioPath("bench")).sensors.loadcell.enabled);
  const Scenario loss = LoadScenario(ScenarioPath("thrust_loss"));
  ASSERT_EQ(loss.faults.thrust_steps.size(), 1u);
  EXPECT_EQ(loss.faults.thrust_steps[0].rotor, 2);
  EXPECT_DOUBLE_EQ(loss.faults.thrust_steps[0].scale, 0.75);
  EXPECT_DOUBLE_EQ(LoadScenario(ScenarioPath("thrust_loss_severe")).faults.thrust_steps.at(0).scale, 0.6);
  EXPECT_DOUBLE_EQ(LoadScenario(ScenarioPath("density")).faults.initial_thrust_scale[1], 0.9);
}

TEST(ScenarioYamlTest, HoverHoldsTheReferenceVehicleAndSensors) {
  const Scenario s = LoadScenario(ScenarioPath("hover"));
  EXPECT_DOUBLE_EQ(s.vehicle.arms[0].stiffness_n_m_rad, 2628.0);  // reference-vehicle.md
  EXPECT_DOUBLE_EQ(s.step_s, 0.00025);
  EXPECT_DOUBLE_EQ(s.sensors.strain.rate_hz, 1000.0);
  EXPECT_DOUBLE_EQ(s.sensors.strain_noise_rad, 2e-5);
  EXPECT_DOUBLE_EQ(s.sensors.motor.rate_hz, 500.0);
  EXPECT_DOUBLE_EQ(s.sensors.pose.rate_hz, 100.0);
  EXPECT_FALSE(s.sensors.loadcell.enabled);
}

TEST(ScenarioYamlTest, EmptyOrPartialFileIsRefusedNamingEachMissingKey) {
  // Issue 14: an empty scenario file used to run as `hover`.
  const std::string empty = LoadError("");
  EXPECT_EQ(empty,
            "bad.yaml: missing 10 keys: scenario, vehicle, trajectory, bench, sensors, gauge, ground, faults, "
            "controller, esc (every key is required; the shipped reference files have them all)");
  const std::string partial = LoadError("scenario: {name: x, mode: flight, duration_s: 1, seed: 1, step_s: 0.001}\n");
  EXPECT_NE(partial.find("missing 10 keys: scenario.start_position_m, vehicle, trajectory,"), std::string::npos)
      << partial;
}

TEST(ScenarioYamlTest, DuplicateKeyIsRefused) {
  std::ifstream in(ScenarioPath("hover"));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(LoadError(text), "");
  const std::string error = LoadError(text + "controller:\n  rate_hz: 250\n");
  EXPECT_NE(error.find("bad.yaml: key 'controller': appears twice"), std::string::npos) << error;
}

TEST(ScenarioYamlTest, UnknownKeyIsRefusedNamingFileAndKey) {
  const std::string error = LoadError("sensors:\n  strain:\n    noise_rads: 1e-5\n");
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("sensors.strain.noise_rads"), std::string::npos) << error;
  EXPECT_NE(LoadError("scenaro:\n  name: x\n").find("'scenaro'"), std::string::npos);
}

TEST(ScenarioYamlTest, NegativeRateIsRefused) {
  const std::string error = LoadError("sensors:\n  imu: {rate_hz: -100}\n");
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("sensors.imu.rate_hz"), std::string::npos) << error;
}

TEST(ScenarioYamlTest, RateThatIsNotAWholeNumberOfStepsIsRefused) {
  const std::string error = LoadError("sensors:\n  strain: {rate_hz: 1500}\n");
  EXPECT_NE(error.find("sensors.strain.rate_hz"), std::string::npos) << error;
}

// sensors.strain.stamp_jitter_s (the mismatch cases' 50 us): 0 by default,
// refused below 0 and above a tenth of the 1 kHz period (1e-4 s), naming
// the file, the key and the range.
TEST(ScenarioYamlTest, StrainStampJitterIsReadAndRangeChecked) {
  EXPECT_EQ(LoadScenario(ScenarioPath("gentle")).sensors.strain_stamp_jitter_s, 0.0);
  const Scenario s = LoadScenario(ScenarioPath("gentle"), {"sensors.strain.stamp_jitter_s=5.0e-5"});
  EXPECT_DOUBLE_EQ(s.sensors.strain_stamp_jitter_s, 5e-5);
  for (const char* bad : {"-1.0e-6", "2.0e-4"}) {
    const std::string error = LoadError("sensors:\n  strain: {stamp_jitter_s: " + std::string(bad) + "}\n");
    EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
    EXPECT_NE(error.find("sensors.strain.stamp_jitter_s"), std::string::npos) << error;
    EXPECT_NE(error.find("0.0001"), std::string::npos) << error;
  }
  // At 500 Hz the limit is 2e-4 s.
  EXPECT_DOUBLE_EQ(
      LoadScenario(ScenarioPath("gentle"), {"sensors.strain.rate_hz=500", "sensors.strain.stamp_jitter_s=2.0e-4"})
          .sensors.strain_stamp_jitter_s,
      2e-4);
}

TEST(ScenarioYamlTest, FaultTimePastTheEndIsRefused) {
  const std::string base = "scenario: {duration_s: 10}\n";
  std::string error = LoadError(base + "faults:\n  thrust_steps:\n    - {time_s: 12, rotor: 2, scale: 0.75}\n");
  EXPECT_NE(error.find("bad.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("faults.thrust_steps[0].time_s"), std::string::npos) << error;
  error = LoadError(base + "faults:\n  strain_nan_times_s: [3, 11]\n");
  EXPECT_NE(error.find("faults.strain_nan_times_s"), std::string::npos) << error;
  error = LoadError(base + "faults:\n  motor_telemetry_gap: {start_s: 10.5, duration_s: 1}\n");
  EXPECT_NE(error.find("faults.motor_telemetry_gap.start_s"), std::string::npos) << error;
}

TEST(ScenarioYamlTest, BadFileOnDiskIsRefusedNamingTheFile) {
  try {
    LoadScenario("/nonexistent/scenario.yaml");
    FAIL() << "no error";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.yaml"), std::string::npos);
  }
}

TEST(ScenarioYamlTest, OverridesApplyOnTopOfTheFileAndAreValidated) {
  const Scenario s =
      LoadScenario(ScenarioPath("gentle"), {"sensors.strain.noise_rad=0", "scenario.seed=99",
                                            "faults.strain_nan_times_s=[1.5, 2.5]", "vehicle.turbulence_std=0"});
  EXPECT_EQ(s.sensors.strain_noise_rad, 0.0);
  EXPECT_EQ(s.seed, 99u);
  EXPECT_EQ(s.faults.strain_nan_times_s.size(), 2u);
  EXPECT_EQ(s.vehicle.turbulence_std, 0.0);
  EXPECT_EQ(s.trajectory.waypoints.size(), 1u);  // untouched parts of the file stay

  const std::string unknown = LoadError("", {"sensors.strain.noise=1"});
  EXPECT_NE(unknown.find("sensors.strain.noise"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("--set"), std::string::npos) << unknown;
  EXPECT_NE(LoadError("", {"sensors.pose.rate_hz=-1"}).find("sensors.pose.rate_hz"), std::string::npos);
  EXPECT_NE(LoadError("", {"no_equals_sign"}).find("no_equals_sign"), std::string::npos);
}

TEST(ScenarioYamlTest, ParameterFileBecomesOverrides) {
  const std::string path = ::testing::TempDir() + "scenario_yaml_test_params.yaml";
  std::ofstream(path) << "vehicle:\n  arm_stiffness_n_m_rad: 2500\nsensors:\n  strain: {noise_rad: 0}\n"
                         "faults:\n  thrust_steps:\n    - {time_s: 3, rotor: 1, scale: 0.8}\n";
  const std::vector<std::string> overrides = OverridesFromFile(path);
  EXPECT_EQ(overrides.size(), 3u);
  const Scenario s = LoadScenario(ScenarioPath("hover"), overrides);
  EXPECT_EQ(s.vehicle.arms[0].stiffness_n_m_rad, 2500.0);
  EXPECT_EQ(s.vehicle.body_mass_kg, 4.0);
  EXPECT_EQ(s.sensors.strain_noise_rad, 0.0);
  EXPECT_TRUE(s.sensors.strain.enabled);
  ASSERT_EQ(s.faults.thrust_steps.size(), 1u);
  EXPECT_EQ(s.faults.thrust_steps[0].rotor, 1);
  EXPECT_EQ(s.faults.thrust_steps[0].scale, 0.8);
  std::remove(path.c_str());
}

// Read for a vehicle of three arms: the per-arm lists take three numbers,
// or the two equal numbers of the birotor's files (every arm takes them),
// and a fault may name rotor 3, which the birotor refuses with the file,
// the key and the range.
TEST(ScenarioYamlTest, PerArmListsAndRotorsFollowTheVehiclesArmCount) {
  const Scenario tri = LoadScenario(ScenarioPath("density"), {"gauge.offset_rad=[1.0e-5, 2.0e-5, 3.0e-5]"}, 3);
  EXPECT_EQ(tri.arm_count, 3);
  EXPECT_DOUBLE_EQ(tri.gauge.offset_rad[2], 3.0e-5);
  EXPECT_DOUBLE_EQ(tri.faults.initial_thrust_scale[2], 0.9);  // [0.9, 0.9] for every arm
  const std::string rotor3 = "faults.thrust_steps=[{time_s: 1.0, rotor: 3, scale: 0.8}]";
  EXPECT_EQ(LoadScenario(ScenarioPath("hover"), {rotor3}, 3).faults.thrust_steps.at(0).rotor, 3);
  try {
    LoadScenario(ScenarioPath("hover"), {rotor3});
    FAIL() << "rotor 3 accepted on the birotor";
  } catch (const ParamError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("hover.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("key 'faults.thrust_steps[0].rotor'"), std::string::npos) << what;
    EXPECT_NE(what.find("[1, 2]"), std::string::npos) << what;
  }
  try {
    LoadScenario(ScenarioPath("hover"), {"gauge.scale=[1.03, 0.98]"}, 3);
    FAIL() << "two different numbers accepted for three arms";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'gauge.scale'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("3 numbers, or 2 equal ones"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LoadScenario(ScenarioPath("hover"), {"gauge.scale=[1.0, 1.0, 1.0]"}), ParamError);  // birotor: 2
  EXPECT_THROW(LoadScenario(ScenarioPath("hover"), {}, 7), ParamError);                            // kMaxArms = 6
}

}  // namespace
}  // namespace birotor

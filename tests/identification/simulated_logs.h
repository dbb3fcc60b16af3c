// Test data for the identification tests: runs the project's simulator on a
// scenario file with overrides and collects its samples into a SensorLog.
#pragma once

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "params/scenario_yaml.h"
#include "samples/sample_sink.h"
#include "samples/sensor_log.h"
#include "simulator/simulator.h"

namespace birotor::testing {

class CollectingSink : public SampleSink {
 public:
  explicit CollectingSink(SensorLog* log) : log_(log) {}
  void OnStrain(const StrainSample& s) override { log_->strain.push_back(s); }
  void OnMotor(const MotorSample& s) override { log_->motor.push_back(s); }
  void OnImu(const ImuSample& s) override { log_->imu.push_back(s); }
  void OnPose(const PoseSample& s) override { log_->pose.push_back(s); }
  void OnLoadCell(const LoadCellSample& s) override { log_->loadcell.push_back(s); }
  void OnTruth(const TruthSample& s) override { log_->truth.push_back(s); }

 private:
  SensorLog* log_;
};

inline std::string ScenarioPath(const std::string& name) {
  return std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

// Simulates config/scenarios/<name>.yaml with the overrides; *truth gets the
// scenario's vehicle.
inline SensorLog SimulateScenario(const std::string& name, const std::vector<std::string>& overrides,
                                  BirotorParams* truth = nullptr) {
  const Scenario scenario = LoadScenario(ScenarioPath(name), overrides);
  if (truth != nullptr) *truth = BirotorModelOf(scenario.vehicle);
  SensorLog log;
  log.source = name;
  CollectingSink sink(&log);
  Simulator simulator(scenario);
  simulator.Run(&sink);
  return log;
}

// Uniform in [lo, hi) from the raw generator (portable, unlike the std distributions).
inline double Uniform(std::mt19937* rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>((*rng)()) / 4294967296.0);
}

// Scenario overrides that fly vehicle v (its identified parameters k, d,
// m_p, c_T, tau_m) with the true gauge (scale, offset) for duration_s with seed.
inline std::vector<std::string> VehicleOverrides(const BirotorParams& v, double duration_s, int seed,
                                                 const double gauge_scale[2], const double gauge_offset_rad[2]) {
  std::vector<std::string> overrides;
  auto add = [&](const char* format, double a, double b = 0.0) {
    char text[160];
    std::snprintf(text, sizeof(text), format, a, b);
    overrides.push_back(text);
  };
  add("scenario.duration_s=%.10g", duration_s);
  add("scenario.seed=%.10g", seed);
  add("vehicle.arm_stiffness_n_m_rad=%.10g", v.arm_stiffness_n_m_rad);
  add("vehicle.arm_damping_n_m_s_rad=%.10g", v.arm_damping_n_m_s_rad);
  add("vehicle.tip_mass_kg=%.10g", v.tip_mass_kg);
  add("vehicle.thrust_coeff_n_s2_rad2=%.10g", v.thrust_coeff_n_s2_rad2);
  add("vehicle.motor_time_constant_s=%.10g", v.motor_time_constant_s);
  add("gauge.scale=[%.10g, %.10g]", gauge_scale[0], gauge_scale[1]);
  add("gauge.offset_rad=[%.10g, %.10g]", gauge_offset_rad[0], gauge_offset_rad[1]);
  return overrides;
}

}  // namespace birotor::testing

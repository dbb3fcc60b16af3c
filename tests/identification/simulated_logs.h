// Test data for the identification tests: runs the project's simulator on a
// scenario file with overrides and collects its samples into a SensorLog.
#pragma once

#include <string>
#include <vector>

#include "params/scenario_yaml.h"
#include "samples/sensor_log.h"
#include "simulator/sample_sink.h"
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
                                  VehicleParams* truth = nullptr) {
  const Scenario scenario = LoadScenario(ScenarioPath(name), overrides);
  if (truth != nullptr) *truth = scenario.vehicle;
  SensorLog log;
  log.source = name;
  CollectingSink sink(&log);
  Simulator simulator(scenario);
  simulator.Run(&sink);
  return log;
}

}  // namespace birotor::testing

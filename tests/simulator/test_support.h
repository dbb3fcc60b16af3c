// Helpers shared by the simulator tests: a sink that keeps every sample and
// the path of the repository's scenario files.
#pragma once

#include <string>
#include <vector>

#include "samples/sample_sink.h"

namespace birotor {

inline std::string ScenarioPath(const std::string& name) {
  return std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

struct CollectingSink : SampleSink {
  std::vector<StrainSample> strain;
  std::vector<MotorSample> motor;
  std::vector<ImuSample> imu;
  std::vector<PoseSample> pose;
  std::vector<LoadCellSample> loadcell;
  std::vector<TruthSample> truth;
  void OnStrain(const StrainSample& s) override { strain.push_back(s); }
  void OnMotor(const MotorSample& s) override { motor.push_back(s); }
  void OnImu(const ImuSample& s) override { imu.push_back(s); }
  void OnPose(const PoseSample& s) override { pose.push_back(s); }
  void OnLoadCell(const LoadCellSample& s) override { loadcell.push_back(s); }
  void OnTruth(const TruthSample& s) override { truth.push_back(s); }
};

// Only truth, for closed-loop checks.
struct TruthSink : SampleSink {
  std::vector<TruthSample> truth;
  void OnTruth(const TruthSample& s) override { truth.push_back(s); }
};

}  // namespace birotor

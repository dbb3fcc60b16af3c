// Helpers shared by the simulator tests: a sink that keeps every sample, the
// path of the repository's scenario files, and running birotor-sim.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "samples/sample_sink.h"

namespace birotor {

inline std::string ScenarioPath(const std::string& name) {
  return std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/" + name + ".yaml";
}

// The whole file as bytes ("" when it cannot be read).
inline std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Runs program with args (a shell command line) and stderr into stderr_path,
// read into *err (may be null) and removed; the exit status, -1 when the
// program did not exit.
inline int RunProgram(const std::string& program, const std::string& args, const std::string& stderr_path,
                      std::string* err) {
  const std::string command = program + " " + args + " 2> " + stderr_path;
  const int status = std::system(command.c_str());
  if (err) *err = ReadFileBytes(stderr_path);
  std::remove(stderr_path.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
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

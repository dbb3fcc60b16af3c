#include "tools/eval_multi_arm_accuracy.h"

#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "evaluation/multi_arm_accuracy.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "program/config_files.h"
#include "program/program_options.h"

namespace birotor {
namespace {

// The description, or false after its one-line error.
bool LoadVehicle(const std::string& file, VehicleDescription* vehicle) {
  try {
    *vehicle = LoadVehicleDescription(file);
  } catch (const std::exception& e) {
    ReportError(e.what());
    return false;
  }
  return true;
}

}  // namespace

int RunMultiArmAccuracyMode(const std::string& vehicle_file, const std::vector<std::string>& scenarios,
                            bool scenarios_named, const std::vector<std::string>& methods,
                            const std::vector<std::string>& overrides, const EstimatorConfig& estimator,
                            const EvalOptions& options) {
  VehicleDescription vehicle;
  if (!LoadVehicle(vehicle_file, &vehicle)) return kExitFailure;
  // Every scenario loaded for the vehicle's arms before anything is flown.
  std::vector<std::pair<std::string, Scenario>> flights;
  std::string skipped;  // after the table: default scenarios that do not fit the vehicle
  for (const std::string& name : scenarios) {
    std::string file, error;
    if (!FindScenario(name, &file, &error)) return ReportError(error);
    try {
      flights.emplace_back(name, LoadScenario(file, overrides, vehicle.arm_count));
    } catch (const std::exception& e) {
      if (scenarios_named) return ReportError(name + ": " + e.what());
      skipped += "skipped: " + name + ": " + e.what() + " (fly it with --scenarios " + name + " --set KEY=[...])\n";
    }
  }
  std::printf("N-arm estimator on %s (%d arms)\n\n%s", vehicle.name.c_str(), vehicle.arm_count,
              MultiArmAccuracyHeader().c_str());
  std::string ground_notes;  // after the table: the estimates before lift-off
  for (const auto& [name, scenario] : flights) {
    // Without --methods: the parameter file's estimator.method (the daemon's).
    for (const std::string& method : methods.empty() ? std::vector<std::string>{estimator.method} : methods) {
      try {
        EstimatorConfig config = estimator;
        config.method = method;
        const MultiArmAccuracy result = RunMultiArmAccuracy(vehicle, scenario, config, options);
        std::printf("%s", MultiArmAccuracyRow(name, method, result).c_str());
        std::fflush(stdout);
        if (result.before_liftoff > 0) {
          ground_notes += name + ", " + method + ": scored from lift-off; before it " +
                          std::to_string(result.before_liftoff) + " estimates, " +
                          std::to_string(result.before_liftoff_valid_beyond_3sigma) +
                          " VALID with a rotor more than 3 sigma off\n";
        }
      } catch (const std::exception& e) {
        return ReportError(name + ", " + method + ": " + e.what());
      }
    }
  }
  if (!ground_notes.empty()) std::printf("\n%s", ground_notes.c_str());
  if (!skipped.empty()) std::printf("\n%s", skipped.c_str());
  return 0;
}

int RunMultiArmLogAccuracy(const std::string& vehicle_file, const std::string& log_path, const std::string& prefix,
                           const EvalOptions& options) {
  VehicleDescription vehicle;
  if (!LoadVehicle(vehicle_file, &vehicle)) return kExitFailure;
  MultiArmAccuracy result;
  std::string error;
  if (!ScoreMultiArmLog(log_path, prefix, vehicle.arm_count, options, &result, &error)) return ReportError(error);
  std::printf("FORCE_N of %s against its TRUTH_N (%s, %d arms)\n\n%s%s", log_path.c_str(), vehicle.name.c_str(),
              vehicle.arm_count, MultiArmAccuracyHeader().c_str(),
              MultiArmAccuracyRow(log_path, "FORCE_N", result).c_str());
  return 0;
}

}  // namespace birotor

#include "tools/eval_multi_arm_accuracy.h"

#include <cstdio>
#include <exception>

#include "evaluation/multi_arm_accuracy.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "program/config_files.h"
#include "program/program_options.h"

namespace birotor {

int RunMultiArmAccuracyMode(const std::string& vehicle_file, const std::vector<std::string>& scenarios,
                            const std::vector<std::string>& overrides, const EkfOptions& ekf,
                            const EvalOptions& options) {
  VehicleDescription vehicle;
  try {
    vehicle = LoadVehicleDescription(vehicle_file);
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
  std::printf("N-arm EKF on %s (%d arms)\n\n%s", vehicle.name.c_str(), vehicle.arm_count,
              MultiArmAccuracyHeader().c_str());
  for (const std::string& name : scenarios) {
    std::string file, error;
    if (!FindScenario(name, &file, &error)) return ReportError(error);
    try {
      const Scenario scenario = LoadScenario(file, overrides, vehicle.arm_count);
      const MultiArmAccuracy result = RunMultiArmAccuracy(vehicle, scenario, ekf, options);
      std::printf("%s", MultiArmAccuracyRow(name, result).c_str());
      std::fflush(stdout);
    } catch (const std::exception& e) {
      return ReportError(name + ": " + e.what());
    }
  }
  return 0;
}

}  // namespace birotor

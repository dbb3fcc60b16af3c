// The shipped files the N-arm estimator tests read from the source tree
// (BIROTOR_SOURCE_DIR, the SOURCE_TREE option of birotor_add_test): a vehicle
// description, the estimator file and a scenario for a given arm count.
#pragma once

#include <string>
#include <vector>

#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"

namespace birotor {

inline std::string SourceFile(const std::string& relative) { return std::string(BIROTOR_SOURCE_DIR) + "/" + relative; }
// config/vehicles/<name>.yaml
inline VehicleDescription Vehicle(const std::string& name) {
  return LoadVehicleDescription(SourceFile("config/vehicles/" + name + ".yaml"));
}
// config/estimator.yaml
inline EstimatorConfig Config() { return LoadEstimatorConfig(SourceFile("config/estimator.yaml")); }
// config/scenarios/<name>.yaml with --set overrides, for a vehicle of `arms` arms.
inline Scenario ScenarioFor(const std::string& name, const std::vector<std::string>& overrides, int arms) {
  return LoadScenario(SourceFile("config/scenarios/" + name + ".yaml"), overrides, arms);
}

}  // namespace birotor

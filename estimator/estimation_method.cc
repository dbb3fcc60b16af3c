#include "estimator/estimation_method.h"

#include <stdexcept>

#include "estimator/baseline_estimators.h"
#include "estimator/ekf_force_estimator.h"
#include "estimator/linear_force_estimator.h"
#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_inversion.h"
#include "estimator/multi_arm_linear_estimator.h"

namespace birotor {
namespace {

struct MethodEntry {
  EstimationMethod method;
  const char* name;
  std::unique_ptr<ForceEstimator> (*make)(const EstimatorConfig& config);
  // For config.vehicle of any arm count; nullptr: no N-arm version. Null
  // for an arm count outside 2 .. kMaxArms.
  std::unique_ptr<MultiArmForceEstimator> (*make_multi_arm)(const EstimatorConfig& config);
};

// The registry: one row per method, in EstimationMethod order. A new method
// is a row here and an enumerator (docs/estimator.md).
const MethodEntry kMethods[kNumEstimationMethods] = {
    {EstimationMethod::kEkf, "ekf",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<EkfForceEstimator>(BirotorModelOf(c.vehicle), c.ekf);
     },
     [](const EstimatorConfig& c) { return MakeMultiArmEkf(c.vehicle, c.ekf); }},
    {EstimationMethod::kLinearKf, "linear_kf",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<LinearForceEstimator>(BirotorModelOf(c.vehicle), c.ekf, c.linear_model);
     },
     [](const EstimatorConfig& c) { return MakeMultiArmLinearEstimator(c.vehicle, c.ekf, c.linear_model, nullptr); }},
    {EstimationMethod::kLuenberger, "luenberger",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<LinearForceEstimator>(BirotorModelOf(c.vehicle), c.ekf, c.linear_model, c.luenberger);
     },
     [](const EstimatorConfig& c) {
       return MakeMultiArmLinearEstimator(c.vehicle, c.ekf, c.linear_model, &c.luenberger);
     }},
    {EstimationMethod::kInversion, "inversion",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<InversionEstimator>(BirotorModelOf(c.vehicle), c.inversion);
     },
     [](const EstimatorConfig& c) -> std::unique_ptr<MultiArmForceEstimator> {
       if (c.vehicle.arm_count < 2 || c.vehicle.arm_count > kMaxArms) return nullptr;
       return std::make_unique<MultiArmInversion>(c.vehicle, c.inversion);
     }},
    {EstimationMethod::kMotorMap, "motor_map",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<MotorMapEstimator>(BirotorModelOf(c.vehicle), c.motor_map);
     },
     nullptr},
};

}  // namespace

const std::vector<std::string>& EstimationMethodNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const MethodEntry& entry : kMethods) out.emplace_back(entry.name);
    return out;
  }();
  return names;
}

const char* EstimationMethodName(EstimationMethod method) {
  const int index = static_cast<int>(method);
  return index >= 0 && index < kNumEstimationMethods ? kMethods[index].name : "?";
}

bool ParseEstimationMethod(const std::string& name, EstimationMethod* method) {
  for (const MethodEntry& entry : kMethods) {
    if (name == entry.name) {
      *method = entry.method;
      return true;
    }
  }
  return false;
}

std::unique_ptr<ForceEstimator> MakeForceEstimator(EstimationMethod method, const EstimatorConfig& config) {
  const int index = static_cast<int>(method);
  if (index < 0 || index >= kNumEstimationMethods) return nullptr;
  return kMethods[index].make(config);
}

std::unique_ptr<ForceEstimator> MakeForceEstimator(const EstimatorConfig& config) {
  EstimationMethod method;
  if (!ParseEstimationMethod(config.method, &method)) return nullptr;
  return MakeForceEstimator(method, config);
}

std::unique_ptr<MultiArmForceEstimator> MakeMultiArmForceEstimator(EstimationMethod method,
                                                                   const EstimatorConfig& config) {
  const int index = static_cast<int>(method);
  if (index < 0 || index >= kNumEstimationMethods) throw std::invalid_argument("no such estimation method");
  const MethodEntry& entry = kMethods[index];
  if (entry.make_multi_arm == nullptr) {
    throw std::invalid_argument(std::string("estimator.method ") + entry.name +
                                " has no N-arm version (--vehicle: ekf, linear_kf, luenberger, inversion)");
  }
  std::unique_ptr<MultiArmForceEstimator> out = entry.make_multi_arm(config);
  if (out == nullptr) {
    throw std::invalid_argument(std::string("estimator.method ") + entry.name + ": no N-arm version for a vehicle of " +
                                std::to_string(config.vehicle.arm_count) + " arms (2 to " + std::to_string(kMaxArms) +
                                ")");
  }
  return out;
}

std::unique_ptr<MultiArmForceEstimator> MakeMultiArmForceEstimator(const EstimatorConfig& config) {
  EstimationMethod method;
  if (!ParseEstimationMethod(config.method, &method)) {
    throw std::invalid_argument("estimator.method " + config.method + " is not a method");
  }
  return MakeMultiArmForceEstimator(method, config);
}

}  // namespace birotor

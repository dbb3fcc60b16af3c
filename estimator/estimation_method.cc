#include "estimator/estimation_method.h"

#include "estimator/baseline_estimators.h"
#include "estimator/ekf_force_estimator.h"
#include "estimator/linear_force_estimator.h"

namespace birotor {
namespace {

struct MethodEntry {
  EstimationMethod method;
  const char* name;
  std::unique_ptr<ForceEstimator> (*make)(const EstimatorConfig& config);
};

// The registry: one row per method, in EstimationMethod order. A new method
// is a row here and an enumerator (docs/estimator.md).
const MethodEntry kMethods[kNumEstimationMethods] = {
    {EstimationMethod::kEkf, "ekf",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<EkfForceEstimator>(BirotorModelOf(c.vehicle), c.ekf);
     }},
    {EstimationMethod::kLinearKf, "linear_kf",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<LinearForceEstimator>(BirotorModelOf(c.vehicle), c.ekf, c.linear_model);
     }},
    {EstimationMethod::kLuenberger, "luenberger",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<LinearForceEstimator>(BirotorModelOf(c.vehicle), c.ekf, c.linear_model, c.luenberger);
     }},
    {EstimationMethod::kInversion, "inversion",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<InversionEstimator>(BirotorModelOf(c.vehicle), c.inversion);
     }},
    {EstimationMethod::kMotorMap, "motor_map",
     [](const EstimatorConfig& c) -> std::unique_ptr<ForceEstimator> {
       return std::make_unique<MotorMapEstimator>(BirotorModelOf(c.vehicle), c.motor_map);
     }},
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

}  // namespace birotor

// The estimation methods as an enum with one registry: each method's name
// (the `estimator.method` key, --method), and its factory. The only place a
// method name is compared with a string; the pipeline, the tools and the
// benchmark hold an EstimationMethod.
#pragma once

#include <memory>
#include <string>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"

namespace birotor {

// In the order of the thesis's ladder and the evaluation table.
enum class EstimationMethod : int {
  kEkf = 0,         // "ekf": the extended Kalman filter (ekf_force_estimator.h)
  kLinearKf = 1,    // "linear_kf": Kalman filter on the linear hover model (linear_force_estimator.h)
  kLuenberger = 2,  // "luenberger": fixed-gain observer on the same model
  kInversion = 3,   // "inversion": the thesis's open-loop inversion (baseline_estimators.h)
  kMotorMap = 4,    // "motor_map": nominal map f = c_T omega^2
};
constexpr int kNumEstimationMethods = 5;

const char* EstimationMethodName(EstimationMethod method);
// The method named `name` (one of EstimationMethodNames()); false if none.
bool ParseEstimationMethod(const std::string& name, EstimationMethod* method);

// Creates `method` with its options from config (config.method is not read).
std::unique_ptr<ForceEstimator> MakeForceEstimator(EstimationMethod method, const EstimatorConfig& config);
// Creates the method named in config.method; nullptr for an unknown name
// (the config loader refuses such names earlier).
std::unique_ptr<ForceEstimator> MakeForceEstimator(const EstimatorConfig& config);

}  // namespace birotor

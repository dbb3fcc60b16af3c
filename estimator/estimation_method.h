// The estimation methods as an enum with one registry: each method's name
// (the `estimator.method` key, --method), its factory for the birotor and
// its factory for a described vehicle of N arms (--vehicle). The only place a
// method name is compared with a string; the pipeline, the tools and the
// benchmark hold an EstimationMethod.
#pragma once

#include <memory>
#include <string>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"

namespace birotor {

class MultiArmForceEstimator;  // estimator/multi_arm_ekf.h

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

// The N-arm version of `method` for config.vehicle (2 .. kMaxArms arms),
// with the same options (config.ekf, linear_model, luenberger, inversion).
// Throws std::invalid_argument naming the method when it has no N-arm
// version (motor_map) or cannot serve the vehicle (its arm count, a model
// check of the method).
std::unique_ptr<MultiArmForceEstimator> MakeMultiArmForceEstimator(EstimationMethod method,
                                                                   const EstimatorConfig& config);
// The N-arm version of the method named in config.method; throws
// std::invalid_argument for an unknown name too.
std::unique_ptr<MultiArmForceEstimator> MakeMultiArmForceEstimator(const EstimatorConfig& config);

}  // namespace birotor

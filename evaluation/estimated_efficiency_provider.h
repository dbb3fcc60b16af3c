// The N-arm estimator (estimator/multi_arm_pipeline.h: admission, resets and
// status around the EKF of estimator/multi_arm_ekf.h, the code of
// birotor-estimator --vehicle) as the efficiency source of the N-rotor
// lock-step loop: fed every STRAIN_N, MOTOR_N, IMU and POSE sample the
// simulator emits, in its order, and its newest estimate handed to the
// controller once per control period. The controller then flies what the
// estimator says, not the truth: the product path of force feedback.
#pragma once

#include <cstdint>

#include "controller/multi_arm_controller.h"
#include "estimator/estimator_config.h"
#include "estimator/multi_arm_pipeline.h"
#include "evaluation/multi_arm_closed_loop.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"

namespace birotor {

// Each rotor's mu_i with the sigma of its force turned into the sigma of
// mu_i (the same relative sigma: f_i = mu_i c_T,i omega_i^2 with omega_i
// read much better than f_i), VALID and the rotor-fault bits as published.
RotorEfficiencyEstimate EfficiencyOf(const MultiArmForceEstimate& estimate);

class EstimatedEfficiencyProvider : public EfficiencyProvider {
 public:
  // config: the estimator's (ekf:, pipeline:); its vehicle is replaced by
  // vehicle. Throws std::invalid_argument as MultiArmPipeline does.
  EstimatedEfficiencyProvider(const VehicleDescription& vehicle, EstimatorConfig config);

  void OnStrainN(const MultiArmStrainSample& sample) override;
  void OnMotorN(const MultiArmMotorSample& sample) override { pipeline_.OnMotor(sample); }
  void OnImu(const ImuSample& sample) override { pipeline_.OnImu(sample); }
  void OnPose(const PoseSample& sample) override { pipeline_.OnPose(sample); }
  bool Latest(int64_t now_us, RotorEfficiencyEstimate* estimate) override;

  // Every estimate of the flight so far (one per strain sample).
  int64_t estimates() const { return estimates_; }

 private:
  static EstimatorConfig WithVehicle(EstimatorConfig config, const VehicleDescription& vehicle) {
    config.vehicle = vehicle;
    return config;
  }

  MultiArmPipeline pipeline_;
  MultiArmForceEstimate newest_;
  int64_t estimates_ = 0;
  bool fresh_ = false;
};

}  // namespace birotor

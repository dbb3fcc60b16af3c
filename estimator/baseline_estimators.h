// The two baselines the EKF must beat, behind the ForceEstimator interface:
// the thesis's open-loop model inversion (thesis section 5.2, eq. 5.1-5.2)
// and the nominal motor map f = c_T omega^2.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/motor_speed_tracker.h"

namespace birotor {

// Open-loop inversion of the linear arm model about hover, in the thesis's
// coordinates b_s = b1 + b2, b_d = b1 - b2 (eq. 5.1, with the printed typos
// fixed: stiffness multiplies b, not b_dot; damping included):
//   [bs_dd; bd_dd] = A2 [bs; bd - bd0; bs_dot; bd_dot] + B2 [f1 - f0; f2 - f0]
// solved for f (eq. 5.2). b, b_dot and b_ddot come from a causal least-squares
// quadratic fit over the newest window_samples strain samples, evaluated at
// the newest one.
class InversionEstimator : public ForceEstimator {
 public:
  static constexpr int kMaxWindow = 64;

  InversionEstimator(const BirotorParams& params, const InversionOptions& options);
  const char* Name() const override { return "inversion"; }

 private:
  void DoReset() override;
  // Telemetry is used as the rotor speed of thrust_scale: reported fused.
  void DoAddMotor(const MotorSample& sample) override;
  void DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) override;

  BirotorParams params_;
  InversionOptions options_;
  MotorSpeedTracker motor_;
  Eigen::Matrix<double, 2, 4> a2_;  // rows bs_dd, bd_dd; columns bs, bd, bs_dot, bd_dot
  Eigen::Matrix2d b2_inverse_;      // (d[bs_dd; bd_dd] / d[f1; f2])^-1
  double bd0_rad_ = 0;              // b_d at hover
  double bs0_rad_ = 0;              // b_s at hover
  double f0_n_ = 0;                 // hover force per rotor
  // Ring buffer of the newest strain samples.
  int64_t utime_[kMaxWindow] = {};
  double deflection_rad_[kMaxWindow][2] = {};
  int head_ = 0;  // next slot to write
  int count_ = 0;
};

// f_i = c_T omega_i^2 with omega from telemetry (else the motor model);
// thrust_scale 1 by construction.
class MotorMapEstimator : public ForceEstimator {
 public:
  MotorMapEstimator(const BirotorParams& params, const MotorMapOptions& options);
  const char* Name() const override { return "motor_map"; }

 private:
  void DoReset() override { motor_.Reset(); }
  // Telemetry is the rotor speed of the map: reported fused. The strain
  // gauges are not used: each strain sample is reported not fused.
  void DoAddMotor(const MotorSample& sample) override;
  void DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) override;

  BirotorParams params_;
  MotorMapOptions options_;
  MotorSpeedTracker motor_;
};

}  // namespace birotor

// The thesis's open-loop inversion (thesis section 5.2, eq. 5.1-5.2) for any
// described vehicle (N = 2 .. kMaxArms arms, a gauge on each): the arm rows of
// the N-arm linear model about hover (model/multi_arm_linearization.h),
//   b_ddot = A_bb (b - b_hover) + A_bd b_dot + B (f - f_hover),
// solved for f, with b, b_dot and b_ddot from a causal least-squares
// quadratic fit over the newest window_samples strain samples at the newest
// one: InversionEstimator (estimator/baseline_estimators.h) generalised,
// which it reproduces on the birotor description (there in the sum and
// difference coordinates, the same equations after a change of basis). Its
// sigma is inversion.force_std_n, the birotor's convention (no covariance);
// it raises no rotor-fault flag (no uncertainty to judge one with), as the
// birotor's. Its fusion reports (reports()) are the birotor's: each strain
// sample fused and each MOTOR_N with telemetry on every rotor fused, none
// with an innovation (it has none to judge), for ESTIMATOR_STATUS's counts.
// Fixed-size storage: no heap per sample.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_linear_speed.h"
#include "estimator/step_fusion_reports.h"

namespace birotor {

class MultiArmInversion : public MultiArmForceEstimator {
 public:
  static constexpr int kMaxWindow = 64;

  // Throws std::invalid_argument for an arm without a gauge or a singular B.
  MultiArmInversion(const VehicleDescription& vehicle, const InversionOptions& options);

  int arm_count() const override { return n_; }
  void Reset() override;
  // Rotor speeds for the thrust efficiency.
  void AddMotor(const MultiArmMotorSample& sample) override;
  void AddImu(const ImuSample& /*sample*/) override {}
  void AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) override;
  double force_std_n(int /*rotor*/) const override { return options_.force_std_n; }
  const MultiArmFilterFacts& facts() const override { return facts_; }
  const FusionReports* reports() const override { return reports_.reports(); }

 private:
  using ArmMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxArms, kMaxArms>;
  using ArmVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxArms, 1>;

  // b (row 0) [rad], b_dot (row 1) [rad/s], b_ddot (row 2) [rad/s^2] of each arm (column).
  void FitWindow(int64_t utime, Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxArms>* derivatives) const;

  int n_;
  VehicleDescription vehicle_;
  InversionOptions options_;
  MultiArmSpeedTracker motor_;
  ArmMatrix a_deflection_;  // A_bb = d b_ddot / d b [1/s^2]
  ArmMatrix a_rate_;        // A_bd = d b_ddot / d b_dot [1/s]
  ArmMatrix b_inverse_;     // (d b_ddot / d f)^-1 [N s^2/rad]
  ArmVector deflection_hover_rad_;
  ArmVector force_hover_n_;
  // Ring buffer of the newest calibrated strain samples.
  std::array<int64_t, kMaxWindow> utime_{};
  std::array<ArmValues, kMaxWindow> deflection_rad_{};
  int head_ = 0;  // next slot to write
  int count_ = 0;
  MultiArmFilterFacts facts_;
  StepFusionReports reports_;
};

}  // namespace birotor

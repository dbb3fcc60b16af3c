// The extended Kalman filter that estimates each rotor's thrust and its
// efficiency mu_i against the nominal map from the strain gauges, with the
// motor commands as inputs and motor telemetry and gyro as extra measurements.
#pragma once

#include <cstdint>

#include "estimator/ekf_model.h"
#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/ground_contact.h"

namespace birotor {

class EkfForceEstimator : public ForceEstimator {
 public:
  EkfForceEstimator(const VehicleParams& params, const EkfOptions& options);

  const char* Name() const override { return "ekf"; }
  void Reset() override;
  void AddMotor(const MotorSample& sample) override;
  void AddImu(const ImuSample& sample) override;
  void AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainUpdateInfo* info) override;

  bool initialized() const { return initialized_; }
  const EkfState& state() const { return state_; }
  const EkfMatrix& covariance() const { return covariance_; }
  const EkfProcessModel& process_model() const { return process_; }
  const GroundContact& ground_contact() const { return contact_; }

 private:
  // Motor command in effect at time utime (zero-order hold of the newest
  // command not newer than utime).
  EkfInput CommandAt(int64_t utime) const;
  void Initialize(const StrainSample& sample);
  void Predict(double dt_s, const EkfInput& input);
  void FuseTelemetry(int64_t utime);
  void FuseGyro();
  // Strain update with the chi-square gate; fills info.
  void FuseStrain(const StrainSample& sample, StrainUpdateInfo* info);
  // Symmetrises P and applies the variance floors and ceilings; false if the
  // state or covariance is not finite (or a variance is negative).
  bool ConditionCovariance();
  void UpdateFaults(int64_t utime);
  void FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate);

  VehicleParams params_;
  EkfOptions options_;
  EkfProcessModel process_;
  StrainMeasurementModel strain_model_;
  MotorSpeedMeasurementModel motor_model_;
  GyroMeasurementModel gyro_model_;
  GroundContact contact_;        // from the IMU: selects the supported-body model
  EkfMatrix process_noise_psd_;  // diagonal Qc; Q = Qc dt

  bool initialized_ = false;
  bool converged_ = false;
  int64_t last_utime_ = 0;
  EkfState state_;
  EkfMatrix covariance_;
  int consecutive_gated_ = 0;

  // Two newest motor samples (commands and telemetry).
  bool has_motor_ = false;
  bool has_previous_motor_ = false;
  MotorSample motor_;
  MotorSample previous_motor_;
  bool telemetry_pending_ = false;
  bool gyro_pending_ = false;
  double gyro_rad_s_ = 0;

  // Rotor fault detection with persistence and hysteresis.
  bool fault_[2] = {false, false};
  int64_t below_since_utime_[2] = {-1, -1};
};

}  // namespace birotor

// The two middle steps of the thesis's plan (section 5.4.2 and 7.3.1) behind
// the ForceEstimator interface, on the linear hover model with the forces as
// random-walk states (estimator/linear_force_model.h):
//   "luenberger": fixed gain by pole placement (estimator/luenberger_gain.h);
//   "linear_kf":  Kalman filter, gain from the propagated covariance.
// Both fuse the gyro (phi_dot) when IMU samples arrive and ekf.use_gyro is
// set; the observer uses it only for phi_dot (estimator/luenberger_gain.h).
// The model is discretised at the strain period, so the newest gyro sample is
// fused at the next strain sample's time (an older one it replaces is
// reported not fused). Both propagate the error covariance with the same
// model and noise (for the observer: through its own error dynamics, Joseph
// form for its fixed gain), which gives force_std_n and the gates of the
// strain (ekf.strain_gate_nis) and gyro (ekf.gyro_gate_nis) innovations;
// after ekf.gate_consecutive_limit rejections in a row the strain inflates
// the forces' variance, the gyro the pitch rate's, and each is fused.
// Telemetry is the rotor speed of thrust_scale (MotorSpeedTracker): reported
// fused, as by the baselines.
#pragma once

#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/force_estimator.h"
#include "estimator/kalman_fusion.h"
#include "estimator/linear_force_model.h"
#include "estimator/luenberger_gain.h"
#include "estimator/motor_speed_tracker.h"

namespace birotor {

class LinearForceEstimator : public ForceEstimator {
 public:
  // Linear Kalman filter ("linear_kf").
  LinearForceEstimator(const BirotorParams& params, const EkfOptions& noise, const LinearModelOptions& options);
  // Luenberger observer ("luenberger").
  LinearForceEstimator(const BirotorParams& params, const EkfOptions& noise, const LinearModelOptions& options,
                       const LuenbergerOptions& observer);

  const char* Name() const override { return kalman_ ? "linear_kf" : "luenberger"; }
  // Strain and gyro with the EKF's gates; telemetry is used without an update.
  double Gate(FusionSource source) const override;

  const LinearForceModel& model() const { return model_; }
  // The observer's fixed gains (physical units); unused by the Kalman filter.
  const ObserverGains& fixed_gains() const { return fixed_gains_; }
  // State and covariance in physical units (deviation from hover).
  LinearState state() const { return scale_.asDiagonal() * state_; }
  LinearMatrix covariance() const { return scale_.asDiagonal() * covariance_ * scale_.asDiagonal(); }

 private:
  void DoReset() override;
  void DoAddMotor(const MotorSample& sample) override;
  void DoAddImu(const ImuSample& sample) override;
  void DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) override;
  void Initialize(const StrainSample& sample);
  void Predict(int periods);
  // The pending gyro sample's update, gated; reported.
  void UpdateGyro();
  // The strain update with its gate and the inflation after persistent
  // rejection; returns what happened.
  FusionReport UpdateStrain(const StrainSample& sample);
  // The forces, their sigmas and thrust scales, and the filter facts.
  void FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate, FilterStatusFacts* facts);

  bool kalman_;
  EkfOptions noise_;
  LinearForceModel model_;
  MotorSpeedTracker motor_;
  // Everything below runs in scaled coordinates x = diag(scale_) x_s, y = scale_(b) y_s,
  // so that every matrix is O(1) (the physical one spans 1e-10 to 1e2).
  LinearState scale_;
  LinearMatrix a_;                          // A_d
  LinearMatrix q_;                          // Q_d
  ObserverGains fixed_gains_;               // physical units
  LinearGain fixed_gain_s_;                 // strain, scaled
  LinearGyroGain fixed_gyro_gain_s_;        // gyro, scaled
  Eigen::Matrix2d strain_noise_;            // R / scale_b^2, both gauges [1]
  Eigen::Matrix<double, 1, 1> gyro_noise_;  // R_gyro / scale_phi_dot^2 [1]
  GateWithInflation strain_gate_;           // strain gate and its inflation policy
  GateWithInflation gyro_gate_;             // gyro gate; a lost pitch rate is inflated by its initial variance
  double pitch_rate_variance_s_ = 0;        // initial_pitch_rate_std_rad_s^2 / scale_phi_dot^2 [1]
  bool gyro_pending_ = false;
  ImuSample gyro_;  // the pending gyro sample

  bool initialized_ = false;
  bool converged_ = false;
  int64_t last_utime_ = 0;
  LinearState state_;
  LinearMatrix covariance_;
};

}  // namespace birotor

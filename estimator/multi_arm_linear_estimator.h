// The linear Kalman filter ("linear_kf") and the Luenberger observer
// ("luenberger") for any described vehicle (N = 2 .. kMaxArms arms), on the
// N-arm linear hover model with the forces as random-walk states
// (estimator/multi_arm_linear_model.h): LinearForceEstimator
// (estimator/linear_force_estimator.h) generalised, one class with a gain
// policy (the Kalman gain, or the observer's fixed gain of
// estimator/multi_arm_luenberger.h), which reproduces it on the birotor
// description. The gauges are calibrated with the description's s_i, o_i
// (z = (raw - o) / s, as the N-arm EKF); an arm without a reading is not
// fused. The thrust efficiency is f_i / (c_T,i omega_i^2) with the speeds of
// MultiArmSpeedTracker, and the rotor-fault flags of MultiArmFaultMonitor are
// judged from it, its covariance var(mu) = var(f) / (c_T,i omega_i^2)^2. A
// template on N (fixed sizes, no heap per sample) behind MultiArmForceEstimator.
//
// Fusion reports (reports()), as LinearForceEstimator's, for the pipeline's
// model-consistency monitor and ESTIMATOR_STATUS's counts: the strain (an
// arm without a reading has variance 0: left out) and the gyro with their
// innovations in physical units, gated; telemetry with finite speeds on
// every rotor as fused without an innovation (it only feeds the
// efficiency); a gyro sample replaced before it was fused, or dropped by a
// reset, as not fused. reports() holds what happened from the call after
// the previous AddStrain up to the newest AddStrain (the AddMotor and
// AddImu between them, then the strain step).
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "estimator/estimator_config.h"
#include "estimator/kalman_fusion.h"
#include "estimator/multi_arm_ekf.h"
#include "estimator/multi_arm_fault_monitor.h"
#include "estimator/multi_arm_linear_model.h"
#include "estimator/multi_arm_linear_speed.h"
#include "estimator/step_fusion_reports.h"

namespace birotor {

template <int N>
class MultiArmLinearEstimator : public MultiArmForceEstimator {
 public:
  using Layout = MultiArmLinearLayout;
  static constexpr int kSize = Layout::StateSize(N);
  using State = Eigen::Matrix<double, kSize, 1>;
  using Matrix = Eigen::Matrix<double, kSize, kSize>;
  using StrainGain = Eigen::Matrix<double, kSize, N>;
  using GyroGain = Eigen::Matrix<double, kSize, 1>;

  // The Kalman filter ("linear_kf"); vehicle.arm_count must be N.
  MultiArmLinearEstimator(const VehicleDescription& vehicle, const EkfOptions& noise,
                          const LinearModelOptions& options);
  // The Luenberger observer ("luenberger").
  MultiArmLinearEstimator(const VehicleDescription& vehicle, const EkfOptions& noise, const LinearModelOptions& options,
                          const LuenbergerOptions& observer);

  int arm_count() const override { return N; }
  void Reset() override;
  // Rotor speeds for the thrust efficiency (no update).
  void AddMotor(const MultiArmMotorSample& sample) override;
  // The newest gyro sample is fused at the next strain sample's time.
  void AddImu(const ImuSample& sample) override;
  void AddStrain(const MultiArmStrainSample& sample, MultiArmForceEstimate* estimate) override;
  double force_std_n(int rotor) const override { return force_std_n_[static_cast<size_t>(rotor)]; }
  const MultiArmFilterFacts& facts() const override { return facts_; }
  const FusionReports* reports() const override { return reports_.reports(); }
  // The ground holds the body: the newest forces below half the hover's
  // (the gyro is then not fused, and the arm-mode test waits).
  bool body_supported() const override { return supported_; }
  // The strain's and the gyro's NIS gates (ekf.strain_gate_nis,
  // ekf.gyro_gate_nis); NaN for telemetry and the accelerometer (not gated).
  double Gate(FusionSource source) const override;

  const MultiArmLinearForceModel& model() const { return model_; }
  // State and covariance in physical units (deviation from hover).
  State state() const { return scale_.asDiagonal() * state_; }
  Matrix covariance() const { return scale_.asDiagonal() * covariance_ * scale_.asDiagonal(); }

 private:
  // The pending gyro sample, dropped unfused (a reset, a newer sample).
  void DropPendingGyro();
  void Initialize(const MultiArmStrainSample& sample);
  void Predict(int periods);
  void UpdateGyro();
  // Scaled deviations of the calibrated readings and which arms are read.
  void ScaledStrain(const MultiArmStrainSample& sample, Eigen::Matrix<double, N, 1>* z,
                    std::array<bool, N>* measured) const;
  FusionReport UpdateStrain(const MultiArmStrainSample& sample);
  void UpdateFaults(int64_t utime);
  void FillEstimate(const MultiArmStrainSample& sample, bool gated, MultiArmForceEstimate* estimate);

  bool kalman_;
  VehicleDescription vehicle_;
  EkfOptions noise_;
  MultiArmLinearForceModel model_;
  MultiArmSpeedTracker motor_;
  // Scaled coordinates x = diag(scale_) x_s (linear_force_estimator.h).
  State scale_;
  Matrix a_;                      // A_d
  Matrix q_;                      // Q_d
  StrainGain fixed_gain_s_;       // the observer's L, scaled
  GyroGain fixed_gyro_gain_s_;    // the observer's L_g, scaled
  double strain_variance_s_ = 0;  // R / scale_b^2 per gauge [1]
  Eigen::Matrix<double, 1, 1> gyro_noise_;
  GateWithInflation strain_gate_;
  GateWithInflation gyro_gate_;       // a lost pitch rate: inflated by its initial variance
  double pitch_rate_variance_s_ = 0;  // initial_pitch_rate_std_rad_s^2, scaled [1]
  bool gyro_pending_ = false;
  ImuSample gyro_;
  MultiArmFaultMonitor faults_;

  bool initialized_ = false;
  bool converged_ = false;
  bool supported_ = false;
  int64_t last_utime_ = 0;
  State state_;
  Matrix covariance_;
  std::array<double, N> force_std_n_{};
  MultiArmFilterFacts facts_;
  StepFusionReports reports_;
};

// The Kalman filter or (observer not null) the Luenberger observer for the
// description's arm count (2 .. kMaxArms); null outside. Throws
// std::invalid_argument as the model and the pole placement do.
std::unique_ptr<MultiArmForceEstimator> MakeMultiArmLinearEstimator(const VehicleDescription& vehicle,
                                                                    const EkfOptions& noise,
                                                                    const LinearModelOptions& options,
                                                                    const LuenbergerOptions* observer);

extern template class MultiArmLinearEstimator<2>;
extern template class MultiArmLinearEstimator<3>;
extern template class MultiArmLinearEstimator<4>;
extern template class MultiArmLinearEstimator<5>;
extern template class MultiArmLinearEstimator<6>;

}  // namespace birotor

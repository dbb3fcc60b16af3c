#include "estimator/linear_force_estimator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "estimator/filter_status.h"
#include "estimator/luenberger_gain.h"

namespace birotor {
namespace {

constexpr double kMicrosecond = 1e-6;
using OutputMatrix = Eigen::Matrix2d;

}  // namespace

LinearForceEstimator::LinearForceEstimator(const VehicleParams& params, const EkfOptions& noise,
                                           const LinearModelOptions& options)
    : kalman_(true), noise_(noise), model_(BuildLinearForceModel(params, noise, options)), motor_(params) {
  scale_ = model_.scale;
  const LinearMatrix s_inv = scale_.cwiseInverse().asDiagonal();
  a_ = s_inv * model_.a_discrete * scale_.asDiagonal();
  q_ = s_inv * model_.noise_discrete * s_inv;
  const double deflection_scale = scale_(kLinDeflection1);
  measurement_variance_ = (noise.strain_noise_rad / deflection_scale) * (noise.strain_noise_rad / deflection_scale);
  const double gyro_std = noise.gyro_noise_rad_s / scale_(kLinPitchRate);
  gyro_variance_ = gyro_std * gyro_std;
  fixed_gains_.strain.setZero();
  fixed_gains_.gyro.setZero();
  fixed_gain_s_.setZero();
  fixed_gyro_gain_s_.setZero();
  state_.setZero();
  covariance_.setIdentity();
}

LinearForceEstimator::LinearForceEstimator(const VehicleParams& params, const EkfOptions& noise,
                                           const LinearModelOptions& options, const LuenbergerOptions& observer)
    : LinearForceEstimator(params, noise, options) {
  kalman_ = false;
  fixed_gains_ = PlaceObserverPoles(model_, observer);
  // Scaled: x_s += diag(1/scale) L scale_y y_s.
  fixed_gain_s_ = scale_.cwiseInverse().asDiagonal() * fixed_gains_.strain * scale_(kLinDeflection1);
  fixed_gyro_gain_s_ = scale_.cwiseInverse().asDiagonal() * fixed_gains_.gyro * scale_(kLinPitchRate);
}

void LinearForceEstimator::AddMotor(const MotorSample& sample) {
  motor_.AddMotor(sample);
  if (std::isfinite(sample.omega_meas_rad_s[0]) && std::isfinite(sample.omega_meas_rad_s[1])) {
    Report(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
  }
}

void LinearForceEstimator::AddImu(const ImuSample& sample) {
  if (!noise_.use_gyro || !std::isfinite(sample.gyro_y_rad_s)) {
    Report(MakeFusionReport(FusionSource::kGyro, sample.utime, FusionOutcome::kNotFused));
    return;
  }
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_ = sample;
  gyro_pending_ = true;
}

void LinearForceEstimator::Reset() {
  motor_.Reset();
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_pending_ = false;
  initialized_ = false;
  converged_ = false;
  consecutive_gated_ = 0;
}

void LinearForceEstimator::Initialize(const StrainSample& sample) {
  // Deflections from the sample, rates 0, forces at hover; the EKF's initial
  // uncertainties (thrust scale sigma at the hover force).
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < 2; ++i) {
    state_(kLinDeflectionIndex[i]) =
        (sample.deflection_rad[i] - model_.deflection_hover_rad[i]) / scale_(kLinDeflection1);
    covariance_(kLinDeflectionIndex[i], kLinDeflectionIndex[i]) = measurement_variance_;
    const double rate_std = noise_.initial_deflection_rate_std_rad_s / scale_(kLinDeflectionRate1);
    covariance_(kLinDeflectionRate1 + i, kLinDeflectionRate1 + i) = rate_std * rate_std;
    const double force_std = noise_.initial_thrust_scale_std * model_.force_hover_n[i] / scale_(kLinForceIndex[i]);
    covariance_(kLinForceIndex[i], kLinForceIndex[i]) = force_std * force_std;
  }
  const double pitch_rate_std = noise_.initial_pitch_rate_std_rad_s / scale_(kLinPitchRate);
  covariance_(kLinPitchRate, kLinPitchRate) = pitch_rate_std * pitch_rate_std;
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_pending_ = false;
  consecutive_gated_ = 0;
  converged_ = false;
  last_utime_ = sample.utime;
  initialized_ = true;
}

void LinearForceEstimator::Predict(int periods) {
  // x = A_d x, P = A_d P A_d^T + Q_d, once per strain period.
  LinearMatrix temp;
  for (int k = 0; k < periods; ++k) {
    state_ = a_ * state_;
    temp.noalias() = a_.lazyProduct(covariance_);
    covariance_.noalias() = temp.lazyProduct(a_.transpose());
    covariance_ += q_;
  }
}

void LinearForceEstimator::UpdateGyro() {
  if (!gyro_pending_) return;
  gyro_pending_ = false;
  // y = phi_dot_meas - phi_dot, s = P_ww + R; gain K = P c^T / s (Kalman) or L_g.
  const double residual = gyro_.gyro_y_rad_s / scale_(kLinPitchRate) - state_(kLinPitchRate);
  const LinearGyroGain p_ct = covariance_.col(kLinPitchRate);
  const double innovation_variance = p_ct(kLinPitchRate) + gyro_variance_;
  FusionReport report;
  report.source = FusionSource::kGyro;
  report.utime = gyro_.utime;
  report.size = 1;
  report.innovation(0) = residual * scale_(kLinPitchRate);
  report.innovation_covariance(0, 0) = innovation_variance * scale_(kLinPitchRate) * scale_(kLinPitchRate);
  report.nis = residual * residual / innovation_variance;
  report.gate = noise_.gyro_gate_nis;
  if (!(report.nis <= report.gate)) {  // a NaN NIS is rejected too
    report.outcome = FusionOutcome::kRejectedGate;
    Report(report);
    return;
  }
  const LinearGyroGain gain = kalman_ ? LinearGyroGain(p_ct / innovation_variance) : fixed_gyro_gain_s_;
  state_.noalias() += gain * residual;
  // Joseph form for any gain (see UpdateStrain).
  const LinearGyroGain half = 0.5 * innovation_variance * gain - p_ct;
  LinearMatrix delta;
  delta.noalias() = half.lazyProduct(gain.transpose());
  covariance_ += delta + delta.transpose();
  report.outcome = FusionOutcome::kFused;
  Report(report);
}

FusionReport LinearForceEstimator::UpdateStrain(const StrainSample& sample) {
  // Innovation y = z - C x, S = C P C^T + R (C selects the deflections).
  Eigen::Vector2d residual;
  for (int i = 0; i < 2; ++i) {
    residual(i) = (sample.deflection_rad[i] - model_.deflection_hover_rad[i]) / scale_(kLinDeflection1) -
                  state_(kLinDeflectionIndex[i]);
  }
  const LinearGain p_ct = covariance_.leftCols<kLinearOutputSize>();
  OutputMatrix innovation_covariance = p_ct.topRows<kLinearOutputSize>();
  innovation_covariance.diagonal().array() += measurement_variance_;
  const OutputMatrix innovation_inverse = innovation_covariance.inverse();
  const double deflection_scale = scale_(kLinDeflection1);
  FusionReport report;
  report.source = FusionSource::kStrain;
  report.utime = sample.utime;
  report.size = kLinearOutputSize;
  report.innovation = residual * deflection_scale;
  report.innovation_covariance = innovation_covariance * (deflection_scale * deflection_scale);
  report.nis = residual.dot(innovation_inverse * residual);
  report.gate = noise_.strain_gate_nis;
  if (!(report.nis <= report.gate)) {  // a NaN NIS is rejected too
    ++consecutive_gated_;
    if (consecutive_gated_ < noise_.gate_consecutive_limit) {
      report.outcome = FusionOutcome::kRejectedGate;
      return report;
    }
    // A persistent change is real: open up the forces (the EKF's inflation of
    // var(mu_i), at the hover force), then fuse.
    for (int i = 0; i < 2; ++i) {
      const double extra = noise_.gate_inflation_thrust_scale_std * model_.force_hover_n[i] / scale_(kLinForceIndex[i]);
      covariance_(kLinForceIndex[i], kLinForceIndex[i]) += extra * extra;
    }
    report.fused_after_inflation = true;
  }
  consecutive_gated_ = 0;
  LinearGain gain;
  if (kalman_) {
    gain.noalias() = p_ct * innovation_inverse;  // K = P C^T S^-1
  } else {
    gain = fixed_gain_s_;  // L by pole placement
  }
  state_.noalias() += gain * residual;
  // Joseph form for any gain: (I - K C) P (I - K C)^T + K R K^T
  //   = P - K (P C^T)^T - (P C^T) K^T + K S K^T (the inflation changes only
  // the force variances, not P C^T or S).
  const LinearGain k_s = gain * innovation_covariance;
  const LinearGain half = 0.5 * k_s - p_ct;
  LinearMatrix delta;
  delta.noalias() = half.lazyProduct(gain.transpose());
  covariance_ += delta + delta.transpose();
  report.outcome = FusionOutcome::kFused;
  return report;
}

void LinearForceEstimator::FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate) {
  for (int i = 0; i < 2; ++i) {
    const int f = kLinForceIndex[i];
    const double force = model_.force_hover_n[i] + scale_(f) * state_(f);
    estimate->force_n[i] = force;
    estimate->force_std_n[i] = scale_(f) * std::sqrt(std::max(covariance_(f, f), 0.0));
    estimate->thrust_scale[i] = motor_.ThrustScale(i, force);
  }
  SetFilterStatus(sample, noise_.converged_force_std_n, gated, motor_.has_motor(), &converged_, estimate);
}

void LinearForceEstimator::AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) {
  *info = StrainStepInfo();
  motor_.Advance(sample.utime);
  // At (re-)initialisation the state is set from the sample: fused, without an innovation.
  FusionReport strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
  if (!initialized_) {
    Initialize(sample);
  } else {
    const double dt_s = (sample.utime - last_utime_) * kMicrosecond;
    if (dt_s > 0) {
      // The model is sampled at the nominal strain period: an interval is
      // predicted in whole periods (a gap of n samples is n periods; the
      // pipeline re-initialises after reset_gap_s).
      Predict(std::max(1, static_cast<int>(std::lround(dt_s / model_.period_s))));
      last_utime_ = sample.utime;
    }
    UpdateGyro();
    strain = UpdateStrain(sample);
    if (!state_.allFinite() || !covariance_.allFinite()) {
      // Numerical failure: start again from this sample.
      Initialize(sample);
      info->reset = ResetReason::kNumerical;
      strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
    }
  }
  Report(strain);
  FillEstimate(sample, strain.outcome == FusionOutcome::kRejectedGate, estimate);
}

}  // namespace birotor

#include "estimator/ekf_force_estimator.h"

#include <algorithm>
#include <cmath>

namespace birotor {
namespace {

// Numerical guards on the diagonal of P (not tuning: they only keep the
// covariance well conditioned). Floors [unit^2], per state.
constexpr double kVarianceFloor[kEkfStateSize] = {
    1e-16, 1e-16,  // b [rad^2]
    1e-12,         // phi_dot [(rad/s)^2]
    1e-12, 1e-12,  // b_dot [(rad/s)^2]
    1e-6,  1e-6,   // omega [(rad/s)^2]
    1e-10, 1e-10,  // mu [1]
};
constexpr double kVarianceCeiling[kEkfStateSize] = {
    1e-2, 1e-2,  // b: 0.1 rad
    1e4,         // phi_dot: 100 rad/s
    1e4,  1e4,   // b_dot
    1e6,  1e6,   // omega: 1000 rad/s
    4.0,  4.0,   // mu: 2
};
constexpr double kMicrosecond = 1e-6;

}  // namespace

EkfForceEstimator::EkfForceEstimator(const VehicleParams& params, const EkfOptions& options)
    : params_(params),
      options_(options),
      process_(params),
      strain_model_(options.strain_noise_rad),
      motor_model_(options.motor_speed_noise_rad_s),
      gyro_model_(options.gyro_noise_rad_s),
      contact_(params, options) {
  process_noise_psd_.setZero();
  process_noise_psd_(kPitchRate, kPitchRate) = options.pitch_rate_psd_rad2_s3;
  for (int i = 0; i < 2; ++i) {
    process_noise_psd_(kDeflectionRateIndex[i], kDeflectionRateIndex[i]) = options.deflection_rate_psd_rad2_s3;
    process_noise_psd_(kOmegaIndex[i], kOmegaIndex[i]) = options.omega_psd_rad2_s;
    process_noise_psd_(kThrustScaleIndex[i], kThrustScaleIndex[i]) = options.thrust_scale_psd_1_s;
  }
  state_.setZero();
  covariance_.setIdentity();
}

void EkfForceEstimator::Reset() {
  initialized_ = false;
  converged_ = false;
  consecutive_gated_ = 0;
  has_motor_ = false;
  has_previous_motor_ = false;
  telemetry_pending_ = false;
  gyro_pending_ = false;
  for (int i = 0; i < 2; ++i) {
    fault_[i] = false;
    below_since_utime_[i] = -1;
  }
}

void EkfForceEstimator::AddMotor(const MotorSample& sample) {
  if (has_motor_ && sample.utime < motor_.utime) return;  // the pipeline keeps order; be safe
  if (has_motor_) {
    previous_motor_ = motor_;
    has_previous_motor_ = true;
  }
  motor_ = sample;
  has_motor_ = true;
  telemetry_pending_ = options_.use_motor_telemetry && std::isfinite(sample.omega_meas_rad_s[0]) &&
                       std::isfinite(sample.omega_meas_rad_s[1]);
}

void EkfForceEstimator::AddImu(const ImuSample& sample) {
  // Thrust of the current estimate (hover before the first strain sample).
  const double total_force_n =
      initialized_ ? process_.Force(state_, 0) + process_.Force(state_, 1) : 2.0 * params_.HoverForceN();
  contact_.Update(sample.utime, sample.accel_z_m_s2, total_force_n);
  if (!options_.use_gyro || !std::isfinite(sample.gyro_y_rad_s)) return;
  gyro_rad_s_ = sample.gyro_y_rad_s;
  gyro_pending_ = true;
}

EkfInput EkfForceEstimator::CommandAt(int64_t utime) const {
  EkfInput input;
  input.body_supported = options_.body_held || contact_.supported();
  const MotorSample* source = nullptr;
  if (has_motor_) source = (motor_.utime <= utime || !has_previous_motor_) ? &motor_ : &previous_motor_;
  for (int i = 0; i < 2; ++i) {
    input.omega_cmd_rad_s[i] = source ? ClampCommand(params_, source->omega_cmd_rad_s[i])
                                      : std::sqrt(params_.HoverForceN() / params_.thrust_coeff_n_s2_rad2);
  }
  return input;
}

void EkfForceEstimator::Initialize(const StrainSample& sample) {
  // b from the measurement, rates 0, omega from telemetry, else the newest
  // command, else hover; mu = 1 with a large variance.
  const EkfInput input = CommandAt(sample.utime);
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < 2; ++i) {
    state_(kDeflectionIndex[i]) = sample.deflection_rad[i];
    state_(kOmegaIndex[i]) = telemetry_pending_ ? motor_.omega_meas_rad_s[i] : input.omega_cmd_rad_s[i];
    state_(kThrustScaleIndex[i]) = 1.0;
    covariance_(kDeflectionIndex[i], kDeflectionIndex[i]) = strain_model_.noise(i, i);
    covariance_(kDeflectionRateIndex[i], kDeflectionRateIndex[i]) =
        options_.initial_deflection_rate_std_rad_s * options_.initial_deflection_rate_std_rad_s;
    covariance_(kOmegaIndex[i], kOmegaIndex[i]) = options_.initial_omega_std_rad_s * options_.initial_omega_std_rad_s;
    covariance_(kThrustScaleIndex[i], kThrustScaleIndex[i]) =
        options_.initial_thrust_scale_std * options_.initial_thrust_scale_std;
  }
  covariance_(kPitchRate, kPitchRate) = options_.initial_pitch_rate_std_rad_s * options_.initial_pitch_rate_std_rad_s;
  telemetry_pending_ = false;
  gyro_pending_ = false;
  consecutive_gated_ = 0;
  converged_ = false;
  for (int i = 0; i < 2; ++i) {
    fault_[i] = false;
    below_since_utime_[i] = -1;
  }
  last_utime_ = sample.utime;
  initialized_ = true;
}

void EkfForceEstimator::Predict(double dt_s, const EkfInput& input) {
  // Linearise at the prior, then propagate the state with RK4 and
  // P = Phi P Phi^T + Qc dt.
  const EkfMatrix a = process_.Jacobian(state_, input);
  const EkfMatrix phi = EkfProcessModel::Transition(a, dt_s);
  state_ = process_.Step(state_, input, dt_s);
  EkfMatrix temp;
  temp.noalias() = phi.lazyProduct(covariance_);
  covariance_.noalias() = temp.lazyProduct(phi.transpose());
  covariance_ += process_noise_psd_ * dt_s;
}

void EkfForceEstimator::FuseTelemetry(int64_t utime) {
  if (!telemetry_pending_) return;
  telemetry_pending_ = false;
  // Carry the telemetry from its own time to the strain time with the motor
  // model: omega(t) ~ omega_meas + (cmd - omega_meas) / tau_m (t - t_meas).
  const double lead_s = (utime - motor_.utime) * kMicrosecond;
  if (lead_s < 0 || lead_s > 0.05) return;
  const EkfInput input = CommandAt(motor_.utime);
  MotorSpeedMeasurementModel::Vector z;
  for (int i = 0; i < 2; ++i) {
    const double meas = motor_.omega_meas_rad_s[i];
    z(i) = meas + (input.omega_cmd_rad_s[i] - meas) / params_.motor_time_constant_s * lead_s;
  }
  const Innovation<2> innovation = ComputeInnovation(motor_model_, state_, covariance_, z);
  JosephUpdate(motor_model_, innovation, &state_, &covariance_);
}

void EkfForceEstimator::FuseGyro() {
  if (!gyro_pending_) return;
  gyro_pending_ = false;
  const Innovation<1> innovation =
      ComputeInnovation(gyro_model_, state_, covariance_, GyroMeasurementModel::Vector(gyro_rad_s_));
  JosephUpdate(gyro_model_, innovation, &state_, &covariance_);
}

void EkfForceEstimator::FuseStrain(const StrainSample& sample, StrainUpdateInfo* info) {
  const StrainMeasurementModel::Vector z(sample.deflection_rad[0], sample.deflection_rad[1]);
  Innovation<2> innovation = ComputeInnovation(strain_model_, state_, covariance_, z);
  info->nis = innovation.nis;
  if (!(innovation.nis <= options_.gate_nis_threshold)) {
    ++consecutive_gated_;
    if (consecutive_gated_ < options_.gate_consecutive_limit) {
      info->gated = true;
      return;
    }
    // A persistent change is real (e.g. a lost propeller blade): open up mu
    // and the arm rates, then fuse.
    const double extra = options_.gate_inflation_thrust_scale_std;
    for (int i = 0; i < 2; ++i) {
      covariance_(kThrustScaleIndex[i], kThrustScaleIndex[i]) += extra * extra;
    }
    innovation = ComputeInnovation(strain_model_, state_, covariance_, z);
  }
  consecutive_gated_ = 0;
  JosephUpdate(strain_model_, innovation, &state_, &covariance_);
  info->fused = true;
}

bool EkfForceEstimator::ConditionCovariance() {
  if (!state_.allFinite() || !covariance_.allFinite()) return false;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  for (int i = 0; i < kEkfStateSize; ++i) {
    const double variance = covariance_(i, i);
    if (variance < -1e-6 * kVarianceCeiling[i]) return false;  // clearly negative: broken
    if (variance < kVarianceFloor[i]) {
      covariance_(i, i) = kVarianceFloor[i];
    } else if (variance > kVarianceCeiling[i]) {
      // Scale row and column: keeps P positive semi-definite.
      const double s = std::sqrt(kVarianceCeiling[i] / variance);
      covariance_.row(i) *= s;
      covariance_.col(i) *= s;
    }
  }
  for (int i = 0; i < 2; ++i) {
    const double mu = state_(kThrustScaleIndex[i]);
    if (mu < -1.0 || mu > 5.0 || state_(kOmegaIndex[i]) < -1e3) return false;
  }
  return true;
}

void EkfForceEstimator::UpdateFaults(int64_t utime) {
  const int64_t persistence_us = static_cast<int64_t>(options_.fault_persistence_s * 1e6);
  for (int i = 0; i < 2; ++i) {
    const double mu = state_(kThrustScaleIndex[i]);
    const double margin = options_.fault_n_sigma * std::sqrt(covariance_(kThrustScaleIndex[i], kThrustScaleIndex[i]));
    if (!fault_[i]) {
      if (mu + margin < options_.fault_thrust_scale) {
        if (below_since_utime_[i] < 0) below_since_utime_[i] = utime;
        if (utime - below_since_utime_[i] >= persistence_us) fault_[i] = true;
      } else {
        below_since_utime_[i] = -1;
      }
    } else if (mu - margin > options_.fault_clear_thrust_scale) {
      fault_[i] = false;
      below_since_utime_[i] = -1;
    }
  }
}

void EkfForceEstimator::FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate) {
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  double max_std_n = 0;
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector2d grad = process_.ForceGradient(state_, i);
    const int w = kOmegaIndex[i], m = kThrustScaleIndex[i];
    const double variance = grad(0) * grad(0) * covariance_(w, w) + 2.0 * grad(0) * grad(1) * covariance_(w, m) +
                            grad(1) * grad(1) * covariance_(m, m);
    estimate->force_n[i] = process_.Force(state_, i);
    estimate->force_std_n[i] = std::sqrt(std::max(variance, 0.0));
    estimate->thrust_scale[i] = state_(m);
    max_std_n = std::max(max_std_n, estimate->force_std_n[i]);
  }
  if (max_std_n < options_.converged_force_std_n) converged_ = true;
  int32_t status = converged_ ? kStatusValid : kStatusConverging;
  if (gated) status |= kStatusMeasurementRejected;
  if (fault_[0]) status |= kStatusRotor1Fault;
  if (fault_[1]) status |= kStatusRotor2Fault;
  if (!has_motor_) status |= kStatusNoMotorInput;
  estimate->status = status;
}

void EkfForceEstimator::AddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainUpdateInfo* info) {
  *info = StrainUpdateInfo();
  info->nis = std::nan("");
  const double dt_s = (sample.utime - last_utime_) * kMicrosecond;
  if (initialized_ && dt_s > options_.max_dt_s) {
    initialized_ = false;
    info->reset = true;
  }
  if (!initialized_) {
    Initialize(sample);
    info->fused = true;
    FillEstimate(sample, false, estimate);
    return;
  }
  if (dt_s > 0) {
    // Equal sub-steps no longer than max_prediction_step_s (one step at the
    // nominal 1 kHz; several across a short gap in the strain stream).
    const int steps = static_cast<int>(std::ceil(dt_s / options_.max_prediction_step_s - 1e-9));
    const double step_s = dt_s / steps;
    for (int k = 0; k < steps; ++k) {
      const int64_t step_start_utime = last_utime_ + static_cast<int64_t>(std::llround(k * step_s / kMicrosecond));
      Predict(step_s, CommandAt(step_start_utime));
    }
    last_utime_ = sample.utime;
  }
  FuseTelemetry(sample.utime);
  FuseGyro();
  FuseStrain(sample, info);
  if (!ConditionCovariance()) {
    // Numerical failure: start again from this sample.
    Initialize(sample);
    info->reset = true;
    info->fused = true;
  }
  UpdateFaults(sample.utime);
  FillEstimate(sample, info->gated, estimate);
}

}  // namespace birotor

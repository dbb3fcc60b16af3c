#include "estimator/linear_force_estimator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "estimator/filter_status.h"
#include "estimator/linear_method_reports.h"
#include "estimator/luenberger_gain.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr double kMicrosecond = 1e-6;

}  // namespace

LinearForceEstimator::LinearForceEstimator(const BirotorParams& params, const EkfOptions& noise,
                                           const LinearModelOptions& options)
    : kalman_(true),
      noise_(noise),
      model_(BuildLinearForceModel(params, noise, options)),
      motor_(params),
      strain_gate_(noise.gate_consecutive_limit),
      gyro_gate_(noise.gate_consecutive_limit) {
  scale_ = model_.scale;
  const LinearMatrix s_inv = scale_.cwiseInverse().asDiagonal();
  a_ = s_inv * model_.a_discrete * scale_.asDiagonal();
  q_ = s_inv * model_.noise_discrete * s_inv;
  const double deflection_scale = scale_(kLinDeflection1);
  const double strain_std = noise.strain_noise_rad / deflection_scale;
  strain_noise_ = Eigen::Matrix2d::Identity() * (strain_std * strain_std);
  const double gyro_std = noise.gyro_noise_rad_s / scale_(kLinPitchRate);
  gyro_noise_(0, 0) = gyro_std * gyro_std;
  const double pitch_rate_std = noise.initial_pitch_rate_std_rad_s / scale_(kLinPitchRate);
  pitch_rate_variance_s_ = pitch_rate_std * pitch_rate_std;
  fixed_gains_.strain.setZero();
  fixed_gains_.gyro.setZero();
  fixed_gain_s_.setZero();
  fixed_gyro_gain_s_.setZero();
  state_.setZero();
  covariance_.setIdentity();
}

LinearForceEstimator::LinearForceEstimator(const BirotorParams& params, const EkfOptions& noise,
                                           const LinearModelOptions& options, const LuenbergerOptions& observer)
    : LinearForceEstimator(params, noise, options) {
  kalman_ = false;
  fixed_gains_ = PlaceObserverPoles(model_, observer);
  // Scaled: x_s += diag(1/scale) L scale_y y_s.
  fixed_gain_s_ = scale_.cwiseInverse().asDiagonal() * fixed_gains_.strain * scale_(kLinDeflection1);
  fixed_gyro_gain_s_ = scale_.cwiseInverse().asDiagonal() * fixed_gains_.gyro * scale_(kLinPitchRate);
}

void LinearForceEstimator::DoAddMotor(const MotorSample& sample) {
  motor_.AddMotor(sample);
  if (std::isfinite(sample.omega_meas_rad_s[0]) && std::isfinite(sample.omega_meas_rad_s[1])) {
    Report(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
  }
}

void LinearForceEstimator::DoAddImu(const ImuSample& sample) {
  if (!noise_.use_gyro || !std::isfinite(sample.gyro_y_rad_s)) {
    Report(MakeFusionReport(FusionSource::kGyro, sample.utime, FusionOutcome::kNotFused));
    return;
  }
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_ = sample;
  gyro_pending_ = true;
}

double LinearForceEstimator::Gate(FusionSource source) const { return LinearMethodGate(noise_, source); }

void LinearForceEstimator::DoReset() {
  motor_.Reset();
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_pending_ = false;
  initialized_ = false;
  converged_ = false;
  strain_gate_.Reset();
  gyro_gate_.Reset();
}

void LinearForceEstimator::Initialize(const StrainSample& sample) {
  // Deflections from the sample, rates 0, forces at hover; the EKF's initial
  // uncertainties (thrust scale sigma at the hover force).
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < kBirotorRotors; ++i) {
    state_(kLinDeflectionIndex[i]) =
        (sample.deflection_rad[i] - model_.deflection_hover_rad[i]) / scale_(kLinDeflection1);
    covariance_(kLinDeflectionIndex[i], kLinDeflectionIndex[i]) = strain_noise_(i, i);
    const double rate_std = noise_.initial_deflection_rate_std_rad_s / scale_(kLinDeflectionRate1);
    covariance_(kLinDeflectionRate1 + i, kLinDeflectionRate1 + i) = rate_std * rate_std;
    const double force_std = noise_.initial_thrust_scale_std * model_.force_hover_n[i] / scale_(kLinForceIndex[i]);
    covariance_(kLinForceIndex[i], kLinForceIndex[i]) = force_std * force_std;
  }
  covariance_(kLinPitchRate, kLinPitchRate) = pitch_rate_variance_s_;
  if (gyro_pending_) Report(MakeFusionReport(FusionSource::kGyro, gyro_.utime, FusionOutcome::kNotFused));
  gyro_pending_ = false;
  strain_gate_.Reset();
  gyro_gate_.Reset();
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
  // y = phi_dot_meas - phi_dot; the Kalman gain, or the observer's L_g.
  const double pitch_rate_scale = scale_(kLinPitchRate);
  MeasurementLinearization<1, kLinearStateSize> at;
  at.jacobian = model_.c_gyro;
  at.predicted(0) = state_(kLinPitchRate);
  const Eigen::Matrix<double, 1, 1> z(gyro_.gyro_y_rad_s / pitch_rate_scale);
  // After gate_consecutive_limit gyro samples gated in a row the pitch rate
  // is taken as lost (a lift-off's thrust ramp, which the hover model does
  // not follow, left it rad/s off): its variance grows by the initial one
  // and the gyro is fused ungated (else it stays gated for the flight).
  const auto inflate = [this](LinearMatrix* cov) { (*cov)(kLinPitchRate, kLinPitchRate) += pitch_rate_variance_s_; };
  const FusionReport report =
      gyro_gate_.Fuse(at, gyro_noise_, z, {FusionSource::kGyro, gyro_.utime, noise_.gyro_gate_nis}, &state_,
                      &covariance_, inflate, kalman_ ? nullptr : &fixed_gyro_gain_s_);
  Report(LinearReportInPhysicalUnits(report, pitch_rate_scale));
}

FusionReport LinearForceEstimator::UpdateStrain(const StrainSample& sample) {
  // y = z - C x (C selects the deflections); the Kalman gain, or the observer's L.
  const double deflection_scale = scale_(kLinDeflection1);
  MeasurementLinearization<kLinearOutputSize, kLinearStateSize> at;
  at.jacobian = model_.c;
  Eigen::Vector2d z;
  for (int i = 0; i < kBirotorRotors; ++i) {
    at.predicted(i) = state_(kLinDeflectionIndex[i]);
    z(i) = (sample.deflection_rad[i] - model_.deflection_hover_rad[i]) / deflection_scale;
  }
  // After gate_consecutive_limit rejections in a row: open up the forces
  // (the EKF's inflation of var(mu_i), at the hover force), then fuse.
  const auto inflate = [this](LinearMatrix* cov) {
    for (int i = 0; i < kBirotorRotors; ++i) {
      const double extra = noise_.gate_inflation_thrust_scale_std * model_.force_hover_n[i] / scale_(kLinForceIndex[i]);
      (*cov)(kLinForceIndex[i], kLinForceIndex[i]) += extra * extra;
    }
  };
  const FusionReport report =
      strain_gate_.Fuse(at, strain_noise_, z, {FusionSource::kStrain, sample.utime, noise_.strain_gate_nis}, &state_,
                        &covariance_, inflate, kalman_ ? nullptr : &fixed_gain_s_);
  return LinearReportInPhysicalUnits(report, deflection_scale);
}

void LinearForceEstimator::FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate,
                                        FilterStatusFacts* facts) {
  for (int i = 0; i < kBirotorRotors; ++i) {
    const int f = kLinForceIndex[i];
    const double force = model_.force_hover_n[i] + scale_(f) * state_(f);
    estimate->force_n[i] = force;
    estimate->force_std_n[i] = scale_(f) * std::sqrt(std::max(covariance_(f, f), 0.0));
    estimate->thrust_scale[i] = motor_.ThrustScale(i, force);
  }
  SetFilterFacts(sample, noise_.converged_force_std_n, gated, &converged_, estimate, facts);
}

void LinearForceEstimator::DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) {
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
  FillEstimate(sample, strain.outcome == FusionOutcome::kRejectedGate, estimate, &info->filter);
}

}  // namespace birotor

#include "estimator/baseline_estimators.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "model/equilibrium.h"
#include "model/linearization.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

bool HasTelemetry(const MotorSample& sample) {
  return std::isfinite(sample.omega_meas_rad_s[0]) && std::isfinite(sample.omega_meas_rad_s[1]);
}

}  // namespace

InversionEstimator::InversionEstimator(const BirotorParams& params, const InversionOptions& options)
    : params_(params), options_(options), motor_(params) {
  options_.window_samples = std::clamp(options_.window_samples, 3, kMaxWindow);
  const LinearModel model = ToSumDifferenceCoordinates(LinearizeAtHover(params));
  // Sum/difference coordinates sit in the b1/b2 slots of the 10-state model.
  constexpr int kBs = kB1, kBd = kB2;
  constexpr int kColumns[4] = {kBs, kBd, kNumCoordinates + kBs, kNumCoordinates + kBd};
  constexpr int kRows[2] = {kNumCoordinates + kBs, kNumCoordinates + kBd};
  Eigen::Matrix2d b2;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 4; ++c) a2_(r, c) = model.a(kRows[r], kColumns[c]);
    for (int c = 0; c < 2; ++c) b2(r, c) = model.b(kRows[r], c);
  }
  b2_inverse_ = b2.inverse();
  const Equilibrium eq = SolveHoverEquilibrium(params);
  bs0_rad_ = eq.deflection_rad[0] + eq.deflection_rad[1];
  bd0_rad_ = eq.deflection_rad[0] - eq.deflection_rad[1];
  f0_n_ = 0.5 * (eq.force_n[0] + eq.force_n[1]);
}

void InversionEstimator::DoReset() {
  motor_.Reset();
  head_ = 0;
  count_ = 0;
}

void InversionEstimator::DoAddMotor(const MotorSample& sample) {
  motor_.AddMotor(sample);
  if (HasTelemetry(sample)) Report(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
}

void InversionEstimator::DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) {
  *info = StrainStepInfo();
  Report(MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused));
  utime_[head_] = sample.utime;
  deflection_rad_[head_][0] = sample.deflection_rad[0];
  deflection_rad_[head_][1] = sample.deflection_rad[1];
  head_ = (head_ + 1) % kMaxWindow;
  count_ = std::min(count_ + 1, kMaxWindow);
  motor_.Advance(sample.utime);

  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  // Without motor input (the pipeline flags it) the thrust scale is 1.
  const int n = options_.window_samples;
  if (count_ < n) {
    for (int i = 0; i < 2; ++i) {
      estimate->force_n[i] = f0_n_;
      estimate->force_std_n[i] = options_.force_std_n;
      estimate->thrust_scale[i] = 1.0;
    }
    info->filter.convergence = FilterConvergence::kConverging;
    return;
  }
  // Least squares b(tau) = c0 + c1 tau + c2 tau^2, tau = t - t_newest in ms
  // (scaled for conditioning), for both arms at once.
  constexpr double kTauScale = 1e-3;  // [s per unit of tau]
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> rhs = Eigen::Matrix<double, 3, 2>::Zero();
  for (int j = 0; j < n; ++j) {
    const int slot = (head_ - 1 - j + 2 * kMaxWindow) % kMaxWindow;
    const double tau = (utime_[slot] - sample.utime) * 1e-6 / kTauScale;
    const Eigen::Vector3d basis(1.0, tau, tau * tau);
    normal.noalias() += basis * basis.transpose();
    rhs.row(0) += basis(0) * Eigen::RowVector2d(deflection_rad_[slot][0], deflection_rad_[slot][1]);
    rhs.row(1) += basis(1) * Eigen::RowVector2d(deflection_rad_[slot][0], deflection_rad_[slot][1]);
    rhs.row(2) += basis(2) * Eigen::RowVector2d(deflection_rad_[slot][0], deflection_rad_[slot][1]);
  }
  const Eigen::Matrix<double, 3, 2> coeffs = normal.ldlt().solve(rhs);
  // Rows: value [rad], rate [rad/s], acceleration [rad/s^2]; columns: b1, b2.
  const double b[kBirotorRotors] = {coeffs(0, 0), coeffs(0, 1)};
  const double b_dot[kBirotorRotors] = {coeffs(1, 0) / kTauScale, coeffs(1, 1) / kTauScale};
  const double b_ddot[kBirotorRotors] = {2.0 * coeffs(2, 0) / (kTauScale * kTauScale),
                                         2.0 * coeffs(2, 1) / (kTauScale * kTauScale)};
  const Eigen::Vector4d x(b[0] + b[1] - bs0_rad_, b[0] - b[1] - bd0_rad_, b_dot[0] + b_dot[1], b_dot[0] - b_dot[1]);
  const Eigen::Vector2d acc(b_ddot[0] + b_ddot[1], b_ddot[0] - b_ddot[1]);
  const Eigen::Vector2d df = b2_inverse_ * (acc - a2_ * x);  // thesis eq. 5.2
  for (int i = 0; i < 2; ++i) {
    const double force = f0_n_ + df(i);
    estimate->force_n[i] = force;
    estimate->force_std_n[i] = options_.force_std_n;
    estimate->thrust_scale[i] = motor_.ThrustScale(i, force);
  }
  info->filter.convergence = FilterConvergence::kConverged;
}

MotorMapEstimator::MotorMapEstimator(const BirotorParams& params, const MotorMapOptions& options)
    : params_(params), options_(options), motor_(params) {}

void MotorMapEstimator::DoAddMotor(const MotorSample& sample) {
  motor_.AddMotor(sample);
  if (HasTelemetry(sample)) Report(MakeFusionReport(FusionSource::kTelemetry, sample.utime, FusionOutcome::kFused));
}

void MotorMapEstimator::DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) {
  *info = StrainStepInfo();
  Report(MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kNotFused));
  motor_.Advance(sample.utime);
  estimate->utime = sample.utime;
  estimate->seq = sample.seq;
  const double c_t = params_.thrust_coeff_n_s2_rad2;
  for (int i = 0; i < 2; ++i) {
    // Before any motor input, assume hover speed.
    const double omega = motor_.has_motor() ? motor_.omega_rad_s(i) : std::sqrt(params_.HoverForceN() / c_t);
    const double speed_std =
        motor_.from_telemetry(i) ? options_.motor_speed_noise_rad_s : options_.model_speed_std_rad_s;
    estimate->force_n[i] = c_t * omega * omega;
    estimate->force_std_n[i] = 2.0 * c_t * std::abs(omega) * speed_std;
    estimate->thrust_scale[i] = 1.0;
  }
  // Converging until the first command: the forces are the assumed hover.
  info->filter.convergence = motor_.has_motor() ? FilterConvergence::kConverged : FilterConvergence::kConverging;
}

}  // namespace birotor

#include "estimator/ekf_force_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "estimator/filter_status.h"
#include "estimator/fusion_counters.h"
#include "estimator/parameter_hypotheses.h"
#include "samples/rotor_count.h"

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
    1e-16, 1e-16,  // e [rad^2]
    1e-12, 1e-12,  // g [1] (0 when not learned: EkfForceEstimator's copy)
    1e-12,         // r_m [1] (as g)
};
constexpr double kVarianceCeiling[kEkfStateSize] = {
    1e-2, 1e-2,  // b: 0.1 rad
    1e4,         // phi_dot: 100 rad/s
    1e4,  1e4,   // b_dot
    1e6,  1e6,   // omega: 1000 rad/s
    4.0,  4.0,   // mu: 2
    1e-6, 1e-6,  // e: 1 mrad (the tare refuses 0.5 mrad)
    0.25, 0.25,  // g: 0.5 (kStrainScaleVarianceCeiling)
    0.25,        // r_m: 0.5
};
static_assert(kVarianceCeiling[kStrainScale1] == kStrainScaleVarianceCeiling &&
                  kVarianceCeiling[kStrainScale2] == kStrainScaleVarianceCeiling,
              "the published sigma of g has the ceiling of P");
// The slow parameters are the last states (Predict skips them by head<>).
static_assert(kStrainScale1 == kGaugeOffset2 + 1 && kBodyMassScale == kEkfStateSize - 1, "slow states last");
// A learned scale outside this range is a numerical failure, not a vehicle [1].
constexpr double kMinLearnedScale = 0.2, kMaxLearnedScale = 5.0;
constexpr double kMicrosecond = 1e-6;

}  // namespace

EkfForceEstimator::EkfForceEstimator(const BirotorParams& params, const EkfOptions& options)
    : params_(params),
      options_(options),
      process_(params, options.learn_body_mass),
      strain_model_(options.strain_noise_rad),
      motor_model_(options.motor_speed_noise_rad_s),
      gyro_model_(options.gyro_noise_rad_s),
      accel_model_(options.accel_noise_m_s2),
      contact_(params, options),
      strain_gate_(options.gate_consecutive_limit),
      gyro_gate_(options.gate_consecutive_limit),
      accel_gate_(options.gate_consecutive_limit),
      strain_noise_(StrainNoiseSettings(options)),
      accel_noise_(AccelerometerNoiseSettings(options), 1),
      strain_noise_rad2_(strain_model_.noise),
      faults_(options) {
  process_noise_psd_.setZero();
  process_noise_psd_(kPitchRate) = options.pitch_rate_psd_rad2_s3;
  for (int i = 0; i < 2; ++i) {
    process_noise_psd_(kDeflectionRateIndex[i]) = options.deflection_rate_psd_rad2_s3;
    process_noise_psd_(kOmegaIndex[i]) = options.omega_psd_rad2_s;
    process_noise_psd_(kThrustScaleIndex[i]) = options.thrust_scale_psd_1_s;
    // The gauge reads s_i (b_i + e_i): a raw offset drift of q [rad^2/s] is q / s_i^2 in e_i.
    const double scale = params.gauge_scale[i];
    process_noise_psd_(kGaugeOffsetIndex[i]) =
        options.estimate_gauge_offsets ? params.gauge_drift_psd_rad2_s / (scale * scale) : 0.0;
    offset_prior_std_rad_[i] = options.estimate_gauge_offsets ? params.gauge_offset_std_rad / scale : 0.0;
    hover_input_.omega_cmd_rad_s[i] =
        ClampCommand(params_, std::sqrt(params_.HoverForceN() / params_.thrust_coeff_n_s2_rad2));
  }
  const double g_std = options.learn_strain_scale ? options.strain_scale_prior_std : 0.0;
  const double m_std = options.learn_body_mass ? options.body_mass_scale_prior_std : 0.0;
  for (int i = 0; i < kEkfStateSize; ++i) variance_floor_[i] = kVarianceFloor[i];
  for (int i = 0; i < 2; ++i) {
    const int g = kStrainScaleIndex[i];
    process_noise_psd_(g) = options.learn_strain_scale ? options.strain_scale_psd_1_s : 0.0;
    learned_.value[g] = 1.0;
    learned_.std[g] = g_std;
    learned_.published_strain_scale_std[i] = g_std;
    if (!options.learn_strain_scale) variance_floor_[g] = 0.0;
  }
  process_noise_psd_(kBodyMassScale) = options.learn_body_mass ? options.body_mass_scale_psd_1_s : 0.0;
  learned_.value[kBodyMassScale] = 1.0;
  learned_.std[kBodyMassScale] = m_std;
  if (!options.learn_body_mass) variance_floor_[kBodyMassScale] = 0.0;
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) slow_noise_psd_[p] = process_noise_psd_(p);
  command_ = hover_input_;
  state_.setZero();
  covariance_.setIdentity();
}

void EkfForceEstimator::DoReset() {
  DiscardQueued();
  initialized_ = false;
  converged_ = false;
  strain_gate_.Reset();
  gyro_gate_.Reset();
  accel_gate_.Reset();
  has_motor_ = false;
  command_ = hover_input_;
  faults_.Reset();
}

bool EkfForceEstimator::TelemetryUsable(const MotorSample& sample) const {
  return options_.use_motor_telemetry && std::isfinite(sample.omega_meas_rad_s[0]) &&
         std::isfinite(sample.omega_meas_rad_s[1]);
}

void EkfForceEstimator::ReportNotFused(FusionSource source, int64_t utime) const {
  Report(MakeFusionReport(source, utime, FusionOutcome::kNotFused));
}

void EkfForceEstimator::DoAddMotor(const MotorSample& sample) {
  // Telemetry switched off is a measurement the filter does not use: said at once.
  const bool has_telemetry = std::isfinite(sample.omega_meas_rad_s[0]) && std::isfinite(sample.omega_meas_rad_s[1]);
  if (has_telemetry && !options_.use_motor_telemetry) ReportNotFused(FusionSource::kTelemetry, sample.utime);
  MotorSample dropped;
  if (motor_queue_.push(sample, &dropped) && TelemetryUsable(dropped)) {
    ReportNotFused(FusionSource::kTelemetry, dropped.utime);
  }
}

bool EkfForceEstimator::AccelerometerUsable(const ImuSample& sample) const {
  return std::isfinite(sample.accel_z_m_s2);
}

void EkfForceEstimator::ReportImuNotFused(const ImuSample& sample) const {
  if (options_.use_gyro) ReportNotFused(FusionSource::kGyro, sample.utime);
  if (options_.use_accelerometer && AccelerometerUsable(sample)) {
    ReportNotFused(FusionSource::kAccelerometer, sample.utime);
  }
}

void EkfForceEstimator::DoAddImu(const ImuSample& sample) {
  // Ground contact on arrival, with the thrust of the current estimate
  // (hover before the first strain sample); it selects the model of the
  // next predictions.
  const double total_force_n =
      initialized_ ? process_.Force(state_, 0) + process_.Force(state_, 1) : 2.0 * params_.HoverForceN();
  const bool was_supported = contact_.supported();
  contact_.Update(sample.utime, sample.accel_z_m_s2, total_force_n);
  if (was_supported && !contact_.supported()) contact_released_utime_ = sample.utime;
  // A reading switched off is a measurement the filter does not use: said at once.
  if (!options_.use_gyro) ReportNotFused(FusionSource::kGyro, sample.utime);
  if (!options_.use_accelerometer && AccelerometerUsable(sample)) {
    ReportNotFused(FusionSource::kAccelerometer, sample.utime);
  }
  if (!options_.use_gyro && !options_.use_accelerometer) return;
  ImuSample dropped;
  if (imu_queue_.push(sample, &dropped)) ReportImuNotFused(dropped);
}

void EkfForceEstimator::DiscardQueued() {
  while (!motor_queue_.empty()) {
    if (TelemetryUsable(motor_queue_.front())) ReportNotFused(FusionSource::kTelemetry, motor_queue_.front().utime);
    motor_queue_.pop();
  }
  while (!imu_queue_.empty()) {
    ReportImuNotFused(imu_queue_.front());
    imu_queue_.pop();
  }
}

void EkfForceEstimator::Initialize(const StrainSample& sample) {
  // Commands stamped up to the sample: the newest holds. The newest
  // telemetry sets omega (else the command); older telemetry and queued gyro
  // samples are not fused. Offsets e = 0 with their prior sigma, b = z - e
  // (so var b = R + var e and cov(b, e) = -var e), rates 0, mu = 1 with a
  // large variance.
  bool has_telemetry = false;
  MotorSample telemetry;
  while (!motor_queue_.empty() && motor_queue_.front().utime <= sample.utime) {
    const MotorSample& m = motor_queue_.front();
    for (int i = 0; i < 2; ++i) command_.omega_cmd_rad_s[i] = ClampCommand(params_, m.omega_cmd_rad_s[i]);
    has_motor_ = true;
    if (TelemetryUsable(m)) {
      if (has_telemetry) ReportNotFused(FusionSource::kTelemetry, telemetry.utime);
      telemetry = m;
      has_telemetry = true;
    }
    motor_queue_.pop();
  }
  while (!imu_queue_.empty() && imu_queue_.front().utime <= sample.utime) {
    ReportImuNotFused(imu_queue_.front());
    imu_queue_.pop();
  }
  state_.setZero();
  covariance_.setZero();
  for (int i = 0; i < 2; ++i) {
    const int b = kDeflectionIndex[i], e = kGaugeOffsetIndex[i];
    const double offset_variance = offset_prior_std_rad_[i] * offset_prior_std_rad_[i];
    state_(b) = sample.deflection_rad[i];
    covariance_(b, b) = strain_noise_rad2_(i, i) + offset_variance;
    covariance_(b, e) = covariance_(e, b) = -offset_variance;
    covariance_(e, e) = offset_variance;
    state_(kOmegaIndex[i]) = has_telemetry ? telemetry.omega_meas_rad_s[i] : command_.omega_cmd_rad_s[i];
    state_(kThrustScaleIndex[i]) = 1.0;
    covariance_(kDeflectionRateIndex[i], kDeflectionRateIndex[i]) =
        options_.initial_deflection_rate_std_rad_s * options_.initial_deflection_rate_std_rad_s;
    // Without any MOTOR sample omega is the assumed hover speed: known no
    // better than that speed itself (a bench starts anywhere in its range).
    const double omega_std = has_motor_ ? options_.initial_omega_std_rad_s
                                        : std::max(options_.initial_omega_std_rad_s, hover_input_.omega_cmd_rad_s[i]);
    covariance_(kOmegaIndex[i], kOmegaIndex[i]) = omega_std * omega_std;
    covariance_(kThrustScaleIndex[i], kThrustScaleIndex[i]) =
        options_.initial_thrust_scale_std * options_.initial_thrust_scale_std;
  }
  covariance_(kPitchRate, kPitchRate) = options_.initial_pitch_rate_std_rad_s * options_.initial_pitch_rate_std_rad_s;
  // The slow parameters start from what was learned (the vehicle did not
  // change across a reset), or the file's value with the prior sigma.
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) {
    state_(p) = learned_.value[p];
    covariance_(p, p) = learned_.std[p] * learned_.std[p];
  }
  scales_frozen_ = mass_frozen_ = false;
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) process_noise_psd_(p) = slow_noise_psd_[p];
  flying_since_utime_ = kFlyingSinceStart;  // no lift-off seen (a start in the air): no delay
  carried_in_flight_ = false;
  UpdateLearning();
  if (has_telemetry) {
    // The state was set from it: fused, without an innovation.
    Report(MakeFusionReport(FusionSource::kTelemetry, telemetry.utime, FusionOutcome::kFused));
  }
  strain_gate_.Reset();
  gyro_gate_.Reset();
  accel_gate_.Reset();
  step_hold_until_utime_ = 0;
  liftoff_hold_until_utime_ = 0;
  converged_ = false;
  faults_.Reset();
  accel_linearization_.valid = false;  // from before the re-initialisation
  last_utime_ = sample.utime;
  StartSettling();  // a start in the air learns at once, and splits again once settled
  initialized_ = true;
}

void EkfForceEstimator::PredictTo(int64_t utime) {
  UpdateLearning();  // before any fusion at this time
  if (utime <= last_utime_) return;
  const double dt_s = (utime - last_utime_) * kMicrosecond;
  // Equal sub-steps no longer than max_prediction_step_s (one step at the
  // nominal 1 kHz; several across a short gap in the strain stream).
  const int steps = static_cast<int>(std::ceil(dt_s / options_.max_prediction_step_s - 1e-9));
  const double step_s = dt_s / steps;
  EkfInput input = command_;
  input.body_supported = options_.body_held || contact_.supported();
  for (int k = 0; k < steps; ++k) Predict(step_s, input);
  last_utime_ = utime;
}

void EkfForceEstimator::ApplyQueuedUpTo(int64_t utime) {
  DrainInTimeOrder(
      utime, &motor_queue_, &imu_queue_, [this](const MotorSample& sample) { ApplyMotor(sample); },
      [this](const ImuSample& sample) { ApplyImu(sample); });
}

bool EkfForceEstimator::ConditionCovariance() {
  switch (LiveStates()) {
    case kStrainScale1:
      return ConditionCovariance<kStrainScale1>();
    case kBodyMassScale:
      return ConditionCovariance<kBodyMassScale>();
    default:
      return ConditionCovariance<kEkfStateSize>();
  }
}

template <int N>
bool EkfForceEstimator::ConditionCovariance() {
  if (!state_.allFinite()) return false;
  // Beyond the N live states the rows and columns of P are zero
  // (LiveStates): the leading block only (their floor is 0 or skipped).
  const Eigen::Matrix<double, N, N> lead = covariance_.topLeftCorner<N, N>();
  if (!lead.allFinite()) return false;
  covariance_.topLeftCorner<N, N>() = 0.5 * (lead + lead.transpose());
  for (int i = 0; i < N; ++i) {
    const double variance = covariance_(i, i);
    if (variance < -1e-6 * kVarianceCeiling[i]) return false;  // clearly negative: broken
    if (variance < variance_floor_[i] && !(i >= kStrainScale1 && SlowStateFrozen(i))) {
      covariance_(i, i) = variance_floor_[i];
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
  for (const int p : {kStrainScale1, kStrainScale2, kBodyMassScale}) {
    if (state_(p) < kMinLearnedScale || state_(p) > kMaxLearnedScale) return false;
  }
  return true;
}

void EkfForceEstimator::FillEstimate(const StrainSample& sample, bool gated, ForceEstimate* estimate,
                                     FilterStatusFacts* facts) {
  // Averaged over the body-mass hypotheses (the file's mass, a payload;
  // parameter_hypotheses.h): r_m, its variance while live (0 frozen: no
  // correlation, both hypotheses give the filter's x) and P(payload).
  const double scale = state_(kBodyMassScale);
  const double scale_variance = BodyMassLive() ? covariance_(kBodyMassScale, kBodyMassScale) : 0.0;
  const double payload = PayloadProbability();
  for (int i = 0; i < 2; ++i) {
    // var f_i = g^T P_(omega_i, mu_i) g with g = (df/domega, df/dmu); cov(f_i, r_m) likewise.
    const Eigen::Vector2d grad = process_.ForceGradient(state_, i);
    const int w = kOmegaIndex[i], m = kThrustScaleIndex[i], r = kBodyMassScale;
    const double variance = grad(0) * grad(0) * covariance_(w, w) + 2.0 * grad(0) * grad(1) * covariance_(w, m) +
                            grad(1) * grad(1) * covariance_(m, m);
    const double covariance_with_scale = grad(0) * covariance_(w, r) + grad(1) * covariance_(m, r);
    const HypothesesAverage force = AverageOverHypotheses(process_.Force(state_, i), variance, covariance_with_scale,
                                                          scale, scale_variance, payload);
    estimate->force_n[i] = force.value;
    estimate->force_std_n[i] = std::sqrt(std::max(force.variance, 0.0));
    estimate->thrust_scale[i] =
        AverageOverHypotheses(state_(m), covariance_(m, m), covariance_(m, r), scale, scale_variance, payload).value;
  }
  SetFilterFacts(sample, options_.converged_force_std_n, gated, &converged_, estimate, facts);
  // While learned strain scales settle after a start or a lift-off the
  // unexplained part of the readings sits in the offsets (SplitScaleAndOffsetAgain):
  // once they moved (settling_offset_limit_sigma) a payload's forces are
  // off, and nothing tells it yet.
  if (settling_.pending && SettlingOffsetsMoved()) facts->convergence = FilterConvergence::kConverging;
  faults_.FillFacts(facts);
}

bool EkfForceEstimator::GyroMayInflate(int64_t utime) const {
  // Within gyro_liftoff_recovery_s of a lift-off, outside a thrust step
  // other than the lift-off's own spin-up (its first step_hold_s: the strain
  // gate rejects there when the body is let go with the rotors far apart,
  // and the pitch rate it then starts is the one the gyro must give back).
  const double since_liftoff_s = (utime - contact_released_utime_) * kMicrosecond;
  if (contact_released_utime_ < 0 || since_liftoff_s < 0 || since_liftoff_s > options_.gyro_liftoff_recovery_s) {
    return false;
  }
  return since_liftoff_s <= options_.step_hold_s || !InThrustStep();
}

void EkfForceEstimator::SetGaugeOffsetPrior(const double offset_std_rad[kBirotorRotors]) {
  if (!options_.estimate_gauge_offsets) return;
  for (int i = 0; i < 2; ++i) {
    offset_prior_std_rad_[i] = offset_std_rad[i];
    if (!initialized_) continue;
    // The calibration moved by what was learned: start e_i again from 0.
    const int e = kGaugeOffsetIndex[i];
    state_(e) = 0.0;
    covariance_.row(e).setZero();
    covariance_.col(e).setZero();
    covariance_(e, e) = std::max(offset_std_rad[i] * offset_std_rad[i], kVarianceFloor[e]);
  }
}

double EkfForceEstimator::Gate(FusionSource source) const { return EkfGateNis(options_, source); }

void EkfForceEstimator::FillLearnedOffsets(StrainStepInfo* info) const {
  info->has_learned_gauge_offset = options_.estimate_gauge_offsets;
  if (!info->has_learned_gauge_offset) return;
  for (int i = 0; i < 2; ++i) {
    const int e = kGaugeOffsetIndex[i];
    info->learned_gauge_offset_rad[i] = state_(e);
    info->learned_gauge_offset_std_rad[i] = std::sqrt(std::max(covariance_(e, e), 0.0));
  }
}

void EkfForceEstimator::DoAddStrain(const StrainSample& sample, ForceEstimate* estimate, StrainStepInfo* info) {
  // Copied from a constant: for `*info = StrainStepInfo()` GCC 12 also
  // zero-fills a stack temporary it never reads (12 instructions more per
  // strain sample under callgrind, BM_StrainSample/ekf).
  static const StrainStepInfo kNothingDone;
  *info = kNothingDone;
  // At (re-)initialisation the state is set from the sample: fused, without an innovation.
  FusionReport strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
  if (!initialized_) {
    Initialize(sample);
  } else {
    ApplyQueuedUpTo(sample.utime);
    PredictTo(sample.utime);
    strain = FuseStrain(sample);
    if (strain.fused_after_inflation) step_hold_until_utime_ = StepHoldEndUtime();
    if (!ConditionCovariance()) {
      // Numerical failure: start again from this sample.
      Initialize(sample);
      info->reset = ResetReason::kNumerical;
      strain = MakeFusionReport(FusionSource::kStrain, sample.utime, FusionOutcome::kFused);
    }
    faults_.Update(sample.utime, Eigen::Vector2d(state_(kThrustScale1), state_(kThrustScale2)),
                   covariance_.block<2, 2>(kThrustScale1, kThrustScale1));
    LearnStrainNoise(strain);
  }
  Report(strain);
  FillEstimate(sample, strain.outcome == FusionOutcome::kRejectedGate, estimate, &info->filter);
  FillLearnedOffsets(info);
  FillLearnedParameters(info);
  info->body_supported = options_.body_held || contact_.supported();
}

}  // namespace birotor

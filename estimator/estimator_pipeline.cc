#include "estimator/estimator_pipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "estimator/baseline_estimators.h"
#include "estimator/ekf_force_estimator.h"
#include "estimator/linear_force_estimator.h"

namespace birotor {
namespace {

bool FiniteWithin(double value, double limit) { return std::isfinite(value) && std::abs(value) <= limit; }

// Stamps are microseconds on the vehicle clock: never negative, and below
// 2^53 us (285 years) so that every difference of two stamps is exact in a
// double and cannot overflow int64.
constexpr int64_t kMaxUtime = int64_t{1} << 53;
bool UtimeValid(int64_t utime) { return utime >= 0 && utime < kMaxUtime; }

bool IsFinite(const ForceEstimate& e) {
  for (int i = 0; i < 2; ++i) {
    if (!std::isfinite(e.force_n[i]) || !std::isfinite(e.force_std_n[i]) || !std::isfinite(e.thrust_scale[i])) {
      return false;
    }
  }
  return true;
}

InputCounters& Counters(PipelineHealth* health, InputChannel channel) {
  return health->inputs[static_cast<int>(channel)];
}

}  // namespace

const char* InputChannelName(InputChannel channel) {
  switch (channel) {
    case InputChannel::kStrain:
      return "STRAIN";
    case InputChannel::kMotor:
      return "MOTOR";
    case InputChannel::kImu:
      return "IMU";
    case InputChannel::kPose:
      return "POSE";
  }
  return "?";
}

const char* ResetReasonName(ResetReason reason) {
  switch (reason) {
    case ResetReason::kNone:
      return "";
    case ResetReason::kStart:
      return "start";
    case ResetReason::kGap:
      return "gap";
    case ResetReason::kTimeBackwards:
      return "time_backwards";
    case ResetReason::kNumerical:
      return "numerical";
  }
  return "?";
}

InputChannel InputChannelOf(FusionSource source) {
  switch (source) {
    case FusionSource::kStrain:
      return InputChannel::kStrain;
    case FusionSource::kTelemetry:
      return InputChannel::kMotor;
    case FusionSource::kGyro:
    case FusionSource::kAccelerometer:
      return InputChannel::kImu;
  }
  return InputChannel::kStrain;
}

std::unique_ptr<ForceEstimator> MakeForceEstimator(const EstimatorConfig& config) {
  if (config.method == "ekf") return std::make_unique<EkfForceEstimator>(config.vehicle, config.ekf);
  if (config.method == "inversion") return std::make_unique<InversionEstimator>(config.vehicle, config.inversion);
  if (config.method == "motor_map") return std::make_unique<MotorMapEstimator>(config.vehicle, config.motor_map);
  if (config.method == "linear_kf") {
    return std::make_unique<LinearForceEstimator>(config.vehicle, config.ekf, config.linear_model);
  }
  if (config.method == "luenberger") {
    return std::make_unique<LinearForceEstimator>(config.vehicle, config.ekf, config.linear_model, config.luenberger);
  }
  return nullptr;
}

double GateOf(const EstimatorConfig& config, InputChannel channel) {
  constexpr double kNoGate = std::numeric_limits<double>::quiet_NaN();
  // The linear methods (linear_kf, luenberger) gate strain and gyro with the
  // EKF's options; they use telemetry without a filter update.
  const bool linear = config.method == "linear_kf" || config.method == "luenberger";
  if (config.method != "ekf" && !linear) return kNoGate;
  switch (channel) {
    case InputChannel::kStrain:
      return config.ekf.strain_gate_nis;
    case InputChannel::kMotor:
      return linear ? kNoGate : config.ekf.telemetry_gate_nis;
    case InputChannel::kImu:
      return config.ekf.gyro_gate_nis;
    case InputChannel::kPose:
      return kNoGate;
  }
  return kNoGate;
}

EstimatorPipeline::EstimatorPipeline(const EstimatorConfig& config)
    : config_(config),
      method_(MakeForceEstimator(config)),
      tare_(config.vehicle, config.tare),
      rotor_speed_(config.vehicle, config.pipeline.motor_timeout_s),
      notch_(config.harmonic_notch),
      max_forward_jump_us_(static_cast<int64_t>(std::llround(config.pipeline.max_forward_jump_s * 1e6))) {
  if (!method_) throw std::invalid_argument("unknown estimation method '" + config.method + "'");
  method_->set_fusion_sink(this);
  calibration_ = GaugeCalibration::FromVehicle(config.vehicle);
  health_.gauge = calibration_;
  for (int i = 0; i < kNumInputChannels; ++i) health_.inputs[i].gate = GateOf(config, static_cast<InputChannel>(i));
  health_.accelerometer.gate =
      config.method == "ekf" ? config.ekf.accel_gate_nis : std::numeric_limits<double>::quiet_NaN();
}

EstimatorPipeline::~EstimatorPipeline() = default;

const char* EstimatorPipeline::method_name() const { return method_->Name(); }

void EstimatorPipeline::CountReceived(InputChannel channel) { ++Counters(&health_, channel).received; }
void EstimatorPipeline::CountDecodeError(InputChannel channel) { ++Counters(&health_, channel).decode_errors; }
void EstimatorPipeline::CountOverloadDrop(InputChannel channel) { ++Counters(&health_, channel).dropped_overload; }

void EstimatorPipeline::SetGaugeOffsets(const GaugeCalibration& calibration) {
  UseGaugeOffsets(calibration.offset_rad, calibration.offset_std_rad, calibration.source);
}

void EstimatorPipeline::UseGaugeOffsets(const double offset_rad[2], const double offset_std_rad[2],
                                        GaugeOffsetSource source) {
  double prior_std_rad[2];  // in deflection: o_i / s_i
  for (int i = 0; i < 2; ++i) {
    calibration_.offset_rad[i] = offset_rad[i];
    calibration_.offset_std_rad[i] = offset_std_rad[i];
    prior_std_rad[i] = offset_std_rad[i] / calibration_.scale[i];
  }
  calibration_.source = source;
  health_.gauge = calibration_;
  method_->SetGaugeOffsetPrior(prior_std_rad);
}

void EstimatorPipeline::UpdateReportedGaugeOffsets() {
  // o_i in use = calibration + s_i e_i, one sigma s_i std(e_i).
  double learned_rad[2], learned_std_rad[2];
  if (!method_->LearnedGaugeOffset(learned_rad, learned_std_rad)) return;
  for (int i = 0; i < 2; ++i) {
    health_.gauge.offset_rad[i] = calibration_.offset_rad[i] + calibration_.scale[i] * learned_rad[i];
    health_.gauge.offset_std_rad[i] = calibration_.scale[i] * learned_std_rad[i];
  }
}

void EstimatorPipeline::TakePeriod() {
  const auto clear = [](InputCounters* c) {
    c->accepted_in_period = 0;
    c->nis_sum = 0;
    c->nis_max = 0;
    c->nis_count = 0;
  };
  for (InputCounters& c : health_.inputs) clear(&c);
  clear(&health_.accelerometer);
}

void EstimatorPipeline::OnFusion(const FusionReport& report) {
  consistency_.Add(report);
  InputCounters& c = report.source == FusionSource::kAccelerometer ? health_.accelerometer
                                                                   : Counters(&health_, InputChannelOf(report.source));
  switch (report.outcome) {
    case FusionOutcome::kFused:
      ++c.fused;
      break;
    case FusionOutcome::kRejectedGate:
      ++c.rejected_gate;
      break;
    case FusionOutcome::kNotFused:
      ++c.not_fused;
      break;
  }
  if (std::isfinite(report.nis)) {
    c.nis_sum += report.nis;
    if (report.nis > c.nis_max) c.nis_max = report.nis;
    ++c.nis_count;
  }
}

EstimatorPipeline::TimeOrder EstimatorPipeline::CheckTime(const InputCounters& counters, int64_t utime) const {
  if (counters.last_utime < 0 || utime > counters.last_utime) return TimeOrder::kInOrder;
  if (utime == counters.last_utime) return TimeOrder::kDuplicate;
  const double back_s = (counters.last_utime - utime) * 1e-6;
  return back_s > config_.pipeline.time_backwards_reset_s ? TimeOrder::kBackwardsJump : TimeOrder::kOutOfOrder;
}

bool EstimatorPipeline::IsTimeOutlier(InputCounters* c, int64_t utime) {
  if (health_.newest_utime < 0 || utime - health_.newest_utime <= max_forward_jump_us_) {
    jump_candidate_utime_ = -1;
    jump_confirmations_ = 0;
    return false;
  }
  // Ahead of every input. Consecutive outliers within the bound of each other
  // (any input) confirm a jump of every stream.
  if (jump_confirmations_ > 0 && std::abs(utime - jump_candidate_utime_) <= max_forward_jump_us_) {
    ++jump_confirmations_;
  } else {
    jump_confirmations_ = 1;
  }
  jump_candidate_utime_ = utime;
  if (jump_confirmations_ >= config_.pipeline.forward_jump_confirm_samples) {
    jump_candidate_utime_ = -1;
    jump_confirmations_ = 0;
    return false;
  }
  ++c->time_outliers;
  return true;
}

bool EstimatorPipeline::Admit(InputChannel channel, int64_t utime, int32_t seq, bool* backwards_jump) {
  InputCounters* c = &Counters(&health_, channel);
  const TimeOrder order = CheckTime(*c, utime);
  if (order == TimeOrder::kDuplicate) {
    ++c->duplicates;
    CountViolation(channel, c->last_utime);
    return false;
  }
  if (order == TimeOrder::kOutOfOrder) {
    ++c->out_of_order;
    CountViolation(channel, c->last_utime);
    return false;
  }
  if (order == TimeOrder::kInOrder && IsTimeOutlier(c, utime)) return false;
  *backwards_jump = order == TimeOrder::kBackwardsJump;
  Accept(channel, utime, seq, *backwards_jump);
  return true;
}

void EstimatorPipeline::Accept(InputChannel channel, int64_t utime, int32_t seq, bool backwards_jump) {
  InputCounters* c = &Counters(&health_, channel);
  if (c->last_utime >= 0 && !backwards_jump) {
    // seq wraps at int32: compare in unsigned arithmetic.
    const uint32_t expected = static_cast<uint32_t>(c->last_seq) + 1u;
    const int32_t jump = static_cast<int32_t>(static_cast<uint32_t>(seq) - expected);
    if (jump > 0) {
      ++c->gaps;
      c->missing_samples += jump;
    } else if (jump < 0) {
      CountViolation(channel, utime);  // seq went backwards with a newer stamp: a second sender?
    }
  }
  c->last_utime = utime;
  c->last_seq = seq;
  ++c->accepted_in_period;
  ConflictDetector& d = conflict_[static_cast<int>(channel)];
  if (c->conflict_active && utime - d.last_violation_utime > config_.pipeline.conflict_clear_s * 1e6) {
    c->conflict_active = false;
    d.count = 0;
  }
  // The strain clock is the estimator's: a strain stamp far behind the newest
  // (a first sample of another input stamped in the future) takes it back.
  const bool strain_far_behind = channel == InputChannel::kStrain &&
                                 (health_.newest_utime - utime) * 1e-6 > config_.pipeline.time_backwards_reset_s;
  if (backwards_jump || strain_far_behind || utime > health_.newest_utime) health_.newest_utime = utime;
}

void EstimatorPipeline::CountViolation(InputChannel channel, int64_t utime) {
  ConflictDetector& d = conflict_[static_cast<int>(channel)];
  InputCounters& c = Counters(&health_, channel);
  const int needed = std::clamp(config_.pipeline.conflict_min_violations, 2, kMaxConflictViolations);
  d.violation_utime[d.next] = utime;
  d.next = (d.next + 1) % kMaxConflictViolations;
  d.count = std::min(d.count + 1, kMaxConflictViolations);
  d.last_violation_utime = utime;
  if (c.conflict_active || d.count < needed) return;
  // The needed-th newest violation, within the window of this one?
  const int64_t oldest = d.violation_utime[(d.next - needed + 2 * kMaxConflictViolations) % kMaxConflictViolations];
  if ((utime - oldest) * 1e-6 <= config_.pipeline.conflict_window_s) {
    c.conflict_active = true;
    ++c.conflicts;
  }
}

bool EstimatorPipeline::AnyConflictActive() const {
  // POSE is not used by any method: a conflict there is counted, not flagged.
  for (InputChannel channel : {InputChannel::kStrain, InputChannel::kMotor, InputChannel::kImu}) {
    if (health_.inputs[static_cast<int>(channel)].conflict_active) return true;
  }
  return false;
}

void EstimatorPipeline::ResetMethod(ResetReason reason, int64_t utime) {
  ++health_.resets;
  health_.last_reset_reason = reason;
  reset_flag_pending_ = true;
  consistency_.Restart();
  if (reason == ResetReason::kStart) return;  // the method is new: it keeps what it was given so far
  // What the method learned about the gauge offsets survives the reset.
  const GaugeCalibration learned = health_.gauge;
  method_->Reset();
  UseGaugeOffsets(learned.offset_rad, learned.offset_std_rad, learned.source);
  if (has_motor_ && last_motor_.utime <= utime &&
      (utime - last_motor_.utime) * 1e-6 <= config_.pipeline.motor_timeout_s) {
    // The command only: its telemetry was already given to (and reported by) the method.
    MotorSample command = last_motor_;
    command.omega_meas_rad_s[0] = command.omega_meas_rad_s[1] = std::numeric_limits<double>::quiet_NaN();
    method_->AddMotor(command);
  }
}

void EstimatorPipeline::OnMotor(const MotorSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kMotor);
  if (!UtimeValid(sample.utime)) {
    ++c.rejected_invalid;
    return;
  }
  const double limit = config_.pipeline.max_omega_rad_s;
  bool valid = FiniteWithin(sample.omega_cmd_rad_s[0], limit) && FiniteWithin(sample.omega_cmd_rad_s[1], limit);
  for (double meas : sample.omega_meas_rad_s) valid = valid && (std::isnan(meas) || FiniteWithin(meas, limit));
  if (!valid) {
    ++c.rejected_invalid;
    return;
  }
  bool backwards = false;
  if (!Admit(InputChannel::kMotor, sample.utime, sample.seq, &backwards)) return;
  if (std::isnan(sample.omega_meas_rad_s[0]) || std::isnan(sample.omega_meas_rad_s[1])) ++c.reading_missing;
  last_motor_ = sample;
  has_motor_ = true;
  tare_.AddMotor(sample);
  rotor_speed_.AddMotor(sample);
  method_->AddMotor(sample);  // fused / rejected / not fused: counted from its report
}

void EstimatorPipeline::OnImu(const ImuSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kImu);
  if (!UtimeValid(sample.utime)) {
    ++c.rejected_invalid;
    return;
  }
  if (!FiniteWithin(sample.gyro_y_rad_s, config_.pipeline.max_gyro_rad_s)) {
    ++c.rejected_invalid;
    return;
  }
  bool backwards = false;
  if (!Admit(InputChannel::kImu, sample.utime, sample.seq, &backwards)) return;
  // The accelerometer feeds the tare and the ground contact, which both skip
  // a NaN there (a missing reading); the gyro still counts.
  if (!std::isfinite(sample.accel_x_m_s2) || !std::isfinite(sample.accel_z_m_s2)) ++c.reading_missing;
  if (std::isfinite(sample.accel_z_m_s2)) {
    InputCounters& a = health_.accelerometer;
    ++a.received;
    ++a.accepted_in_period;
    a.last_utime = sample.utime;
    a.last_seq = sample.seq;
  }
  tare_.AddImu(sample);
  method_->AddImu(sample);
}

void EstimatorPipeline::OnPose(const PoseSample& sample) {
  InputCounters& c = Counters(&health_, InputChannel::kPose);
  if (!UtimeValid(sample.utime)) {
    ++c.rejected_invalid;
    return;
  }
  if (!std::isfinite(sample.x_m) || !std::isfinite(sample.z_m) || !std::isfinite(sample.phi_rad)) {
    ++c.rejected_invalid;
    return;
  }
  // Accepted for the health counters; no method uses the pose yet.
  bool backwards = false;
  Admit(InputChannel::kPose, sample.utime, sample.seq, &backwards);
}

bool EstimatorPipeline::OnStrain(const StrainSample& sample, ForceEstimate* estimate) {
  InputCounters& c = Counters(&health_, InputChannel::kStrain);
  if (!UtimeValid(sample.utime)) {
    ++c.rejected_invalid;
    return false;
  }
  const double limit = config_.pipeline.max_deflection_rad;
  if (!FiniteWithin(sample.deflection_rad[0], limit) || !FiniteWithin(sample.deflection_rad[1], limit)) {
    ++c.rejected_invalid;
    return false;
  }
  const int64_t previous_utime = c.last_utime;
  bool backwards = false;
  if (!Admit(InputChannel::kStrain, sample.utime, sample.seq, &backwards)) return false;

  bool stale = false;
  if (!started_) {
    ResetMethod(ResetReason::kStart, sample.utime);
    started_ = true;
  } else if (backwards) {
    ResetMethod(ResetReason::kTimeBackwards, sample.utime);
  } else {
    const double interval_s = (sample.utime - previous_utime) * 1e-6;
    if (interval_s > config_.pipeline.reset_gap_s) {
      ResetMethod(ResetReason::kGap, sample.utime);
    } else if (interval_s > config_.pipeline.strain_timeout_s) {
      stale = true;
    }
  }

  if (tare_.AddStrain(sample) == TareEvent::kAccepted) {
    UseGaugeOffsets(tare_.offset_rad(), tare_.offset_std_rad(), GaugeOffsetSource::kTare);
  }
  health_.tare = tare_.counters();

  StrainSample deflection = calibration_.Apply(sample);
  if (config_.harmonic_notch.enabled) {
    rotor_speed_.Advance(sample.utime);
    const double omega_rad_s[2] = {rotor_speed_.omega_rad_s(0), rotor_speed_.omega_rad_s(1)};
    const double dt_s = previous_utime >= 0 && !backwards ? (sample.utime - previous_utime) * 1e-6 : 0.0;
    notch_.Apply(dt_s, omega_rad_s, &deflection);
  }

  StrainStepInfo info;
  method_->AddStrain(deflection, estimate, &info);
  UpdateReportedGaugeOffsets();
  if (info.reset != ResetReason::kNone) {
    // The method re-initialised itself (its numerical guard).
    ++health_.resets;
    health_.last_reset_reason = info.reset;
    reset_flag_pending_ = true;
  }
  if (!IsFinite(*estimate)) {
    ResetMethod(ResetReason::kNumerical, sample.utime);
    if (has_finite_estimate_) {
      *estimate = last_finite_estimate_;
    } else {
      for (int i = 0; i < 2; ++i) {
        estimate->force_n[i] = config_.vehicle.HoverForceN();
        estimate->force_std_n[i] = config_.vehicle.HoverForceN();
        estimate->thrust_scale[i] = 1.0;
      }
    }
    estimate->utime = sample.utime;
    estimate->seq = sample.seq;
    estimate->status = kStatusConverging;
  } else {
    last_finite_estimate_ = *estimate;
    has_finite_estimate_ = true;
  }

  if (!has_motor_) {
    estimate->status |= kStatusNoMotorInput;
  } else if ((sample.utime - last_motor_.utime) * 1e-6 > config_.pipeline.motor_timeout_s) {
    stale = true;
  }
  // VALID means converged, fresh and from one publisher per input.
  if (stale) estimate->status = (estimate->status | kStatusInputStale) & ~kStatusValid;
  if (AnyConflictActive()) estimate->status = (estimate->status | kStatusInputConflict) & ~kStatusValid;
  consistency_.ApplyStatus(estimate);  // MODEL_MISMATCH withdraws VALID (docs/mismatch.md)
  health_.consistency = consistency_.state();
  if (reset_flag_pending_) {
    estimate->status |= kStatusFilterReset;
    reset_flag_pending_ = false;
  }

  ++health_.published;
  health_.last_status = estimate->status;
  health_.last_estimate = *estimate;
  return true;
}

}  // namespace birotor

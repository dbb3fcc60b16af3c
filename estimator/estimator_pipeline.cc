#include "estimator/estimator_pipeline.h"

#include <cmath>
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

EstimatorPipeline::EstimatorPipeline(const EstimatorConfig& config)
    : config_(config),
      method_(MakeForceEstimator(config)),
      tare_(config.vehicle, config.tare),
      rotor_speed_(config.vehicle, config.pipeline.motor_timeout_s),
      notch_(config.harmonic_notch) {
  if (!method_) throw std::invalid_argument("unknown estimation method '" + config.method + "'");
  health_.gauge = GaugeCalibration::FromVehicle(config.vehicle);
  health_.last_reset_reason.reserve(32);  // no allocation when a reason is set later
}

EstimatorPipeline::~EstimatorPipeline() = default;

const char* EstimatorPipeline::method_name() const { return method_->Name(); }

void EstimatorPipeline::CountReceived(InputChannel channel) { ++Counters(&health_, channel).received; }
void EstimatorPipeline::CountDecodeError(InputChannel channel) { ++Counters(&health_, channel).decode_errors; }
void EstimatorPipeline::CountOverloadDrop(InputChannel channel) { ++Counters(&health_, channel).dropped_overload; }

void EstimatorPipeline::SetGaugeOffsets(const GaugeCalibration& calibration) {
  for (int i = 0; i < 2; ++i) {
    health_.gauge.offset_rad[i] = calibration.offset_rad[i];
    health_.gauge.offset_std_rad[i] = calibration.offset_std_rad[i];
  }
  health_.gauge.source = calibration.source;
}

void EstimatorPipeline::TakePeriod() {
  for (InputCounters& c : health_.inputs) c.accepted_in_period = 0;
  health_.nis_sum = 0;
  health_.nis_max = 0;
  health_.nis_count = 0;
}

EstimatorPipeline::TimeOrder EstimatorPipeline::CheckTime(const InputCounters& counters, int64_t utime) const {
  if (counters.last_utime < 0 || utime > counters.last_utime) return TimeOrder::kInOrder;
  if (utime == counters.last_utime) return TimeOrder::kDuplicate;
  const double back_s = (counters.last_utime - utime) * 1e-6;
  return back_s > config_.pipeline.time_backwards_reset_s ? TimeOrder::kBackwardsJump : TimeOrder::kOutOfOrder;
}

bool EstimatorPipeline::Admit(InputCounters* c, int64_t utime, int32_t seq, bool* backwards_jump) {
  const TimeOrder order = CheckTime(*c, utime);
  if (order == TimeOrder::kDuplicate) {
    ++c->duplicates;
    return false;
  }
  if (order == TimeOrder::kOutOfOrder) {
    ++c->out_of_order;
    return false;
  }
  *backwards_jump = order == TimeOrder::kBackwardsJump;
  Accept(c, utime, seq, *backwards_jump);
  return true;
}

void EstimatorPipeline::Accept(InputCounters* c, int64_t utime, int32_t seq, bool backwards_jump) {
  if (c->last_utime >= 0 && !backwards_jump) {
    // seq wraps at int32: compare in unsigned arithmetic.
    const uint32_t expected = static_cast<uint32_t>(c->last_seq) + 1u;
    const int32_t jump = static_cast<int32_t>(static_cast<uint32_t>(seq) - expected);
    if (jump > 0) {
      ++c->gaps;
      c->missing_samples += jump;
    }
  }
  c->last_utime = utime;
  c->last_seq = seq;
  ++c->accepted_in_period;
  if (backwards_jump || utime > health_.newest_utime) health_.newest_utime = utime;
}

void EstimatorPipeline::ResetMethod(const char* reason, int64_t utime) {
  method_->Reset();
  ++health_.resets;
  health_.last_reset_reason = reason;  // short literals: fits the reserved capacity
  reset_flag_pending_ = true;
  if (has_motor_ && last_motor_.utime <= utime &&
      (utime - last_motor_.utime) * 1e-6 <= config_.pipeline.motor_timeout_s) {
    method_->AddMotor(last_motor_);
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
  if (!Admit(&c, sample.utime, sample.seq, &backwards)) return;
  if (std::isnan(sample.omega_meas_rad_s[0]) || std::isnan(sample.omega_meas_rad_s[1])) ++c.telemetry_missing;
  last_motor_ = sample;
  has_motor_ = true;
  tare_.AddMotor(sample);
  rotor_speed_.AddMotor(sample);
  method_->AddMotor(sample);
  ++c.fused;
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
  if (!Admit(&c, sample.utime, sample.seq, &backwards)) return;
  tare_.AddImu(sample);
  method_->AddImu(sample);
  const bool fuses_gyro = config_.method == "ekf" || config_.method == "linear_kf" || config_.method == "luenberger";
  if (fuses_gyro && config_.ekf.use_gyro) ++c.fused;
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
  Admit(&c, sample.utime, sample.seq, &backwards);
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
  if (!Admit(&c, sample.utime, sample.seq, &backwards)) return false;

  bool stale = false;
  if (!started_) {
    ResetMethod("start", sample.utime);
    started_ = true;
  } else if (backwards) {
    ResetMethod("time_backwards", sample.utime);
  } else {
    const double interval_s = (sample.utime - previous_utime) * 1e-6;
    if (interval_s > config_.pipeline.reset_gap_s) {
      ResetMethod("gap", sample.utime);
    } else if (interval_s > config_.pipeline.strain_timeout_s) {
      stale = true;
    }
  }

  if (tare_.AddStrain(sample) == TareEvent::kAccepted) {
    for (int i = 0; i < 2; ++i) {
      health_.gauge.offset_rad[i] = tare_.offset_rad()[i];
      health_.gauge.offset_std_rad[i] = tare_.offset_std_rad()[i];
    }
    health_.gauge.source = GaugeOffsetSource::kTare;
  }
  health_.tare = tare_.counters();

  StrainSample deflection = health_.gauge.Apply(sample);
  if (config_.harmonic_notch.enabled) {
    rotor_speed_.Advance(sample.utime);
    const double omega_rad_s[2] = {rotor_speed_.omega_rad_s(0), rotor_speed_.omega_rad_s(1)};
    const double dt_s = previous_utime >= 0 && !backwards ? (sample.utime - previous_utime) * 1e-6 : 0.0;
    notch_.Apply(dt_s, omega_rad_s, &deflection);
  }

  StrainUpdateInfo info;
  method_->AddStrain(deflection, estimate, &info);
  if (info.reset) {
    // The method re-initialised itself (its own dt bound or a numerical guard).
    ++health_.resets;
    health_.last_reset_reason = "numerical";
    reset_flag_pending_ = true;
  }
  if (!IsFinite(*estimate)) {
    ResetMethod("numerical", sample.utime);
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
    info.fused = false;
  } else {
    last_finite_estimate_ = *estimate;
    has_finite_estimate_ = true;
  }

  if (!has_motor_) {
    estimate->status |= kStatusNoMotorInput;
  } else if ((sample.utime - last_motor_.utime) * 1e-6 > config_.pipeline.motor_timeout_s) {
    stale = true;
  }
  if (stale) estimate->status |= kStatusInputStale;
  if (reset_flag_pending_) {
    estimate->status |= kStatusFilterReset;
    reset_flag_pending_ = false;
  }

  if (info.fused) ++c.fused;
  if (info.gated) ++c.rejected_gate;
  if (std::isfinite(info.nis)) {
    health_.nis_sum += info.nis;
    if (info.nis > health_.nis_max) health_.nis_max = info.nis;
    ++health_.nis_count;
  }
  ++health_.published;
  health_.last_status = estimate->status;
  health_.last_estimate = *estimate;
  return true;
}

}  // namespace birotor

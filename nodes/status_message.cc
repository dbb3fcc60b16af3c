// ESTIMATOR_STATUS message building and processing-time statistics.
#include "nodes/status_message.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/percentile.h"
#include "samples/rotor_count.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"

namespace birotor {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMicrosecondsPerSecond = 1e6;
}  // namespace

void ProcessingTimeStats::Add(double time_us) {
  ring_[next_] = time_us;
  next_ = (next_ + 1) % kCapacity;
  ++count_;
  sum_us_ += time_us;
  max_us_ = std::max(max_us_, time_us);
}

double ProcessingTimeStats::MeanUs() const { return count_ > 0 ? sum_us_ / static_cast<double>(count_) : kNaN; }

double ProcessingTimeStats::MaxUs() const { return count_ > 0 ? max_us_ : kNaN; }

double ProcessingTimeStats::P99Us() {
  if (count_ == 0) return kNaN;
  const int n = static_cast<int>(std::min<int64_t>(count_, kCapacity));
  // The newest n samples end just before next_.
  for (int i = 0; i < n; ++i) {
    scratch_[i] = ring_[(next_ - n + i + kCapacity) % kCapacity];
  }
  return Percentile(scratch_.begin(), scratch_.begin() + n, 0.99);
}

void ProcessingTimeStats::TakePeriod() {
  count_ = 0;
  sum_us_ = 0;
  max_us_ = 0;
}

namespace {

// One input's counters as published; ages on the vehicle clock.
void FillInputHealth(const InputCounters& in, const char* channel, int64_t newest_utime, const StatusContext& context,
                     input_health_t* out) {
  out->channel = channel;
  out->received = in.received;
  out->fused = in.fused;
  out->rejected_gate = in.rejected_gate;
  out->rejected_invalid = in.rejected_invalid;
  out->decode_errors = in.decode_errors;
  out->out_of_order = in.out_of_order;
  out->duplicates = in.duplicates;
  out->gaps = in.gaps;
  out->missing_samples = in.missing_samples;
  out->reading_missing = in.reading_missing;
  out->dropped_overload = in.dropped_overload;
  // A sample newer than the vehicle clock (the clock went back after it) has
  // no meaningful age.
  out->age_s = (in.last_utime >= 0 && newest_utime >= in.last_utime)
                   ? static_cast<double>(newest_utime - in.last_utime) / kMicrosecondsPerSecond
                   : kNaN;
  out->rate_hz = context.period_s > 0 ? static_cast<double>(in.accepted_in_period) / context.period_s : kNaN;
  out->not_fused = in.not_fused;
  out->time_outliers = in.time_outliers;
  out->conflicts = in.conflicts;
  out->conflict_active = in.conflict_active ? 1 : 0;
  out->nis_mean = in.nis_count > 0 ? in.nis_sum / static_cast<double>(in.nis_count) : kNaN;
  out->nis_max = in.nis_count > 0 ? in.nis_max : kNaN;
  out->gate = in.gate;
}

}  // namespace

const char* StrainScaleSource(const PipelineHealth& health) {
  if (!health.gauge.has_strain_scale) return kLearnedSourceParams;
  return health.strain_scale_from_state_file ? kLearnedSourceStateFile : kLearnedSourceLearned;
}

namespace {

// The slow vehicle parameters in use: learned (value and sigma) or the
// file's (scale 1, the file's body mass, sigma NaN).
void FillLearnedParameters(const PipelineHealth& health, estimator_status_t* message) {
  const bool scale_learned = health.gauge.has_strain_scale;
  for (int arm = 0; arm < kBirotorRotors; ++arm) {
    message->strain_scale[arm] = scale_learned ? health.gauge.strain_scale[arm] : 1.0;
    message->strain_scale_std[arm] = scale_learned ? health.gauge.strain_scale_std[arm] : kNaN;
  }
  message->strain_scale_source = StrainScaleSource(health);
  message->body_mass_kg = health.body_mass_kg;
  message->body_mass_std_kg = health.body_mass_learned ? health.body_mass_std_kg : kNaN;
  message->body_mass_source = health.body_mass_learned ? kLearnedSourceLearned : kLearnedSourceParams;
}

// What every estimator node's status has: stamps, method, status, the
// per-input counters (inputs in InputChannel order, then the
// accelerometer's), the strain NIS, processing times, resets, estimates.
struct CommonStatus {
  int64_t newest_utime;
  const char* method;
  int32_t status;
  const InputCounters* inputs;  // kNumInputChannels of them
  const InputCounters* accelerometer;
  int64_t resets;
  ResetReason last_reset_reason;
  int64_t published;
};

void FillCommonStatus(const CommonStatus& c, const StatusContext& context, estimator_status_t* message) {
  message->utime = c.newest_utime;
  message->wall_utime = context.wall_utime;
  message->seq = context.seq;
  message->method = c.method;
  message->status = c.status;
  message->num_inputs = kNumInputChannels;
  message->inputs.resize(kNumInputChannels);
  for (int i = 0; i < kNumInputChannels; ++i) {
    FillInputHealth(c.inputs[i], InputChannelName(static_cast<InputChannel>(i)), c.newest_utime, context,
                    &message->inputs[i]);
  }
  FillInputHealth(*c.accelerometer, "IMU accel_z", c.newest_utime, context, &message->accelerometer);
  const input_health_t& strain = message->inputs[static_cast<int>(InputChannel::kStrain)];
  message->strain_nis_mean = strain.nis_mean;
  message->strain_nis_max = strain.nis_max;
  message->strain_gate = strain.gate;
  message->processing_time_mean_us = context.processing_time_mean_us;
  message->processing_time_p99_us = context.processing_time_p99_us;
  message->processing_time_max_us = context.processing_time_max_us;
  message->resets = c.resets;
  message->last_reset_reason = ResetReasonName(c.last_reset_reason);
  message->published = c.published;
  message->udp_datagrams = context.udp.datagrams;
  message->udp_fragments_dropped = context.udp.fragments_dropped;
  message->udp_malformed_dropped = context.udp.malformed_dropped;
  message->udp_kernel_dropped = context.udp.kernel_dropped;
  message->vehicle_checksum = context.vehicle_checksum;
}

}  // namespace

void BuildStatusMessage(const PipelineHealth& health, const char* method, const StatusContext& context,
                        estimator_status_t* message) {
  FillCommonStatus({health.newest_utime, method, health.last_status, health.inputs, &health.accelerometer,
                    health.resets, health.last_reset_reason, health.published},
                   context, message);
  for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
    message->force_n[rotor] = health.last_estimate.force_n[rotor];
    message->thrust_scale[rotor] = health.last_estimate.thrust_scale[rotor];
    message->gauge_offset_rad[rotor] = health.gauge.offset_rad[rotor];
    message->gauge_offset_std_rad[rotor] = health.gauge.offset_std_rad[rotor];
  }
  message->gauge_offset_source = GaugeOffsetSourceName(health.gauge.source);
  message->tares = health.tare.accepted;
  message->tares_refused_motors_running = health.tare.refused_motors_running;
  message->tares_refused_body_moving = health.tare.refused_body_moving;
  message->tares_refused_out_of_range = health.tare.refused_out_of_range;
  message->last_tare_refusal = TareRefusalName(health.tare.last_refusal);
  message->model_consistency_statistic = health.consistency.ReportedStatistic();
  message->mismatch_parameter = MismatchParameterName(health.consistency.parameter);
  FillLearnedParameters(health, message);
  message->vehicle_checksum = context.vehicle_checksum;
}

void BuildMultiArmStatusMessage(const MultiArmPipelineHealth& health, const char* method, const StatusContext& context,
                                estimator_status_t* message) {
  FillCommonStatus({health.newest_utime, method, health.last_status, health.inputs, &health.accelerometer,
                    health.resets, health.last_reset_reason, health.published},
                   context, message);
  // The birotor's two-element fields: the forces are on FORCE_N.
  for (int rotor = 0; rotor < kBirotorRotors; ++rotor) {
    message->force_n[rotor] = message->thrust_scale[rotor] = kNaN;
    message->gauge_offset_rad[rotor] = message->gauge_offset_std_rad[rotor] = kNaN;
    message->strain_scale[rotor] = message->strain_scale_std[rotor] = kNaN;
  }
  message->gauge_offset_source = GaugeOffsetSourceName(health.gauge_offset_source);
  message->last_tare_refusal = "";
  message->model_consistency_statistic = health.consistency.ReportedStatistic();
  message->mismatch_parameter = MismatchParameterName(health.consistency.parameter);
  message->strain_scale_source = kLearnedSourceParams;
  message->body_mass_kg = kNaN;
  message->body_mass_std_kg = kNaN;
  message->body_mass_source = kLearnedSourceParams;
}

bool ReadLastLearnedStatus(const std::string& log_path, const std::string& channel, estimator_status_t* status,
                           std::string* error) {
  LogReader reader;
  if (!reader.Open(log_path, error)) return false;
  LogEvent event;
  estimator_status_t message;
  int64_t found = 0, undecodable = 0;
  while (reader.Next(&event)) {
    if (event.channel != channel) continue;
    if (DecodeMessage(event.data.data(), event.data.size(), &message) != DecodeError::kNone) {
      ++undecodable;  // another layout (an older estimator) or damage
      continue;
    }
    if (message.strain_scale_source != kLearnedSourceParams || message.body_mass_source != kLearnedSourceParams) {
      *status = message;
      ++found;
    }
  }
  if (found == 0) {
    *error = log_path + ": no " + channel + " message with a learned value (" + std::to_string(undecodable) +
             " undecodable; the estimator learns with estimator.ekf learn_strain_scale / learn_body_mass on)";
    return false;
  }
  return true;
}

}  // namespace birotor

// The estimator node: checked decoding, FORCE and ESTIMATOR_STATUS publication.
#include "nodes/estimator_service.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "estimator/force_status.h"
#include "nodes/estimator_learned_message.h"
#include "nodes/gauge_state_file.h"
#include "nodes/guard_status_message.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// FNV-1a over a payload: tells our own FORCE from another publisher's (not a
// security check; a forger can always send our exact bytes).
uint64_t PayloadHash(const void* data, size_t size) {
  uint64_t hash = 14695981039346656037ull;
  const uint8_t* bytes = static_cast<const uint8_t*>(data);
  for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  return hash;
}

}  // namespace

EstimatorService::EstimatorService(const EstimatorConfig& config, const ChannelNames& channels,
                                   const EstimatorServiceOptions& options, MessageSink* sink)
    : pipeline_(config),
      description_(config.vehicle),
      vehicle_checksum_(VehicleChecksum(BirotorModelOf(config.vehicle))),
      channels_(channels),
      options_(options),
      sink_(sink),
      arm_count_warning_(options.warning_interval_s),
      foreign_warning_(options.warning_interval_s),
      decode_warning_(options.warning_interval_s),
      arrival_(options.overload_max_delay_s, options.stale_input_wall_s, options.warning_interval_s),
      mismatch_warning_(options.warning_interval_s),
      rejection_log_(options.warning_interval_s, input_channel_names_) {
  input_channel_names_[static_cast<int>(InputChannel::kStrain)] = &channels_.strain;
  input_channel_names_[static_cast<int>(InputChannel::kMotor)] = &channels_.motor;
  input_channel_names_[static_cast<int>(InputChannel::kImu)] = &channels_.imu;
  input_channel_names_[static_cast<int>(InputChannel::kPose)] = &channels_.pose;
  // The route table: every channel this node reads, once.
  routes_.Add(channels_.strain, EstimatorChannel::kStrain);
  routes_.Add(channels_.motor, EstimatorChannel::kMotor);
  routes_.Add(channels_.imu, EstimatorChannel::kImu);
  routes_.Add(channels_.pose, EstimatorChannel::kPose);
  routes_.Add(channels_.strain_n, EstimatorChannel::kStrainN);
  routes_.Add(channels_.motor_n, EstimatorChannel::kMotorN);
  routes_.Add(channels_.force, EstimatorChannel::kOwnForce);
  buffer_.reserve(1024);
  status_message_.inputs.resize(kNumInputChannels);
  PrepareEstimatorLearned(description_, &learned_message_);
}

EstimatorService::~EstimatorService() = default;

bool EstimatorService::IsInputChannel(std::string_view channel) const {
  EstimatorChannel routed;
  return routes_.Find(channel, &routed) && routed != EstimatorChannel::kOwnForce;
}

void EstimatorService::HandlePacket(std::string_view channel, const void* data, size_t size,
                                    int64_t receive_wall_utime) {
  EstimatorChannel routed;
  if (!routes_.Find(channel, &routed)) return;
  InputChannel input;
  if (Dispatch(routed, data, size, receive_wall_utime, &input)) rejection_log_.Check(pipeline_.health(), input);
}

void EstimatorService::CheckOwnForceChannel(const void* data, size_t size) {
  const uint64_t hash = PayloadHash(data, size);
  for (size_t i = 0; i < kPublishedHashCount; ++i) {
    if (published_hashes_[i] != hash) continue;
    if (!published_seen_[i]) {
      published_seen_[i] = true;  // our own, looped back
      return;
    }
    break;  // the same bytes a second time: another publisher
  }
  ++foreign_forces_;
  const int64_t now_us = SteadyClockUs();
  last_foreign_force_us_ = now_us;
  if (foreign_warning_.ShouldLog(now_us)) {
    spdlog::warn(
        "a FORCE this estimator did not publish arrived on {} (a second estimator on the prefix?): "
        "FORCE says INPUT_CONFLICT, not VALID; {} foreign FORCE so far",
        channels_.force, foreign_forces_);
  }
}

void EstimatorService::PublishGuardStatus(int64_t utime, int64_t wall_utime) {
  if (authentication_ == nullptr) return;
  ++guard_status_.seq;
  BuildGuardStatus(guard_status_t::PROGRAM_ESTIMATOR, utime, wall_utime, signing_, authentication_, nullptr,
                   &guard_status_);
  EncodeMessage(guard_status_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.guard_status, utime, buffer_.data(), buffer_.size());
}

bool EstimatorService::ForeignForceActive() const {
  return last_foreign_force_us_ >= 0 &&
         static_cast<double>(SteadyClockUs() - last_foreign_force_us_) < options_.foreign_force_hold_s * 1e6;
}

bool EstimatorService::Decoded(InputChannel channel, DecodeError error) {
  if (error == DecodeError::kNone) return true;
  pipeline_.CountDecodeError(channel);
  if (decode_warning_.ShouldLog(SteadyClockUs())) {
    spdlog::warn("undecodable {} packet ({}); {} similar warnings suppressed", InputChannelName(channel),
                 DecodeErrorName(error), decode_warning_.suppressed());
  }
  return false;
}

template <class CountedMessage>
bool EstimatorService::ArmCountMatches(const CountedMessage& message, InputChannel input, CountRefusals* refusals) {
  const CountCheck check = CheckCount(message, description_);
  if (check == CountCheck::kMatches) return true;
  refusals->Count(check);
  arm_count_refusals_.last = check;
  pipeline_.CountDecodeError(input);
  if (arm_count_warning_.ShouldLog(SteadyClockUs())) {
    spdlog::warn("counted {} message refused ({}: this vehicle has {} arms); {} similar warnings suppressed",
                 InputChannelName(input), CountCheckName(check), description_.arm_count,
                 arm_count_warning_.suppressed());
  }
  return false;
}

bool EstimatorService::Dispatch(EstimatorChannel channel, const void* data, size_t size, int64_t receive_wall_utime,
                                InputChannel* input) {
  switch (channel) {
    case EstimatorChannel::kStrain:
      *input = InputChannel::kStrain;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &strain_message_))) HandleStrain(receive_wall_utime);
      return true;
    case EstimatorChannel::kStrainN:
      // The birotor's strain_t field for field (transport/counted_messages.h).
      *input = InputChannel::kStrain;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &strain_n_message_)) &&
          ArmCountMatches(strain_n_message_, *input, &arm_count_refusals_.strain) &&
          ToBirotorMessage(strain_n_message_, &strain_message_)) {
        HandleStrain(receive_wall_utime);
      }
      return true;
    case EstimatorChannel::kMotor:
      *input = InputChannel::kMotor;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &motor_message_))) pipeline_.OnMotor(FromMessage(motor_message_));
      return true;
    case EstimatorChannel::kMotorN:
      *input = InputChannel::kMotor;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &motor_n_message_)) &&
          ArmCountMatches(motor_n_message_, *input, &arm_count_refusals_.motor) &&
          ToBirotorMessage(motor_n_message_, &motor_message_)) {
        pipeline_.OnMotor(FromMessage(motor_message_));
      }
      return true;
    case EstimatorChannel::kImu:
      *input = InputChannel::kImu;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &imu_message_))) pipeline_.OnImu(FromMessage(imu_message_));
      return true;
    case EstimatorChannel::kPose:
      *input = InputChannel::kPose;
      pipeline_.CountReceived(*input);
      if (Decoded(*input, DecodeMessage(data, size, &pose_message_))) pipeline_.OnPose(FromMessage(pose_message_));
      return true;
    case EstimatorChannel::kOwnForce:
      CheckOwnForceChannel(data, size);
      return false;
  }
  return false;
}

void EstimatorService::HandleStrain(int64_t receive_wall_utime) {
  const int64_t start_us = options_.report_processing_time ? SteadyClockUs() : 0;
  if (arrival_.Shed(receive_wall_utime, strain_message_.seq)) {
    pipeline_.CountOverloadDrop(InputChannel::kStrain);
    return;
  }
  ForceEstimate estimate;
  if (!pipeline_.OnStrain(FromMessage(strain_message_), &estimate)) return;
  force_message_ = ToMessage(estimate);
  // The pipeline's facts with the transport's (a second FORCE publisher).
  ForceStatusFacts facts = pipeline_.health().last_status_facts;
  facts.transport.foreign_force = foreign_forces_ > 0 && ForeignForceActive();
  force_message_.status = ComposeForceStatus(facts);
  EncodeMessage(force_message_, &buffer_);
  if (!buffer_.empty()) {
    published_hashes_[published_hash_next_] = PayloadHash(buffer_.data(), buffer_.size());
    published_seen_[published_hash_next_] = false;
    published_hash_next_ = (published_hash_next_ + 1) % kPublishedHashCount;
    sink_->Publish(channels_.force, estimate.utime, buffer_.data(), buffer_.size());
    ++forces_published_;
  }
  if (options_.report_processing_time) {
    processing_time_.Add(static_cast<double>(SteadyClockUs() - start_us));
  }
}

void EstimatorService::PublishStatus(int64_t wall_utime, double period_s) {
  StatusContext context;
  context.wall_utime = wall_utime;
  context.seq = status_seq_;
  context.period_s = period_s;
  context.vehicle_checksum = vehicle_checksum_.c_str();
  if (options_.report_processing_time) {
    context.processing_time_mean_us = processing_time_.MeanUs();
    context.processing_time_p99_us = processing_time_.P99Us();
    context.processing_time_max_us = processing_time_.MaxUs();
  } else {
    context.processing_time_mean_us = kNaN;
    context.processing_time_p99_us = kNaN;
    context.processing_time_max_us = kNaN;
  }
  if (udp_counters_ != nullptr) context.udp = *udp_counters_;
  BuildStatusMessage(pipeline_.health(), pipeline_.method_name(), context, &status_message_);
  const ModelConsistencyState& consistency = pipeline_.health().consistency;
  if (consistency.mismatch && mismatch_warning_.ShouldLog(SteadyClockUs())) {
    spdlog::warn(
        "model mismatch: the vehicle does not match its parameter file (statistic {:.2f}, most likely {}); "
        "fix: birotor-identify on this flight's log or on a bench run, then fly with the identified file "
        "(docs/mismatch.md); forces are not VALID meanwhile ({} similar lines suppressed)",
        consistency.ReportedStatistic(), MismatchParameterName(consistency.parameter), mismatch_warning_.suppressed());
  }
  // The newest FORCE's facts with the transport's now: no strain on the host
  // clock, a second FORCE publisher.
  ForceStatusFacts facts = pipeline_.health().last_status_facts;
  facts.transport.no_strain_on_wall_clock = arrival_.Stale(wall_utime);
  facts.transport.foreign_force = foreign_forces_ > 0 && ForeignForceActive();
  status_message_.status = ComposeForceStatus(facts);
  status_message_.foreign_force = foreign_forces_;
  EncodeMessage(status_message_, &buffer_);
  if (!buffer_.empty()) {
    const int64_t timestamp_us = pipeline_.health().newest_utime >= 0 ? pipeline_.health().newest_utime : 0;
    sink_->Publish(channels_.estimator_status, timestamp_us, buffer_.data(), buffer_.size());
    FillEstimatorLearned(pipeline_.health(), pipeline_.config(), status_message_, &learned_message_);
    EncodeMessage(learned_message_, &buffer_);
    if (!buffer_.empty()) sink_->Publish(channels_.estimator_learned_n, timestamp_us, buffer_.data(), buffer_.size());
    PublishGuardStatus(timestamp_us, wall_utime);
  }
  ++status_seq_;
  pipeline_.TakePeriod();
  processing_time_.TakePeriod();
}

void EstimatorService::PublishStatusOnVehicleClock() {
  const int64_t now_utime = pipeline_.health().newest_utime;
  double period_s = 0;
  if (status_schedule_.Due(now_utime, options_.status_rate_hz, &period_s)) PublishStatus(now_utime, period_s);
}

}  // namespace birotor

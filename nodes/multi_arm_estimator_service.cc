// The N-arm estimator node: checked decoding, FORCE_N and ESTIMATOR_STATUS.
#include "nodes/multi_arm_estimator_service.h"

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "estimator/force_status.h"
#include "model/vehicle_description_checksum.h"
#include "nodes/estimator_learned_message.h"
#include "transport/host_clock.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

MultiArmEstimatorService::MultiArmEstimatorService(const EstimatorConfig& config, const ChannelNames& channels,
                                                   const EstimatorServiceOptions& options, MessageSink* sink)
    : pipeline_(config),
      vehicle_checksum_(DescriptionChecksum(config.vehicle)),
      channels_(channels),
      options_(options),
      sink_(sink),
      decode_warning_(options.warning_interval_s),
      arrival_(options.overload_max_delay_s, options.stale_input_wall_s, options.warning_interval_s),
      arm_count_warning_(options.warning_interval_s) {
  routes_.Add(channels_.strain_n, Route::kStrainN);
  routes_.Add(channels_.motor_n, Route::kMotorN);
  routes_.Add(channels_.imu, Route::kImu);
  routes_.Add(channels_.pose, Route::kPose);
  buffer_.reserve(1024);
  status_message_.inputs.resize(kNumInputChannels);
  PrepareEstimatorLearned(pipeline_.vehicle(), &learned_message_);
}

bool MultiArmEstimatorService::IsInputChannel(std::string_view channel) const {
  Route route;
  return routes_.Find(channel, &route);
}

void MultiArmEstimatorService::HandlePacket(std::string_view channel, const void* data, size_t size,
                                            int64_t receive_wall_utime) {
  Route route;
  if (routes_.Find(channel, &route)) Dispatch(route, data, size, receive_wall_utime);
}

bool MultiArmEstimatorService::Decoded(InputChannel input, DecodeError error) {
  if (error == DecodeError::kNone) return true;
  pipeline_.CountDecodeError(input);
  if (decode_warning_.ShouldLog(SteadyClockUs())) {
    spdlog::warn("undecodable {} packet ({}); {} similar warnings suppressed", InputChannelName(input),
                 DecodeErrorName(error), decode_warning_.suppressed());
  }
  return false;
}

template <class CountedMessage>
bool MultiArmEstimatorService::CountMatches(const CountedMessage& message, InputChannel input,
                                            CountRefusals* refusals) {
  const CountCheck check = CheckCount(message, pipeline_.vehicle());
  if (check == CountCheck::kMatches) return true;
  refusals->Count(check);
  arm_count_refusals_.last = check;
  pipeline_.CountDecodeError(input);
  if (arm_count_warning_.ShouldLog(SteadyClockUs())) {
    spdlog::warn("counted {} message refused ({}: this vehicle has {} arms); {} similar warnings suppressed",
                 InputChannelName(input), CountCheckName(check), pipeline_.vehicle().arm_count,
                 arm_count_warning_.suppressed());
  }
  return false;
}

void MultiArmEstimatorService::Dispatch(Route route, const void* data, size_t size, int64_t receive_wall_utime) {
  switch (route) {
    case Route::kStrainN:
      pipeline_.CountReceived(InputChannel::kStrain);
      if (Decoded(InputChannel::kStrain, DecodeMessage(data, size, &strain_message_)) &&
          CountMatches(strain_message_, InputChannel::kStrain, &arm_count_refusals_.strain)) {
        HandleStrain(receive_wall_utime);
      }
      return;
    case Route::kMotorN:
      pipeline_.CountReceived(InputChannel::kMotor);
      if (Decoded(InputChannel::kMotor, DecodeMessage(data, size, &motor_message_)) &&
          CountMatches(motor_message_, InputChannel::kMotor, &arm_count_refusals_.motor)) {
        FromMessage(motor_message_, &motor_sample_);
        pipeline_.OnMotor(motor_sample_);
      }
      return;
    case Route::kImu:
      pipeline_.CountReceived(InputChannel::kImu);
      if (Decoded(InputChannel::kImu, DecodeMessage(data, size, &imu_message_))) {
        pipeline_.OnImu(FromMessage(imu_message_));
      }
      return;
    case Route::kPose:
      pipeline_.CountReceived(InputChannel::kPose);
      if (Decoded(InputChannel::kPose, DecodeMessage(data, size, &pose_message_))) {
        pipeline_.OnPose(FromMessage(pose_message_));
      }
      return;
  }
}

void MultiArmEstimatorService::HandleStrain(int64_t receive_wall_utime) {
  const int64_t start_us = options_.report_processing_time ? SteadyClockUs() : 0;
  if (arrival_.Shed(receive_wall_utime, strain_message_.seq)) {
    pipeline_.CountOverloadDrop(InputChannel::kStrain);
    return;
  }
  FromMessage(strain_message_, &strain_sample_);
  MultiArmForceEstimate estimate;
  if (!pipeline_.OnStrain(strain_sample_, &estimate)) return;
  ToMessage(estimate, &force_message_);
  EncodeMessage(force_message_, &buffer_);
  if (!buffer_.empty()) {
    sink_->Publish(channels_.force_n, estimate.utime, buffer_.data(), buffer_.size());
    ++forces_published_;
  }
  if (options_.report_processing_time) processing_time_.Add(static_cast<double>(SteadyClockUs() - start_us));
}

void MultiArmEstimatorService::PublishStatus(int64_t wall_utime, double period_s) {
  StatusContext context;
  context.wall_utime = wall_utime;
  context.seq = status_seq_;
  context.period_s = period_s;
  context.vehicle_checksum = vehicle_checksum_.c_str();
  const bool timed = options_.report_processing_time;
  context.processing_time_mean_us = timed ? processing_time_.MeanUs() : kNaN;
  context.processing_time_p99_us = timed ? processing_time_.P99Us() : kNaN;
  context.processing_time_max_us = timed ? processing_time_.MaxUs() : kNaN;
  BuildMultiArmStatusMessage(pipeline_.health(), pipeline_.config().method.c_str(), context, &status_message_);
  // No strain on the host clock for stale_input_wall_s: INPUT_STALE, not VALID.
  TransportStatusFacts transport;
  transport.no_strain_on_wall_clock = arrival_.Stale(wall_utime);
  const MultiArmPipelineHealth& health = pipeline_.health();
  status_message_.status =
      ComposeMultiArmForceStatus(health.last_filter_facts, health.last_input_facts, health.last_consistency_facts,
                                 transport, pipeline_.vehicle().arm_count)
          .status;
  EncodeMessage(status_message_, &buffer_);
  if (!buffer_.empty()) {
    const int64_t timestamp_us = pipeline_.health().newest_utime >= 0 ? pipeline_.health().newest_utime : 0;
    sink_->Publish(channels_.estimator_status, timestamp_us, buffer_.data(), buffer_.size());
    FillEstimatorLearned(health, pipeline_.config(), status_message_, &learned_message_);
    EncodeMessage(learned_message_, &buffer_);
    if (!buffer_.empty()) sink_->Publish(channels_.estimator_learned_n, timestamp_us, buffer_.data(), buffer_.size());
  }
  ++status_seq_;
  pipeline_.TakePeriod();
  processing_time_.TakePeriod();
}

void MultiArmEstimatorService::PublishStatusOnVehicleClock() {
  const int64_t now_utime = pipeline_.health().newest_utime;
  double period_s = 0;
  if (status_schedule_.Due(now_utime, options_.status_rate_hz, &period_s)) PublishStatus(now_utime, period_s);
}

}  // namespace birotor

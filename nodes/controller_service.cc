// The controller node: checked decoding,
// the vehicle clock, MOTOR_COMMAND and CONTROLLER_STATUS.
#include "nodes/controller_service.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "numerics/percentile.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// FORCE comes once per strain sample (1 kHz reference): a FORCE this much
// before the period is due still triggers it, so every other one does [us].
constexpr int64_t kForceTriggerEarlyUs = 500;

}  // namespace

ControllerService::ControllerService(const ControllerConfig& config, const ChannelNames& channels, MessageSink* sink)
    : controller_(config),
      channels_(channels),
      sink_(sink),
      period_us_(std::max<int64_t>(1, std::llround(1e6 / config.gains.rate_hz))) {
  buffer_.reserve(256);
}

ControllerService::~ControllerService() = default;

std::vector<std::string> ControllerService::InputChannels() const {
  return {channels_.pose, channels_.imu, channels_.force};
}

void ControllerService::HandlePacket(std::string_view channel, const void* data, size_t size,
                                     int64_t /*receive_wall_utime*/) {
  const std::string* names[kNumControllerInputs] = {&channels_.pose, &channels_.imu, &channels_.force};
  for (int i = 0; i < kNumControllerInputs; ++i) {
    if (channel == *names[i]) {
      HandlePacket(static_cast<ControllerInput>(i), data, size, SteadyClockUs());
      return;
    }
  }
}

void ControllerService::NoteInputTime(int64_t utime, int64_t host_us) {
  if (utime > newest_utime_) {
    newest_utime_ = utime;
    newest_host_us_ = host_us;
  }
}

int64_t ControllerService::VehicleTimeUs(int64_t host_us) const {
  return newest_utime_ < 0 ? -1 : newest_utime_ + std::max<int64_t>(0, host_us - newest_host_us_);
}

void ControllerService::HandlePacket(ControllerInput input, const void* data, size_t size, int64_t host_us) {
  const int index = static_cast<int>(input);
  switch (input) {
    case ControllerInput::kPose: {
      pose_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t accepted_before = health().pose.accepted;
      controller_.OnPose(FromMessage(message));
      if (health().pose.accepted > accepted_before) NoteInputTime(message.utime, host_us);
      return;
    }
    case ControllerInput::kImu: {
      imu_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t accepted_before = health().imu.accepted;
      controller_.OnImu(FromMessage(message));
      if (health().imu.accepted > accepted_before) NoteInputTime(message.utime, host_us);
      return;
    }
    case ControllerInput::kForce: {
      force_estimate_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t accepted_before = health().force.accepted;
      controller_.OnForce(FromMessage(message));
      if (health().force.accepted == accepted_before) return;
      NoteInputTime(message.utime, host_us);
      last_force_host_us_ = host_us;
      if (!controller_.has_pose()) return;  // nothing to fly on yet: the ESCs hold what they have
      // Triggered on the vehicle clock (strain stamps have no jitter): every
      // other FORCE at 1 kHz.
      if (last_period_vehicle_us_ < 0 || message.utime - last_period_vehicle_us_ >= period_us_ - kForceTriggerEarlyUs) {
        RunControlPeriod(message.utime, host_us);  // the command carries its FORCE's (strain's) utime
      }
      return;
    }
  }
  ++decode_errors_[index];
}

int64_t ControllerService::NextPeriodHostUs() const {
  if (last_period_host_us_ < 0) return controller_.has_pose() ? 0 : std::numeric_limits<int64_t>::max();
  const bool force_flowing = last_force_host_us_ >= 0 && last_period_host_us_ - last_force_host_us_ < period_us_;
  return last_period_host_us_ + period_us_ + (force_flowing ? period_us_ / 2 : 0);
}

void ControllerService::RunIfDue(int64_t host_us) {
  if (!controller_.has_pose() || host_us < NextPeriodHostUs()) return;
  RunControlPeriod(VehicleTimeUs(host_us), host_us);
}

void ControllerService::RunControlPeriod(int64_t vehicle_us, int64_t trigger_host_us) {
  // The vehicle clock never runs backwards between commands.
  vehicle_us = std::max(vehicle_us, last_period_vehicle_us_);
  last_command_ = controller_.Update(vehicle_us, controller_.HoldReference());
  EncodeMessage(ToMessage(last_command_), &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.motor_command, last_command_.utime, buffer_.data(), buffer_.size());
  const int64_t done_us = SteadyClockUs();
  loop_times_us_[loop_time_count_ % kLoopTimeCapacity] = static_cast<double>(done_us - trigger_host_us);
  ++loop_time_count_;
  last_period_host_us_ = trigger_host_us;
  last_period_vehicle_us_ = vehicle_us;
}

void ControllerService::PublishStatus(int64_t wall_utime, int64_t host_us) {
  controller_status_t& m = status_message_;
  const ControllerHealth& h = health();
  const int64_t now_us = VehicleTimeUs(host_us);
  m.utime = now_us;
  m.wall_utime = wall_utime;
  ++m.seq;
  m.mode = controller_.config().force_feedback ? kModeForceFeedback : kModeNominal;
  m.status = last_command_.status;
  m.fallbacks = h.fallbacks;
  m.descents = h.descents;
  m.commands = h.commands;
  m.saturated = h.saturated;
  auto age = [&](const ControllerInputCounters& c) {
    return c.last_utime < 0 || now_us < 0 ? kNaN : 1e-6 * static_cast<double>(now_us - c.last_utime);
  };
  m.pose_age_s = age(h.pose);
  m.imu_age_s = age(h.imu);
  m.force_age_s = age(h.force);
  const ControllerInputCounters* counters[kNumControllerInputs] = {&h.pose, &h.imu, &h.force};
  for (int i = 0; i < kNumControllerInputs; ++i) {
    m.received[i] = counters[i]->received + decode_errors_[i];
    m.decode_errors[i] = decode_errors_[i];
    m.rejected_invalid[i] = counters[i]->rejected_invalid;
    m.rejected_out_of_order[i] = counters[i]->rejected_out_of_order;
  }
  const size_t n = std::min(loop_time_count_, kLoopTimeCapacity);
  m.loop_time_p99_us = Percentile(loop_times_us_.begin(), loop_times_us_.begin() + n, 0.99);
  m.loop_time_max_us = n == 0 ? kNaN : *std::max_element(loop_times_us_.begin(), loop_times_us_.begin() + n);
  loop_time_count_ = 0;
  m.udp_fragments_dropped = udp_counters_ != nullptr ? udp_counters_->fragments_dropped : 0;
  m.udp_malformed_dropped = udp_counters_ != nullptr ? udp_counters_->malformed_dropped : 0;
  EncodeMessage(m, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.controller_status, now_us, buffer_.data(), buffer_.size());
}

}  // namespace birotor

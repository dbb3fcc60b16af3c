// The controller node: checked decoding, the own clock and timer,
// MOTOR_COMMAND and CONTROLLER_STATUS.
#include "nodes/controller_service.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "nodes/controller_status_message.h"
#include "nodes/guard_status_message.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
ControllerService::ControllerService(const ControllerConfig& config, const ChannelNames& channels, MessageSink* sink,
                                     HostClockUs host_clock)
    : controller_(config),
      channels_(channels),
      sink_(sink),
      host_clock_(host_clock ? std::move(host_clock) : HostClockUs(SteadyClockUs)),
      clock_(config.supervision),
      grid_(std::max<int64_t>(1, std::llround(1e6 / CommandRateHz(config)))) {
  // The route table: every channel this node reads, once.
  routes_.Add(channels_.pose, ControllerChannel::kPose);
  routes_.Add(channels_.imu, ControllerChannel::kImu);
  routes_.Add(channels_.force, ControllerChannel::kForce);
  routes_.Add(channels_.setpoint, ControllerChannel::kSetpoint);
  buffer_.reserve(256);
}

ControllerService::~ControllerService() = default;

void ControllerService::HandlePacket(std::string_view channel, const void* data, size_t size,
                                     int64_t /*receive_wall_utime*/) {
  ControllerChannel routed;
  if (routes_.Find(channel, &routed)) Dispatch(routed, data, size, host_clock_());
}

void ControllerService::HandleSetpoint(const void* data, size_t size, int64_t host_us) {
  setpoint_t message;
  if (DecodeMessage(data, size, &message) != DecodeError::kNone) {
    ++setpoint_decode_errors_;
    return;
  }
  // A setpoint does not set the clock (a planner's clock is not the vehicle's).
  if (clock_.set()) controller_.OnSetpoint(FromMessage(message), VehicleTimeUs(host_us));
}

void ControllerService::Dispatch(ControllerChannel channel, const void* data, size_t size, int64_t host_us) {
  if (channel == ControllerChannel::kSetpoint) {
    HandleSetpoint(data, size, host_us);
    return;
  }
  const int index = static_cast<int>(channel);  // kPose, kImu, kForce: ControllerInput's order
  const ControllerInputCounters* counters[kNumControllerInputs] = {&health().pose, &health().imu, &health().force};
  const int64_t accepted_before = counters[index]->accepted;
  switch (channel) {
    case ControllerChannel::kPose: {
      pose_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kPose), message.utime, host_us);
      if (now_us >= 0) controller_.OnPose(FromMessage(message), now_us);  // nothing to judge it by before
      if (counters[index]->accepted > accepted_before) clock_.NoteAccepted(host_us);
      return;
    }
    case ControllerChannel::kImu: {
      imu_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kImu), message.utime, host_us);
      if (now_us >= 0) controller_.OnImu(FromMessage(message), now_us);  // nothing to judge it by before
      if (counters[index]->accepted > accepted_before) clock_.NoteAccepted(host_us);
      return;
    }
    case ControllerChannel::kForce: {
      force_estimate_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kForce), message.utime, host_us);
      if (now_us >= 0) controller_.OnForce(FromMessage(message), now_us);  // nothing to judge it by before
      if (counters[index]->accepted > accepted_before) clock_.NoteAccepted(host_us);
      return;
    }
    case ControllerChannel::kSetpoint:
      return;
  }
  ++decode_errors_[index];
}

int64_t ControllerService::NextPeriodHostUs() const {
  if (!controller_.has_pose()) return std::numeric_limits<int64_t>::max();
  return grid_.Next();
}

void ControllerService::RunIfDue(int64_t host_us) {
  if (!controller_.has_pose() || host_us < NextPeriodHostUs()) return;
  RunControlPeriod(host_us);
  grid_.Ran(host_us);
}

void ControllerService::RunControlPeriod(int64_t host_us) {
  // The clock is monotonic; the guard keeps a command's stamp from going back.
  const int64_t vehicle_us = std::max(VehicleTimeUs(host_us), last_period_vehicle_us_);
  last_command_ = controller_.Update(vehicle_us);
  EncodeMessage(ToMessage(last_command_), &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.motor_command, last_command_.utime, buffer_.data(), buffer_.size());
  grid_.NoteLoopTime(host_us, SteadyClockUs());
  last_period_vehicle_us_ = vehicle_us;
}

static_assert(kControllerStatusInputs == kNumControllerInputs, "CONTROLLER_STATUS counts every controller input");

void ControllerService::PublishStatus(int64_t wall_utime, int64_t host_us) {
  ControllerStatusContext context;
  context.now_us = VehicleTimeUs(host_us);
  context.wall_utime = wall_utime;
  context.last_status = last_command_.status;
  for (int i = 0; i < kNumControllerInputs; ++i) context.decode_errors[i] = decode_errors_[i];
  context.setpoint_decode_errors = setpoint_decode_errors_;
  context.clock_relatches = clock_.relatches();
  grid_.TakeLoopTimes(&context.loop_time_p99_us, &context.loop_time_max_us);
  context.udp_fragments_dropped = udp_counters_ != nullptr ? udp_counters_->fragments_dropped : 0;
  context.udp_malformed_dropped = udp_counters_ != nullptr ? udp_counters_->malformed_dropped : 0;
  ++status_message_.seq;
  BuildControllerStatus(controller_, context, &status_message_);
  EncodeMessage(status_message_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.controller_status, context.now_us, buffer_.data(), buffer_.size());
  // GUARD_STATUS: the authenticated channels and the SETPOINT guards.
  ++guard_status_.seq;
  const SetpointCounters setpoint = controller_.setpoint().counters();
  BuildGuardStatus(guard_status_t::PROGRAM_CONTROLLER, context.now_us, wall_utime, signing_, authentication_, &setpoint,
                   &guard_status_);
  EncodeMessage(guard_status_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.guard_status, context.now_us, buffer_.data(), buffer_.size());
}

}  // namespace birotor

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
#include "numerics/percentile.h"
#include "numerics/time_units.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The clock follows the earliest-arriving input this long after it is set [us].
constexpr int64_t kClockAcquireUs = 500000;
// No input accepted for this long: the next input sets the clock again [us].
constexpr int64_t kClockRelatchUs = 2000000;

}  // namespace

ControllerService::ControllerService(const ControllerConfig& config, const ChannelNames& channels, MessageSink* sink,
                                     HostClockUs host_clock)
    : controller_(config),
      channels_(channels),
      sink_(sink),
      host_clock_(host_clock ? std::move(host_clock) : HostClockUs(SteadyClockUs)),
      period_us_(std::max<int64_t>(1, std::llround(1e6 / CommandRateHz(config)))) {
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
  if (clock_set_) controller_.OnSetpoint(FromMessage(message), VehicleTimeUs(host_us));
}

int64_t ControllerService::ClockForInput(int64_t utime, int64_t host_us) {
  const bool restart = clock_set_ && host_us - last_accepted_host_us_ > kClockRelatchUs;
  if ((!clock_set_ || restart) && utime >= 0 && utime <= kLatestPlausibleUtime) {
    if (restart) ++clock_relatches_;
    clock_set_ = true;
    clock_offset_us_ = utime - host_us;
    clock_set_host_us_ = last_accepted_host_us_ = host_us;
  } else if (clock_set_ && host_us - clock_set_host_us_ < kClockAcquireUs) {
    // Acquisition: the offset of the input that arrived soonest, forward
    // only and never by more than the future window at a time.
    // In seconds: a wild stamp must not overflow the subtraction.
    const double lead_s = ElapsedSeconds(utime, VehicleTimeUs(host_us));
    if (lead_s > 0 && lead_s <= controller_.config().supervision.clock_future_window_s) {
      clock_offset_us_ += SecondsToUtime(lead_s);
    }
  }
  return VehicleTimeUs(host_us);
}

int64_t ControllerService::VehicleTimeUs(int64_t host_us) const { return clock_set_ ? host_us + clock_offset_us_ : -1; }

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
      controller_.OnPose(FromMessage(message), ClockForInput(message.utime, host_us));
      if (counters[index]->accepted > accepted_before) last_accepted_host_us_ = host_us;
      return;
    }
    case ControllerChannel::kImu: {
      imu_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      controller_.OnImu(FromMessage(message), ClockForInput(message.utime, host_us));
      if (counters[index]->accepted > accepted_before) last_accepted_host_us_ = host_us;
      return;
    }
    case ControllerChannel::kForce: {
      force_estimate_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      controller_.OnForce(FromMessage(message), ClockForInput(message.utime, host_us));
      if (counters[index]->accepted > accepted_before) last_accepted_host_us_ = host_us;
      return;
    }
    case ControllerChannel::kSetpoint:
      return;
  }
  ++decode_errors_[index];
}

int64_t ControllerService::NextPeriodHostUs() const {
  if (!controller_.has_pose()) return std::numeric_limits<int64_t>::max();
  return next_period_host_us_ < 0 ? 0 : next_period_host_us_;
}

void ControllerService::RunIfDue(int64_t host_us) {
  if (!controller_.has_pose() || host_us < NextPeriodHostUs()) return;
  RunControlPeriod(host_us);
  // The next period on the grid; after a stall longer than a period the
  // grid starts again from now (no burst of catch-up commands).
  next_period_host_us_ = next_period_host_us_ < 0 ? host_us + period_us_ : next_period_host_us_ + period_us_;
  if (next_period_host_us_ <= host_us) next_period_host_us_ = host_us + period_us_;
}

void ControllerService::RunControlPeriod(int64_t host_us) {
  // The clock is monotonic; the guard keeps a command's stamp from going back.
  const int64_t vehicle_us = std::max(VehicleTimeUs(host_us), last_period_vehicle_us_);
  last_command_ = controller_.Update(vehicle_us);
  EncodeMessage(ToMessage(last_command_), &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.motor_command, last_command_.utime, buffer_.data(), buffer_.size());
  const int64_t done_us = SteadyClockUs();
  loop_times_us_[loop_time_count_ % kLoopTimeCapacity] = static_cast<double>(done_us - host_us);
  ++loop_time_count_;
  last_period_vehicle_us_ = vehicle_us;
}

void ControllerService::PublishStatus(int64_t wall_utime, int64_t host_us) {
  controller_status_t& m = status_message_;
  const ControllerHealth& h = health();
  const int64_t now_us = VehicleTimeUs(host_us);
  m.utime = now_us;
  m.wall_utime = wall_utime;
  ++m.seq;
  m.mode = controller_.config().model_predictive ? kModeMpc
           : controller_.config().force_feedback ? kModeForceFeedback
                                                 : kModeNominal;
  m.status = last_command_.status;
  m.fallbacks = h.fallbacks;
  m.descents = h.descents;
  m.commands = h.commands;
  m.saturated = h.saturated;
  auto age = [&](const ControllerInputCounters& c) {
    return c.last_utime < 0 || now_us < 0 ? kNaN : ElapsedSeconds(now_us, c.last_utime);
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
    m.rejected_future[i] = counters[i]->rejected_future;
    m.rejected_past[i] = counters[i]->rejected_past;
    m.rejected_foreign[i] = counters[i]->rejected_foreign;
  }
  m.pose_rejected_gate = h.pose.rejected_gate;
  m.pose_gate_resets = h.pose_gate_resets;
  m.conflicts = h.conflicts;
  m.infeasible = h.infeasible;
  m.clock_relatches = clock_relatches_;
  m.efficiency[0] = h.efficiency[0];
  m.efficiency[1] = h.efficiency[1];
  const SetpointInput& setpoint = controller_.setpoint();
  const SetpointCounters& sc = setpoint.counters();
  m.setpoint_state = static_cast<int32_t>(setpoint.state());
  m.setpoint_age_s = setpoint.last_utime() < 0 || now_us < 0 ? kNaN : ElapsedSeconds(now_us, setpoint.last_utime());
  m.setpoint_received = sc.received + setpoint_decode_errors_;
  m.setpoint_decode_errors = setpoint_decode_errors_;
  m.setpoint_rejected_invalid = sc.rejected_invalid;
  m.setpoint_rejected_stamp = sc.rejected_stamp;
  m.setpoint_rejected_out_of_order = sc.rejected_out_of_order;
  m.setpoint_rejected_rate = sc.rejected_rate;
  m.setpoint_rejected_jump = sc.rejected_jump;
  m.setpoint_timeouts = sc.timeouts;
  const size_t n = std::min(loop_time_count_, kLoopTimeCapacity);
  m.loop_time_p99_us = Percentile(loop_times_us_.begin(), loop_times_us_.begin() + n, 0.99);
  m.loop_time_max_us = n == 0 ? kNaN : *std::max_element(loop_times_us_.begin(), loop_times_us_.begin() + n);
  loop_time_count_ = 0;
  const MpcStats mpc = controller_.MpcStatistics();
  const bool solved = mpc.solves > 0;
  m.mpc_solves = mpc.solves;
  m.mpc_fallbacks = mpc.Fallbacks();
  m.mpc_solve_p50_us = solved ? 1e6 * mpc.solve_p50_s : kNaN;
  m.mpc_solve_p99_us = solved ? 1e6 * mpc.solve_p99_s : kNaN;
  m.mpc_solve_max_us = solved ? 1e6 * mpc.solve_max_s : kNaN;
  m.mpc_iterations = mpc.last_iterations;
  m.mpc_max_iterations = mpc.max_iterations;
  m.udp_fragments_dropped = udp_counters_ != nullptr ? udp_counters_->fragments_dropped : 0;
  m.udp_malformed_dropped = udp_counters_ != nullptr ? udp_counters_->malformed_dropped : 0;
  EncodeMessage(m, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.controller_status, now_us, buffer_.data(), buffer_.size());
}

}  // namespace birotor

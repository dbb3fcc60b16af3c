// The controller node: a PacketHandler (sources/message_source.h) for POSE,
// IMU, FORCE and SETPOINT over VehicleController, with checked decoding (a
// corrupt packet is counted, never trusted), the controller's own clock (the
// host's steady clock, put on the vehicle's time base when two inputs agree
// and never moved by a later one), control periods on its own timer at rate_hz,
// MOTOR_COMMAND and the CONTROLLER_STATUS health message.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/controller_status_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "controller/controller_params.h"
#include "controller/vehicle_controller.h"
#include "nodes/controller_clock.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/channels.h"

namespace birotor {

// The inputs with counters (CONTROLLER_STATUS received[], decode_errors[]).
enum class ControllerInput : int { kPose = 0, kImu = 1, kForce = 2 };
constexpr int kNumControllerInputs = 3;
// The channels the node reads (its route table maps the full names).
enum class ControllerChannel : int { kPose, kImu, kForce, kSetpoint };

// The host's monotonic clock [us] as the node reads it: SteadyClockUs in the
// daemon; a test or a fuzzer sets its own to be deterministic.
using HostClockUs = std::function<int64_t()>;

class ControllerService : public PacketHandler {
 public:
  // sink must outlive the service. host_clock stamps each packet when it is
  // handled (default: the steady clock).
  ControllerService(const ControllerConfig& config, const ChannelNames& channels, MessageSink* sink,
                    HostClockUs host_clock = {});
  ~ControllerService();
  ControllerService(const ControllerService&) = delete;
  ControllerService& operator=(const ControllerService&) = delete;

  // The full names of the input channels (POSE, IMU, FORCE, SETPOINT; the
  // route table's names), to subscribe a source to.
  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  // The live source's UDP counters (MessageSource::udp_counters, nullptr for
  // other sources) go into CONTROLLER_STATUS; they must outlive the service.
  void AttachUdpCounters(const UdpReceiveCounters* counters) { udp_counters_ = counters; }
  // The signing sink behind and the authenticating handler in front of this
  // node: GUARD_STATUS goes out with each CONTROLLER_STATUS. Both must
  // outlive the service.
  void AttachAuthentication(const SigningSink* signing, const AuthenticatingHandler* handler) {
    signing_ = signing;
    authentication_ = handler;
  }
  // PacketHandler, the one way in: a packet of a channel of the route table,
  // stamped with the host clock when it is handled (the receive time is not
  // used); decoded (a failure is counted), then given to the controller.
  // Any other channel is ignored. Never throws; never runs a control period
  // (the timer does).
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  // Host time [us] of the next control period: a fixed grid of 1 / rate_hz
  // on the host clock, whatever the inputs do. No period runs before the
  // first POSE (nothing to fly on: the ESCs keep what they run).
  int64_t NextPeriodHostUs() const;
  // Runs a control period at host_us if it is due.
  void RunIfDue(int64_t host_us);

  // Publishes CONTROLLER_STATUS and starts a new reporting period.
  void PublishStatus(int64_t wall_utime, int64_t host_us);

  // The controller's clock at host_us [us]: host time plus the offset set
  // when two different inputs (of POSE, IMU, FORCE) first agree on it
  // (ControllerClock, nodes/controller_clock.h); -1 before.
  int64_t VehicleTimeUs(int64_t host_us) const { return clock_.VehicleTimeUs(host_us); }
  int64_t clock_relatches() const { return clock_.relatches(); }
  const ControllerHealth& health() const { return controller_.health(); }
  MpcStats mpc_statistics() const { return controller_.MpcStatistics(); }  // zero outside mode mpc
  int64_t decode_errors(ControllerInput input) const { return decode_errors_[static_cast<int>(input)]; }

 private:
  // One routed packet, arrived at host_us (host clock [us]).
  void Dispatch(ControllerChannel channel, const void* data, size_t size, int64_t host_us);
  void HandleSetpoint(const void* data, size_t size, int64_t host_us);
  void RunControlPeriod(int64_t host_us);
  void FillStatus(int64_t now_us);

  VehicleController controller_;
  ChannelNames channels_;
  MessageSink* sink_;
  HostClockUs host_clock_;
  ChannelRoutes<ControllerChannel> routes_;
  int64_t decode_errors_[kNumControllerInputs] = {0, 0, 0};
  int64_t setpoint_decode_errors_ = 0;

  ControllerClock clock_;  // vehicle time = host time + offset
  ControlPeriodGrid grid_;
  int64_t last_period_vehicle_us_ = -1;
  MotorCommand last_command_;

  std::vector<uint8_t> buffer_;
  controller_status_t status_message_;
  const UdpReceiveCounters* udp_counters_ = nullptr;
  const SigningSink* signing_ = nullptr;
  const AuthenticatingHandler* authentication_ = nullptr;
  guard_status_t guard_status_{};
};

}  // namespace birotor

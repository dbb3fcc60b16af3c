// The controller node: a PacketHandler (sources/message_source.h) for POSE,
// IMU and FORCE over VehicleController, with checked decoding (a corrupt
// packet is counted, never trusted), the vehicle clock (newest input utime
// plus the host time since it arrived), control periods triggered by FORCE
// (so a command follows its strain sample at once) or by the period timer
// when FORCE stops, MOTOR_COMMAND and the CONTROLLER_STATUS health message.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/controller_status_t.hpp"
#include "controller/controller_params.h"
#include "controller/vehicle_controller.h"
#include "sinks/message_sink.h"
#include "sources/message_source.h"
#include "transport/channels.h"

namespace birotor {

enum class ControllerInput : int { kPose = 0, kImu = 1, kForce = 2 };
constexpr int kNumControllerInputs = 3;

class ControllerService : public PacketHandler {
 public:
  // sink must outlive the service.
  ControllerService(const ControllerConfig& config, const ChannelNames& channels, MessageSink* sink);
  ~ControllerService();
  ControllerService(const ControllerService&) = delete;
  ControllerService& operator=(const ControllerService&) = delete;

  // The full names of the input channels (POSE, IMU, FORCE), to subscribe a
  // source to.
  std::vector<std::string> InputChannels() const;
  // The live source's UDP counters (MessageSource::udp_counters, nullptr for
  // other sources) go into CONTROLLER_STATUS; they must outlive the service.
  void AttachUdpCounters(const UdpReceiveCounters* counters) { udp_counters_ = counters; }
  // PacketHandler: a packet of an input channel goes to HandlePacket below,
  // stamped with the host's steady clock when it is handled; any other
  // channel is ignored.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  // One encoded packet of an input, arrived at host_us (steady clock [us]).
  // A FORCE stamped at least a period minus half a FORCE interval after the
  // last command (vehicle clock) runs a control period at once, stamped with
  // its utime.
  // Never throws.
  void HandlePacket(ControllerInput input, const void* data, size_t size, int64_t host_us);

  // Host time [us] by which the next control period must run: one period
  // after the last, plus half a period while FORCE flows (the FORCE trigger
  // normally comes first). No period runs before the first POSE (nothing to
  // fly on: the ESCs keep what they run).
  int64_t NextPeriodHostUs() const;
  // Runs a control period at host_us if it is due (timer path).
  void RunIfDue(int64_t host_us);

  // Publishes CONTROLLER_STATUS and starts a new reporting period.
  void PublishStatus(int64_t wall_utime, int64_t host_us);

  // The vehicle clock at host_us [us]; -1 before any input.
  int64_t VehicleTimeUs(int64_t host_us) const;
  const ControllerHealth& health() const { return controller_.health(); }
  int64_t decode_errors(ControllerInput input) const { return decode_errors_[static_cast<int>(input)]; }

 private:
  void RunControlPeriod(int64_t vehicle_us, int64_t trigger_host_us);
  void NoteInputTime(int64_t utime, int64_t host_us);

  VehicleController controller_;
  ChannelNames channels_;
  MessageSink* sink_;
  int64_t period_us_;
  int64_t decode_errors_[kNumControllerInputs] = {0, 0, 0};

  // Vehicle clock: the newest input utime and when it arrived.
  int64_t newest_utime_ = -1;
  int64_t newest_host_us_ = 0;
  int64_t last_period_host_us_ = -1;
  int64_t last_period_vehicle_us_ = -1;
  int64_t last_force_host_us_ = -1;
  MotorCommand last_command_;

  // Loop times of the current reporting period (a fixed ring; the newest win).
  static constexpr size_t kLoopTimeCapacity = 4096;
  std::array<double, kLoopTimeCapacity> loop_times_us_{};
  size_t loop_time_count_ = 0;
  std::vector<uint8_t> buffer_;
  controller_status_t status_message_;
  const UdpReceiveCounters* udp_counters_ = nullptr;
};

}  // namespace birotor

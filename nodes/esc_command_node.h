// The simulator's receive path as the vehicle's ESCs (birotor-sim
// --external-controller): a PacketHandler for MOTOR_COMMAND with checked
// decoding (a corrupt packet is counted, never run), each command handed to
// the Simulator at the step it is handled. The live program feeds it from its
// message source, the fuzzer from bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/motor_command_t.hpp"
#include "simulator/simulator.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"

namespace birotor {

// The channel the node reads (its route table maps the full name).
enum class EscChannel : int { kMotorCommand };

class EscCommandNode : public PacketHandler {
 public:
  // sim must outlive the node; channel is the full MOTOR_COMMAND name.
  EscCommandNode(const std::string& channel, Simulator* sim) : sim_(sim) {
    routes_.Add(channel, EscChannel::kMotorCommand);
  }

  // The route table's names, to subscribe a source to.
  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  // PacketHandler, the one way in: a MOTOR_COMMAND packet, decoded and, when
  // it decodes, offered to the simulator's ESCs at its current step
  // (Simulator::OfferMotorCommand: one commander, stamps and range checked);
  // any other channel is ignored.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  int64_t received() const { return received_; }
  int64_t decode_errors() const { return decode_errors_; }

 private:
  ChannelRoutes<EscChannel> routes_;
  Simulator* sim_;
  motor_command_t message_;
  int64_t received_ = 0;
  int64_t decode_errors_ = 0;
};

}  // namespace birotor

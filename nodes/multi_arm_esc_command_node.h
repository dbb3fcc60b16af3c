// The N-rotor simulator's receive path as the vehicle's ESCs (birotor-sim
// --vehicle FILE --external-controller): a PacketHandler for
// MOTOR_COMMAND_N with checked decoding (a corrupt packet or another rotor
// count is counted, never run) and the ESCs' commander rule
// (simulator/esc_command_rule.h, the birotor's), each accepted command
// handed to the MultiArmSimulator at the step it is handled; Tick() at each
// step spools the motors down (commands 0) after the command timeout.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/motor_command_n_t.hpp"
#include "simulator/esc_command_rule.h"
#include "simulator/multi_arm_simulator.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/counted_messages.h"

namespace birotor {

class MultiArmEscCommandNode : public PacketHandler {
 public:
  // sim must outlive the node and fly on external commands
  // (MultiArmSimulator::UseExternalCommands); channel is the full
  // MOTOR_COMMAND_N name; command_timeout_s as the birotor's ESCs'.
  MultiArmEscCommandNode(const std::string& channel, MultiArmSimulator* sim, double command_timeout_s);

  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  // PacketHandler, the one way in: a MOTOR_COMMAND_N packet, decoded, its
  // count checked against the simulator's description, then the ESCs' rule
  // at the simulator's current step; accepted: OfferRotorCommands.
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;
  // Once per step, before it: after command_timeout_s without an accepted
  // command the ESCs command 0 (the motors spool down with tau_m).
  void Tick();

  int64_t received() const { return received_; }
  int64_t decode_errors() const { return decode_errors_; }
  const CountRefusals& count_refusals() const { return count_refusals_; }
  const EscCommandRule& rule() const { return rule_; }

 private:
  enum class Channel : int { kMotorCommandN };
  ChannelRoutes<Channel> routes_;
  MultiArmSimulator* sim_;
  EscCommandRule rule_;
  motor_command_n_t message_;
  int64_t received_ = 0;
  int64_t decode_errors_ = 0;
  CountRefusals count_refusals_;
};

}  // namespace birotor

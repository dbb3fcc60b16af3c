// MOTOR_COMMAND_N into the simulated ESCs of a vehicle with N rotors.
#include "nodes/multi_arm_esc_command_node.h"

#include <array>

#include "transport/lcm_codec.h"

namespace birotor {

MultiArmEscCommandNode::MultiArmEscCommandNode(const std::string& channel, MultiArmSimulator* sim,
                                               double command_timeout_s)
    : sim_(sim), rule_(sim->scenario().esc, command_timeout_s) {
  routes_.Add(channel, Channel::kMotorCommandN);
  message_.omega_cmd_rad_s.reserve(kMaxArms);
}

void MultiArmEscCommandNode::HandlePacket(std::string_view channel, const void* data, size_t size,
                                          int64_t /*receive_wall_utime*/) {
  Channel routed;
  if (!routes_.Find(channel, &routed)) return;
  ++received_;
  if (DecodeMessage(data, size, &message_) != DecodeError::kNone ||
      !CountMatches(message_, sim_->vehicle(), &count_refusals_)) {
    ++decode_errors_;
    return;
  }
  const int n = sim_->vehicle().arm_count;
  if (rule_.Offer(message_.seq, message_.utime, message_.omega_cmd_rad_s.data(), n, sim_->vehicle().omega_max_rad_s,
                  sim_->utime()) != EscVerdict::kAccepted)
    return;
  std::array<double, kMaxArms> omega_rad_s{};
  for (int i = 0; i < n; ++i) omega_rad_s[static_cast<size_t>(i)] = message_.omega_cmd_rad_s[static_cast<size_t>(i)];
  sim_->OfferRotorCommands(omega_rad_s);
}

void MultiArmEscCommandNode::Tick() {
  const bool was_timed_out = rule_.timed_out();
  if (rule_.TimedOut(sim_->utime()) && !was_timed_out) sim_->OfferRotorCommands({});  // 0: spool down
}

}  // namespace birotor

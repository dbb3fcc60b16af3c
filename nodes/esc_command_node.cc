// MOTOR_COMMAND into the simulated ESCs.
#include "nodes/esc_command_node.h"

#include "transport/lcm_codec.h"

namespace birotor {

void EscCommandNode::HandlePacket(std::string_view channel, const void* data, size_t size,
                                  int64_t /*receive_wall_utime*/) {
  EscChannel routed;
  if (!routes_.Find(channel, &routed)) return;
  ++received_;
  if (DecodeMessage(data, size, &message_) != DecodeError::kNone) {
    ++decode_errors_;
    return;
  }
  sim_->OfferMotorCommand(message_.seq, message_.utime, message_.omega_cmd_rad_s);
}

}  // namespace birotor

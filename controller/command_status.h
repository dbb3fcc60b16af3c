// The status bits of a rotor command (samples/motor_command.h kCommand*, the
// STATUS_* of motor_command_t and motor_command_n_t) from the facts of one
// control period of the N-rotor daemon (nodes/multi_arm_controller_service.h).
// The controller room owns the command's bits, as VehicleController composes
// the birotor's.
#pragma once

#include <cstdint>

#include "samples/motor_command.h"

namespace birotor {

struct CommandStatusFacts {
  bool fallback_active = false;   // force feedback asked for, FORCE unusable: the nominal map
  bool input_stale = false;       // POSE older than pose_timeout_s
  bool input_conflict = false;    // a second seq stream on POSE or FORCE
  bool saturated = false;         // the allocation was limited
  bool mpc_fallback = false;      // mode mpc: the cascade's command was sent
  bool descending = false;        // POSE lost or hover infeasible: the controlled descent (DescentReference)
  bool hover_infeasible = false;  // HoverFeasibility latched: the efficiencies cannot hold the weight level
};

inline int32_t ComposeCommandStatus(const CommandStatusFacts& f) {
  return (f.fallback_active ? kCommandFallbackActive : 0) | (f.input_stale ? kCommandInputStale : 0) |
         (f.input_conflict ? kCommandInputConflict : 0) | (f.saturated ? kCommandSaturated : 0) |
         (f.mpc_fallback ? kCommandMpcFallback : 0) | (f.descending ? kCommandDescending : 0) |
         (f.hover_infeasible ? kCommandHoverInfeasible : 0);
}

}  // namespace birotor

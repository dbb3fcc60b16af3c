// Building GUARD_STATUS (lcmtypes/guard_status_t.lcm): a program's signing
// sink, authenticating handler and (the controller) SETPOINT counters, one
// message. Used by the estimator and controller nodes with their status,
// and by birotor-sim.
#pragma once

#include <cstdint>

#include "birotor/guard_status_t.hpp"
#include "controller/setpoint_input.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"

namespace birotor {

// The guard_status_t slot (CHANNEL_*) of a channel: its own, or for the
// N-arm twins MOTOR_COMMAND_N and FORCE_N their birotor twin's.
int GuardStatusSlot(AuthenticatedChannel channel);

// Fills every field of *message but seq (the publisher's counter). signing,
// handler or setpoint may be null (nothing sealed, nothing read, not the
// controller).
void BuildGuardStatus(int32_t program, int64_t utime, int64_t wall_utime, const SigningSink* signing,
                      const AuthenticatingHandler* handler, const SetpointCounters* setpoint, guard_status_t* message);

}  // namespace birotor

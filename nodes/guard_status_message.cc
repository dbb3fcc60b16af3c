#include "nodes/guard_status_message.h"

namespace birotor {

static_assert(guard_status_t::CHANNEL_MOTOR_COMMAND == static_cast<int>(AuthenticatedChannel::kMotorCommand) &&
                  guard_status_t::CHANNEL_SETPOINT == static_cast<int>(AuthenticatedChannel::kSetpoint) &&
                  guard_status_t::CHANNEL_POSE == static_cast<int>(AuthenticatedChannel::kPose) &&
                  guard_status_t::CHANNEL_FORCE == static_cast<int>(AuthenticatedChannel::kForce),
              "GUARD_STATUS indexes the channels as AuthenticatedChannel");

int GuardStatusSlot(AuthenticatedChannel channel) {
  switch (channel) {
    case AuthenticatedChannel::kMotorCommandN:
      return guard_status_t::CHANNEL_MOTOR_COMMAND;
    case AuthenticatedChannel::kForceN:
      return guard_status_t::CHANNEL_FORCE;
    default:
      return static_cast<int>(channel);
  }
}

void BuildGuardStatus(int32_t program, int64_t utime, int64_t wall_utime, const SigningSink* signing,
                      const AuthenticatingHandler* handler, const SetpointCounters* setpoint, guard_status_t* message) {
  message->utime = utime;
  message->wall_utime = wall_utime;
  message->program = program;
  const bool seals = signing != nullptr && signing->sealed() > 0;
  message->publisher = seals ? static_cast<int64_t>(signing->publisher()) : 0;
  message->sealed = signing != nullptr ? signing->sealed() : 0;
  // The N-arm twins count in their birotor twin's slot (a program flies one
  // vehicle: it reads MOTOR_COMMAND or MOTOR_COMMAND_N, FORCE or FORCE_N), so
  // guard_status_t keeps its four slots and its fingerprint.
  constexpr int kSlots = 4;
  for (int i = 0; i < kSlots; ++i) {
    message->accepted[i] = message->refused[i] = message->replayed[i] = message->unsigned_accepted[i] = 0;
  }
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
    AuthenticationCounters c;
    if (handler != nullptr) c = handler->counters(static_cast<AuthenticatedChannel>(i));
    const int slot = GuardStatusSlot(static_cast<AuthenticatedChannel>(i));
    message->accepted[slot] += c.authenticated;
    message->refused[slot] += c.unauthenticated + c.malformed;
    message->replayed[slot] += c.replayed;
    message->unsigned_accepted[slot] += c.unsigned_accepted;
  }
  const SetpointCounters none;
  const SetpointCounters& sc = setpoint != nullptr ? *setpoint : none;
  message->setpoint_rejected_inconsistent = sc.rejected_inconsistent;
  message->setpoint_conflicts = sc.conflicts;
  message->setpoint_rejected_conflict = sc.rejected_conflict;
  message->setpoint_limited_periods = sc.limited_periods;
}

}  // namespace birotor

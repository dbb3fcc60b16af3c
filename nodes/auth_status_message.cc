#include "nodes/auth_status_message.h"

namespace birotor {

static_assert(auth_status_t::CHANNEL_MOTOR_COMMAND == static_cast<int>(AuthenticatedChannel::kMotorCommand) &&
                  auth_status_t::CHANNEL_SETPOINT == static_cast<int>(AuthenticatedChannel::kSetpoint) &&
                  auth_status_t::CHANNEL_POSE == static_cast<int>(AuthenticatedChannel::kPose) &&
                  auth_status_t::CHANNEL_FORCE == static_cast<int>(AuthenticatedChannel::kForce),
              "AUTH_STATUS indexes the channels as AuthenticatedChannel");

void BuildAuthStatus(int32_t program, int64_t utime, int64_t wall_utime, const SigningSink* signing,
                     const AuthenticatingHandler* handler, auth_status_t* message) {
  message->utime = utime;
  message->wall_utime = wall_utime;
  message->program = program;
  const bool seals = signing != nullptr && signing->sealed() > 0;
  message->publisher = seals ? static_cast<int64_t>(signing->publisher()) : 0;
  message->sealed = signing != nullptr ? signing->sealed() : 0;
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
    AuthenticationCounters c;
    if (handler != nullptr) c = handler->counters(static_cast<AuthenticatedChannel>(i));
    message->accepted[i] = c.authenticated;
    message->refused[i] = c.unauthenticated + c.malformed;
    message->replayed[i] = c.replayed;
    message->unsigned_accepted[i] = c.unsigned_accepted;
  }
}

}  // namespace birotor

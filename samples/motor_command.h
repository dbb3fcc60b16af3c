// The controller's output as a plain struct (channel MOTOR_COMMAND), with the
// mode and status constants of lcmtypes/motor_command_t.lcm (equality checked
// by tests/transport/message_conversion_test.cc). No LCM here.
#pragma once

#include <cstdint>

#include "samples/rotor_count.h"

namespace birotor {

// Values of MotorCommand::mode.
enum ControlMode : int32_t {
  kModeNominal = 0,        // omega = sqrt(f / c_T)
  kModeForceFeedback = 1,  // omega_i = sqrt(f_i / (c_T e_i)), e_i FORCE's thrust_scale conditioned
  kModeMpc = 2,            // model predictive control (controller/mpc_controller.h)
};

// Bits of MotorCommand::status.
enum CommandStatusBit : int32_t {
  kCommandFallbackActive = 1,    // force feedback asked for, FORCE unusable: efficiency decaying towards 1
  kCommandInputStale = 2,        // POSE, IMU or (in force feedback) FORCE older than its timeout
  kCommandDescending = 4,        // POSE lost: controlled descent on the IMU-propagated state
  kCommandSaturated = 8,         // the allocation was limited by [0, omega_max] (integrators held)
  kCommandNoPoseYet = 16,        // no POSE received yet: rotors at 0
  kCommandInputConflict = 32,    // a second publisher on FORCE or POSE: force feedback dropped
  kCommandHoverInfeasible = 64,  // the efficiency cannot hold the weight level: controlled descent
  kCommandMpcFallback = 128,     // mode mpc: the solve failed, was late or bad; the cascade's command
};

struct MotorCommand {
  int64_t utime = 0;                                // vehicle time the command is for [us]
  int32_t seq = 0;                                  // command counter, wraps
  double omega_cmd_rad_s[kBirotorRotors] = {0, 0};  // rotor 1, 2 [rad/s], finite, in [0, omega_max]
  int32_t mode = kModeNominal;                      // ControlMode actually in use
  int32_t status = 0;                               // CommandStatusBit set
};

}  // namespace birotor

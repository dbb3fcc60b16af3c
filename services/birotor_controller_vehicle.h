// birotor-controller --vehicle FILE: the live flight controller for a
// vehicle description with N rotors. Subscribes to POSE, IMU, FORCE_N and
// SETPOINT (POSE, SETPOINT and FORCE_N through their sealed twins unless the
// site lets them through unsigned), flies MultiArmController (cascade, or
// mode mpc) through nodes/multi_arm_controller_service.h, publishes
// MOTOR_COMMAND_N (sealed: MOTOR_COMMAND_N_AUTH, then the plain copy) on
// its own timer and CONTROLLER_STATUS and GUARD_STATUS at
// --status-rate-hz; stops on SIGINT/SIGTERM.
#pragma once

#include <string>

#include "controller/controller_params.h"
#include "program/channel_security.h"

namespace birotor {

struct VehicleControllerOptions {
  std::string vehicle_file;   // --vehicle
  std::string params_file;    // --params (for the start-up line)
  std::string lcm_url;        // --lcm-url
  std::string prefix;         // --prefix
  double status_rate_hz = 5;  // --status-rate-hz
  int realtime_priority = 0;  // --realtime-priority
};

// Runs the daemon until a signal; the exit status (1 with one line when the
// description, LCM or the subscription fails). security: loaded for
// SETPOINT, POSE, MOTOR_COMMAND_N and FORCE_N.
int RunVehicleController(const VehicleControllerOptions& options, const ControllerConfig& config,
                         const ChannelSecurity& security);

}  // namespace birotor

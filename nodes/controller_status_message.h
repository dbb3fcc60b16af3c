// Building the CONTROLLER_STATUS health message (lcmtypes/controller_status_t.lcm)
// from the controller's health: the one encoder, used by the controller node
// (birotor-controller) and by the lock-step closed loop's log
// (evaluation/closed_loop.cc), so both say the same thing the same way.
#pragma once

#include <cstdint>
#include <limits>

#include "birotor/controller_status_t.hpp"
#include "controller/vehicle_controller.h"

namespace birotor {

inline constexpr int kControllerStatusInputs = 3;  // POSE, IMU, FORCE (ControllerInput order)

// What the node knows beyond the controller's health; the lock-step loop
// leaves the transport's counters at 0 and the loop times unknown.
struct ControllerStatusContext {
  int64_t now_us = -1;      // vehicle clock [us]; -1 before it is set
  int64_t wall_utime = 0;   // host time [us since epoch] (vehicle time in the lock-step loop)
  int32_t last_status = 0;  // the newest MOTOR_COMMAND's status bits
  int64_t decode_errors[kControllerStatusInputs] = {0, 0, 0};
  int64_t setpoint_decode_errors = 0;
  int64_t clock_relatches = 0;
  double loop_time_p99_us = std::numeric_limits<double>::quiet_NaN();  // of the reporting period [us]
  double loop_time_max_us = std::numeric_limits<double>::quiet_NaN();
  int64_t udp_fragments_dropped = 0;
  int64_t udp_malformed_dropped = 0;
  // The MPC's solve times are host time: false (the lock-step loop, to be
  // deterministic, as replay leaves out the processing time) sends NaN.
  bool report_solve_times = true;
};

// Fills every field of *message but seq (the publisher's counter).
void BuildControllerStatus(const VehicleController& controller, const ControllerStatusContext& context,
                           controller_status_t* message);
// The same from the pieces (the N-rotor node, nodes/multi_arm_controller_service.h,
// whose law is not a VehicleController): its health, configuration (the
// mode), setpoint input and MPC counters.
void BuildControllerStatus(const ControllerHealth& health, const ControllerConfig& config,
                           const SetpointInput& setpoint, const MpcStats& mpc, const ControllerStatusContext& context,
                           controller_status_t* message);

}  // namespace birotor

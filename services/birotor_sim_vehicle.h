// birotor-sim --vehicle FILE: a vehicle description with N arms flies the
// scenario (simulator/multi_arm_simulator.h, every scenario kind), into an
// LCM log (--output, as fast as possible) or live on LCM (paced by
// --speed), through the birotor's WireSampleSink on the counted channels
// (STRAIN_N, MOTOR_N, LOADCELL_N, TRUTH_N, IMU, POSE) and the description
// on VEHICLE at the start and every simulated second. Live, POSE (and
// SETPOINT) go out sealed unless the site lets them through unsigned; with
// external_controller the ESCs run MOTOR_COMMAND_N (sealed: its _AUTH
// twin) from LCM instead of the scenario's autopilot
// (nodes/multi_arm_esc_command_node.h), and with publish_setpoints the
// scenario's trajectory goes out on SETPOINT for that controller to fly.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <string>

#include "model/vehicle_description.h"
#include "program/channel_security.h"
#include "simulator/scenario.h"
#include "sources/message_source.h"
#include "transport/channels.h"

namespace birotor {

struct VehicleRunOptions {
  std::string vehicle_file;          // where the description came from (messages only)
  std::string output;                // log file; empty: live on lcm
  double speed = 1.0;                // live: simulated seconds per wall second
  bool wall_clock = false;           // utime = wall clock at start + simulated time
  bool publish_truth = true;         // false: no TRUTH_N (--no-truth)
  double vehicle_period_s = 1.0;     // VEHICLE every this much simulated time [s]
  bool external_controller = false;  // live: the ESCs run MOTOR_COMMAND_N from LCM
  double command_timeout_s = 0.1;    // ... and command 0 after this long without one [s]
  bool publish_setpoints = false;    // the trajectory on SETPOINT
  double setpoint_rate_hz = 50.0;    // ... at this rate of simulated time [Hz]
};

// Runs the scenario once; false (said why in the log) when the scenario
// cannot run on the vehicle or the log cannot be written. lcm: the open
// LCM for live mode (unused with an output); source: the live message
// source of the ESCs' commands (external_controller; else unused);
// security: the key and the unsigned channels (live).
bool RunVehicleScenario(const VehicleRunOptions& options, const VehicleDescription& vehicle, const Scenario& scenario,
                        const ChannelNames& channels, lcm::LCM* lcm, MessageSource* source,
                        const ChannelSecurity& security);

}  // namespace birotor

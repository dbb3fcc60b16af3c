// birotor-sim --vehicle FILE: a vehicle description with N arms flies the
// scenario (simulator/multi_arm_simulator.h, every scenario kind), into an
// LCM log (--output, as fast as possible) or live on LCM (paced by
// --speed), through the birotor's WireSampleSink on the counted channels
// (STRAIN_N, MOTOR_N, LOADCELL_N, TRUTH_N, IMU, POSE) and the description
// on VEHICLE at the start and every simulated second.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <string>

#include "model/vehicle_description.h"
#include "simulator/scenario.h"
#include "transport/channels.h"

namespace birotor {

struct VehicleRunOptions {
  std::string vehicle_file;       // where the description came from (messages only)
  std::string output;             // log file; empty: live on lcm
  double speed = 1.0;             // live: simulated seconds per wall second
  bool wall_clock = false;        // utime = wall clock at start + simulated time
  bool publish_truth = true;      // false: no TRUTH_N (--no-truth)
  double vehicle_period_s = 1.0;  // VEHICLE every this much simulated time [s]
};

// Runs the scenario once; false (said why in the log) when the scenario
// cannot run on the vehicle or the log cannot be written. lcm: the open
// LCM for live mode (unused with an output).
bool RunVehicleScenario(const VehicleRunOptions& options, const VehicleDescription& vehicle, const Scenario& scenario,
                        const ChannelNames& channels, lcm::LCM* lcm);

}  // namespace birotor

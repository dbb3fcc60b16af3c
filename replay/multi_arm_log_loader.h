// Reads the N-arm channels of an lcm-logger file (STRAIN_N, MOTOR_N,
// LOADCELL_N and the VEHICLE description, docs/interface.md "Vehicles with
// N arms"; and IMU, the same channel for every vehicle) into the
// MultiArmBenchLog of identification/multi_arm_bench_fit.h:
// the LCM glue of birotor-identify --vehicle, beside LoadSensorLog.
#pragma once

#include <string>

#include "identification/multi_arm_bench_fit.h"
#include "replay/identification_log_loader.h"

namespace birotor {

// As LoadSensorLog: false (with a one-line *error) when the file cannot be
// read or is not usable; corrupt events are counted in report. A VEHICLE
// message that does not decode into a description (FromMessage) is an
// error. Each sample keeps the count its message carried (entries beyond
// kMaxSampleArms dropped), so MultiArmLogMismatch sees a wrong count.
bool LoadMultiArmBenchLog(const std::string& path, const std::string& prefix, MultiArmBenchLog* log,
                          LogLoadReport* report, std::string* error,
                          double min_usable_fraction = kDefaultMinUsableLogFraction);

}  // namespace birotor

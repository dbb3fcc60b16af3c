// birotor-identify --vehicle FILE: the bench or flight identification of a
// vehicle with N arms (identification/multi_arm_bench_fit.h,
// multi_arm_flight_fit.h) from lcm-logger files of its counted channels,
// written as an identified description (params/identified_description_file.h).
#pragma once

#include <string>
#include <vector>

#include "identification/identification_options.h"

namespace birotor {

struct MultiArmIdentifyRequest {
  std::vector<std::string> logs;  // bench (STRAIN_N, MOTOR_N, LOADCELL_N) or flight (STRAIN_N, MOTOR_N, IMU) logs
  std::string mode = "auto";      // bench, flight, or auto (bench when every log has LOADCELL_N samples)
  std::string vehicle;            // the base description (N-arm or birotor form)
  std::string prefix;             // channel prefix
  std::string output;             // identified description, written atomically
  std::string config;             // optional `identification:` section ("" : defaults)
  double min_usable_fraction = 0.0;
};

// Loads, checks every log against the description (VEHICLE and sample
// counts), fits, writes. "" on success, else one line: why nothing was
// written (an unreadable file, a mismatched log, a calibration fact given
// on the command line, or what the data could not determine).
std::string IdentifyMultiArmVehicle(const MultiArmIdentifyRequest& request, const IdentificationOptions& cli_options);

}  // namespace birotor

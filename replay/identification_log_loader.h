// Reads lcm-logger files into the plain SensorLog of identification/: the LCM
// glue of birotor-identify. Decodes the STRAIN, MOTOR, IMU, POSE, LOADCELL and
// TRUTH channels of one prefix, counts what it could not decode.
#pragma once

#include <cstdint>
#include <string>

#include "identification/sensor_log.h"

namespace birotor {

struct LogLoadReport {
  int64_t events = 0;           // events read
  int64_t decode_errors = 0;    // events on a known channel that did not decode
  bool truncated_tail = false;  // the file ends in a partial or corrupt event
  int64_t tail_offset = 0;      // bytes readable [bytes]
  int64_t file_size = 0;        // [bytes]
};

// False (with *error) when the file cannot be opened or is not a log. A
// corrupt tail is not an error: the events up to the damage are kept and
// report->truncated_tail is set.
bool LoadSensorLog(const std::string& path, const std::string& prefix, SensorLog* log, LogLoadReport* report,
                   std::string* error);

}  // namespace birotor

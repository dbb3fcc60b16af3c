// Reads lcm-logger files into the plain SensorLog of identification/: the LCM
// glue of birotor-identify. Decodes the STRAIN, MOTOR, IMU, POSE, LOADCELL and
// TRUTH channels of one prefix, counts what it could not decode.
#pragma once

#include <cstdint>
#include <string>

#include "samples/sensor_log.h"
#include "transport/log_io.h"

namespace birotor {

struct LogLoadReport {
  std::string damage;           // warning line for corrupt events or a cut tail ("" if intact)
  int64_t events = 0;           // events read
  int64_t decode_errors = 0;    // events on a known channel that did not decode
  bool truncated_tail = false;  // the file ends in a partial or corrupt event
  int64_t tail_offset = 0;      // bytes readable [bytes]
  int64_t file_size = 0;        // [bytes]
};

// False (with a one-line *error) when the file cannot be opened, is not a
// regular file or not a log, or is not usable (CheckLogUsable of
// transport/log_io.h with min_usable_fraction). Corrupt events and a cut
// tail in a usable log are not errors: they are skipped, counted and
// described in report->damage.
bool LoadSensorLog(const std::string& path, const std::string& prefix, SensorLog* log, LogLoadReport* report,
                   std::string* error, double min_usable_fraction = kDefaultMinUsableLogFraction);

}  // namespace birotor

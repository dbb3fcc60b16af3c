// The persisted strain-gauge offsets: at a clean stop birotor-estimator writes
// the offsets it learned (tare or filter) to a small text file, and starts
// from them after a restart, so that a restart in the air is not an untared
// start. The file names the vehicle it belongs to (a checksum of every key of
// the vehicle section) and carries a checksum of its own lines: a corrupt or
// foreign file is refused with a one-line reason.
#pragma once

#include <string>

#include "estimator/gauge_calibration.h"
#include "model/vehicle_params.h"

namespace birotor {

// Checksum of the vehicle parameters (VehicleParamsYaml text, FNV-1a 64).
std::string VehicleChecksum(const VehicleParams& params);

// File text for the offsets and std of calibration.
//   # birotor-estimator gauge offset state
//   vehicle_checksum: <16 hex>
//   gauge_offset_rad: <o1> <o2>
//   gauge_offset_std_rad: <s1> <s2>
//   checksum: <16 hex of the lines above>
std::string GaugeStateText(const GaugeCalibration& calibration, const std::string& vehicle_checksum);

// Writes the text to path through a temporary file in the same folder and a
// rename (atomic: a reader sees the old or the new file, never half of one).
bool WriteGaugeState(const std::string& path, const GaugeCalibration& calibration, const std::string& vehicle_checksum,
                     std::string* error);

// Reads offsets and std into *calibration (source kStateFile). False with a
// one-line *error for an unreadable, corrupt (bad checksum, bad or missing
// field, value outside [-max_offset_rad, max_offset_rad]) or foreign (other
// vehicle checksum) file; *calibration is then unchanged.
bool ReadGaugeState(const std::string& path, const std::string& vehicle_checksum, double max_offset_rad,
                    GaugeCalibration* calibration, std::string* error);

}  // namespace birotor

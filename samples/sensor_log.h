// The recorded sensor streams of one experiment (one log file), as plain
// sample structs: the input of the identification. Filled by the log loader
// of tools/ (LCM glue) or directly by tests; no LCM here.
#pragma once

#include <string>
#include <vector>

#include "samples/samples.h"

namespace birotor {

struct SensorLog {
  std::string source;                    // file name or test label, for messages
  std::vector<StrainSample> strain;      // STRAIN, 1 kHz reference
  std::vector<MotorSample> motor;        // MOTOR, 500 Hz reference
  std::vector<ImuSample> imu;            // IMU (optional)
  std::vector<PoseSample> pose;          // POSE (optional, unused by the fits)
  std::vector<LoadCellSample> loadcell;  // LOADCELL (bench only)
  std::vector<TruthSample> truth;        // TRUTH (simulator only; never used by the fits)
};

// Span covered by the strain samples [s] (0 when fewer than two).
double StrainDurationS(const SensorLog& log);

// True when at least one motor sample carries finite telemetry for both rotors.
bool HasMotorTelemetry(const SensorLog& log);

}  // namespace birotor

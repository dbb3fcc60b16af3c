// Entry point of the identification: from recorded sensor logs and the base
// parameter file to identified vehicle parameters with one-sigma
// uncertainties (bench logs with load cells, or free-flight logs).
#pragma once

#include <string>
#include <vector>

#include "identification/identification_options.h"
#include "identification/identification_result.h"
#include "identification/sample_cleaning.h"
#include "identification/sensor_log.h"
#include "model/vehicle_params.h"

namespace birotor {

enum class IdentificationMode { kAuto, kBench, kFlight };

// Bench when every log has load-cell samples, flight otherwise.
IdentificationMode DetectMode(const std::vector<SensorLog>& logs);

// Drops and counts the bad samples of every stream (CleanLog of
// sample_cleaning.h with options.max_time_jump_s), in place.
SampleCleaningReport SanitizeLog(SensorLog* log, const IdentificationOptions& options);

// Identifies c_T, tau_m, k, d (and, on the bench, the deflection-force maps).
// The masses, lengths and inertia of `base` are taken as known. When the data
// cannot give an essential parameter (missing channel, too short, no
// excitation), result.ok is false and result.errors says what is missing.
IdentificationResult Identify(std::vector<SensorLog> logs, const VehicleParams& base,
                              const IdentificationOptions& options,
                              IdentificationMode mode = IdentificationMode::kAuto);

// Parts, exposed for tests. Each appends to *result.
void IdentifyMotorTimeConstant(const std::vector<SensorLog>& logs, const VehicleParams& base,
                               const IdentificationOptions& options, IdentificationResult* result);
void IdentifyBenchThrust(const std::vector<SensorLog>& logs, const VehicleParams& base,
                         const IdentificationOptions& options, IdentificationResult* result);
void IdentifyBenchArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                       const IdentificationOptions& options, IdentificationResult* result);
void IdentifyFlightArms(const std::vector<SensorLog>& logs, const VehicleParams& base,
                        const IdentificationOptions& options, IdentificationResult* result);

}  // namespace birotor

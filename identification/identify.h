// Entry point of the identification: from recorded sensor logs and the base
// parameter file to identified vehicle parameters with one-sigma
// uncertainties (bench logs with load cells, or free-flight logs).
#pragma once

#include <string>
#include <vector>

#include "identification/identification_options.h"
#include "identification/identification_result.h"
#include "identification/sample_cleaning.h"
#include "model/birotor_params.h"
#include "samples/sensor_log.h"

namespace birotor {

enum class IdentificationMode { kAuto, kBench, kFlight };

// Bench when every log has load-cell samples, flight otherwise (Identify in
// kAuto with both kinds of logs fits them jointly, IdentifyBenchAndFlight).
IdentificationMode DetectMode(const std::vector<SensorLog>& logs);

// Drops and counts the bad samples of every stream (CleanLog of
// sample_cleaning.h with options.max_time_jump_s), in place.
SampleCleaningReport SanitizeLog(SensorLog* log, const IdentificationOptions& options);

// Identifies c_T, tau_m, k, d (and, on the bench, the deflection-force maps).
// The masses, lengths and inertia of `base` are taken as known. When the data
// cannot give an essential parameter (missing channel, too short, no
// excitation), result.ok is false and result.errors says what is missing.
IdentificationResult Identify(std::vector<SensorLog> logs, const BirotorParams& base,
                              const IdentificationOptions& options,
                              IdentificationMode mode = IdentificationMode::kAuto);

// Parts, exposed for tests. Each appends to *result.
// Bench logs (load cells) and flight logs of one vehicle in one Ceres problem
// over k, d, c_T, m_p (the bench logs alone give the start and the gauge
// calibration); tau_m from the motor data of every log.
void IdentifyBenchAndFlight(const std::vector<SensorLog>& bench_logs, const std::vector<SensorLog>& flight_logs,
                            const BirotorParams& base, const IdentificationOptions& options,
                            IdentificationResult* result);
void IdentifyMotorTimeConstant(const std::vector<SensorLog>& logs, const BirotorParams& base,
                               const IdentificationOptions& options, IdentificationResult* result);
void IdentifyBenchThrust(const std::vector<SensorLog>& logs, const BirotorParams& base,
                         const IdentificationOptions& options, IdentificationResult* result);
void IdentifyBenchArms(const std::vector<SensorLog>& logs, const BirotorParams& base,
                       const IdentificationOptions& options, IdentificationResult* result);
// With bench_logs (a joint bench + flight fit), `base` is the bench logs' own
// fit and their residuals join the flight's in one Ceres problem over k, d,
// c_T, m_p (bench_residuals.h).
void IdentifyFlightArms(const std::vector<SensorLog>& logs, const BirotorParams& base,
                        const IdentificationOptions& options, IdentificationResult* result,
                        const std::vector<SensorLog>* bench_logs = nullptr);

}  // namespace birotor

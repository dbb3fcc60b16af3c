// Bench identification of a vehicle with N elastic arms (model/
// vehicle_description.h; the simulator's bench, body clamped, one load cell
// under every rotor): per arm its stiffness k_i, damping d_i, tip mass m_p,i
// and gauge offset o_i (the clamped-arm output-error fit of bench_fit.h on
// that arm's hinge), per rotor its c_T,i (load cells) and tau_m,i (motor
// telemetry), each with its Ceres sigma and the birotor fit's honesty rules.
#pragma once

#include <string>
#include <vector>

#include "identification/identification_options.h"
#include "identification/identification_result.h"
#include "model/vehicle_description.h"
#include "samples/multi_arm_samples.h"
#include "samples/samples.h"

namespace birotor {

// The N-arm channels of one log (STRAIN_N, MOTOR_N, LOADCELL_N on the bench;
// STRAIN_N, MOTOR_N, IMU in flight, multi_arm_flight_fit.h) and the VEHICLE
// description it was recorded with, when it has one.
struct MultiArmBenchLog {
  std::string source;
  std::vector<MultiArmStrainSample> strain;
  std::vector<MultiArmMotorSample> motor;
  std::vector<MultiArmLoadCellSample> loadcell;
  std::vector<ImuSample> imu;  // flight: pitch rate and specific force (the birotor's IMU channel)
  bool has_vehicle = false;
  VehicleDescription vehicle;  // the log's VEHICLE message (has_vehicle)
};

// Why the log cannot be fitted against `base`, one sentence; "" when it
// can: a VEHICLE whose arm_count differs from the description's, or any
// STRAIN_N / MOTOR_N / LOADCELL_N sample whose count is not arm_count.
std::string MultiArmLogMismatch(const MultiArmBenchLog& log, const VehicleDescription& base);

// The estimates of one arm and its rotor, in the description's keys
// (ArmDescription field names).
struct ArmEstimates {
  ParameterEstimate stiffness, damping, tip_mass, gauge_offset, thrust_coeff, motor_time_constant;
  double strain_rms_whitened =
      0.0;  // the arm's strain residual RMS (bench: clamped-arm fit; flight: free-flight fit) [sigma]
};

struct MultiArmIdentificationResult {
  bool flight = false;              // the flight fit (multi_arm_flight_fit.h), else the bench fit
  bool ok = false;                  // bench: every arm's k and o, every rotor's c_T, tau_m determined;
                                    // flight: every k, c_T, tau_m determined
  std::vector<std::string> errors;  // what the data lacks, one line each ("arm 2: ...")
  std::vector<std::string> advice;  // flight: what to fly or measure for what stays NOT DETERMINED
  VehicleDescription vehicle;       // base with every determined value
  std::vector<ArmEstimates> arms;   // arms[0 .. arm_count)
};

// The bench fit. Gauge scales are held at the description's (the factory
// fact of shared/spec/gauges.md: on the bench k, m_p and s_i are separated
// only through an outside fact; a weighed tip mass per arm is not supported
// here): a calibration fact in options is an error in the result. Every log
// must match `base` (MultiArmLogMismatch); a mismatch is an error too. d_i
// and m_p,i not determined leave result.ok true (marked, base value kept),
// as on the birotor's bench.
MultiArmIdentificationResult IdentifyMultiArmBench(const std::vector<MultiArmBenchLog>& logs,
                                                   const VehicleDescription& base,
                                                   const IdentificationOptions& options);

}  // namespace birotor

// Sensor samples as the estimator library sees them: plain structs with the
// unit in every field name, independent of LCM. transport/ converts the wire
// messages of lcmtypes/ to and from these.
#pragma once

#include <cstdint>

#include "samples/rotor_count.h"

namespace birotor {

// Strain-gauge arm deflections (channel STRAIN).
struct StrainSample {
  int64_t utime = 0;                               // vehicle clock [us]
  int32_t seq = 0;                                 // per-sensor counter, wraps
  double deflection_rad[kBirotorRotors] = {0, 0};  // arm i relative to the body, sign of phi [rad]
};

// Rotor speed commands and telemetry (channel MOTOR).
struct MotorSample {
  int64_t utime = 0;
  int32_t seq = 0;
  double omega_cmd_rad_s[kBirotorRotors] = {0, 0};   // commanded rotor speed [rad/s]
  double omega_meas_rad_s[kBirotorRotors] = {0, 0};  // ESC telemetry [rad/s]; NaN when absent
};

// Body rate gyro and accelerometer (channel IMU).
struct ImuSample {
  int64_t utime = 0;
  int32_t seq = 0;
  double gyro_y_rad_s = 0;  // body pitch rate phi_dot [rad/s]
  double accel_x_m_s2 = 0;  // specific force, body x [m/s^2]
  double accel_z_m_s2 = 0;  // specific force, body z [m/s^2]
};

// Motion-capture pose (channel POSE).
struct PoseSample {
  int64_t utime = 0;
  int32_t seq = 0;
  double x_m = 0, z_m = 0;  // world frame [m]
  double phi_rad = 0;       // body tilt [rad]
};

// Bench load cells (channel LOADCELL).
struct LoadCellSample {
  int64_t utime = 0;
  int32_t seq = 0;
  double force_n[kBirotorRotors] = {0, 0};  // rotor thrust [N]
};

// Simulator ground truth (channel TRUTH).
struct TruthSample {
  int64_t utime = 0;
  double x_m = 0, z_m = 0, phi_rad = 0;                  // body pose, world frame [m, rad]
  double deflection_rad[kBirotorRotors] = {0, 0};        // arm deflections [rad]
  double x_dot_m_s = 0, z_dot_m_s = 0;                   // body velocity, world frame [m/s]
  double phi_dot_rad_s = 0;                              // body pitch rate [rad/s]
  double deflection_dot_rad_s[kBirotorRotors] = {0, 0};  // arm deflection rates [rad/s]
  double omega_rad_s[kBirotorRotors] = {0, 0};           // actual rotor speeds [rad/s]
  double force_n[kBirotorRotors] = {0, 0};               // actual thrust [N]
  double thrust_scale[kBirotorRotors] = {1, 1};          // actual / nominal map [1]
};

// Bits of ForceEstimate::status; identical to the STATUS_* constants of
// lcmtypes/force_estimate_t.lcm (checked by a test).
enum StatusBit : int32_t {
  kStatusValid = 1,
  kStatusConverging = 2,
  kStatusMeasurementRejected = 4,
  kStatusInputStale = 8,
  kStatusRotor1Fault = 16,
  kStatusRotor2Fault = 32,
  kStatusFilterReset = 64,
  kStatusNoMotorInput = 128,
  kStatusThrustDeficit = 256,
  kStatusInputConflict = 512,
  kStatusModelMismatch = 1024,
};

// One per-rotor force estimate (channel FORCE).
struct ForceEstimate {
  int64_t utime = 0;                             // utime of the newest strain sample included [us]
  int32_t seq = 0;                               // seq of that strain sample
  double force_n[kBirotorRotors] = {0, 0};       // rotor thrust [N]
  double force_std_n[kBirotorRotors] = {0, 0};   // one sigma [N]
  double thrust_scale[kBirotorRotors] = {1, 1};  // actual / (c_T omega^2) [1]
  int32_t status = 0;                            // StatusBit set
};

}  // namespace birotor

// Sensor samples of a vehicle with N arms (docs/multi-arm-model.md,
// "Simulator"): the counted twins of StrainSample, MotorSample,
// LoadCellSample and TruthSample (samples/samples.h), as the wire's
// strain_n_t, motor_n_t, loadcell_n_t and truth_n_t. Plain structs with fixed storage; entries [0, n_arms) are used.
// IMU and POSE do not depend on the arms: ImuSample and PoseSample serve.
#pragma once

#include <array>
#include <cstdint>

namespace birotor {

// The most arms a sample holds (model/vehicle_description.h kMaxArms; the
// simulator checks that they agree).
inline constexpr int kMaxSampleArms = 6;
using ArmValues = std::array<double, kMaxSampleArms>;

// Strain-gauge arm deflections (channel STRAIN_N).
struct MultiArmStrainSample {
  int64_t utime = 0;           // vehicle clock [us]
  int32_t seq = 0;             // per-sensor counter
  int n_arms = 0;              // the description's arm_count
  ArmValues deflection_rad{};  // arm i relative to the body, sign of phi [rad]; NaN: no gauge on arm i
};

// Rotor speed commands and telemetry (channel MOTOR_N).
struct MultiArmMotorSample {
  int64_t utime = 0;
  int32_t seq = 0;
  int n_rotors = 0;
  ArmValues omega_cmd_rad_s{};   // commanded rotor speed [rad/s]
  ArmValues omega_meas_rad_s{};  // ESC telemetry [rad/s]; NaN when absent
};

// Test-bench load cells, one under each rotor (channel LOADCELL_N).
struct MultiArmLoadCellSample {
  int64_t utime = 0;
  int32_t seq = 0;
  int n_rotors = 0;
  ArmValues force_n{};  // thrust of rotor i along its axis [N]
};

// Simulator ground truth (channel TRUTH_N).
struct MultiArmTruthSample {
  int64_t utime = 0;
  double x_m = 0, z_m = 0, phi_rad = 0;  // body pose, world frame [m, rad]
  int n_arms = 0;
  ArmValues deflection_rad{};           // [rad]
  double x_dot_m_s = 0, z_dot_m_s = 0;  // body velocity, world frame [m/s]
  double phi_dot_rad_s = 0;             // [rad/s]
  ArmValues deflection_dot_rad_s{};     // [rad/s]
  ArmValues omega_rad_s{};              // actual rotor speeds [rad/s]
  ArmValues force_n{};                  // actual thrust [N]
  ArmValues thrust_scale{};             // actual / nominal map, mu_i [1]
};

// Rotor-force estimate of a vehicle with N arms (channel FORCE_N,
// force_estimate_n_t; estimator/multi_arm_ekf.h).
struct MultiArmForceEstimate {
  int64_t utime = 0;             // utime of the newest strain sample included [us]
  int32_t seq = 0;               // seq of that strain sample
  int n_rotors = 0;              // the description's arm_count
  ArmValues force_n{};           // rotor thrust [N]
  ArmValues force_std_n{};       // one sigma [N]
  ArmValues thrust_scale{};      // actual / (c_T,i omega_i^2), mu_i [1]
  int32_t status = 0;            // StatusBit set (samples/samples.h), force_estimate_n_t's STATUS_*
  int32_t rotor_fault_bits = 0;  // bit i: rotor i + 1 weaker than the others (ROTOR_FAULT_ROTOR*)
};

}  // namespace birotor

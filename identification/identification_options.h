// Options of the identification (noise levels used to whiten the residuals,
// window lengths, robust loss, acceptance thresholds). Every field has a
// documented default; ReadIdentificationOptions loads the `identification:` section.
#pragma once

#include <string>

#include "params/yaml_reader.h"

namespace birotor {

struct IdentificationOptions {
  // Sensor noise, one sigma (reference sensors of reference-vehicle.md).
  double strain_noise_rad = 2e-5;        // strain gauges [rad]
  double telemetry_noise_rad_s = 5.0;    // ESC speed telemetry [rad/s]
  double loadcell_noise_n = 0.02;        // bench load cells [N]
  double gyro_noise_rad_s = 0.005;       // IMU pitch rate [rad/s]
  double accel_noise_m_s2 = 0.05;        // IMU specific force [m/s^2]
  // Thrust regression (bench): one load-cell/telemetry pair every this many
  // seconds, so that the turbulence (correlation time 0.1 s) is nearly white
  // between pairs; the turbulence std of the base parameters is added to sigma.
  double thrust_sample_spacing_s = 0.3;
  // Output-error windows (multiple shooting, each window has its own initial state).
  double motor_window_s = 1.0;           // motor speed response [s]
  double bench_arm_window_s = 0.5;       // clamped arm response [s]
  double flight_window_s = 0.3;          // free-flight arm response [s]
  int integration_substeps = 2;          // RK4 steps per sample interval of the arm models
  // Robust loss: Huber with this threshold on whitened residuals [sigma].
  double huber_threshold = 3.0;
  // Static deflection-force map: polynomial degree (1..3).
  int map_degree = 1;
  // Use the IMU (gyro and accelerometer) in flight identification when present.
  bool use_imu = true;
  // Refusal thresholds.
  double min_duration_s = 5.0;           // shorter logs are refused [s]
  double max_relative_sigma = 0.2;       // above: the parameter is not determined [1]
  double command_step_rad_s = 30.0;      // a command change this large in one sample is a step [rad/s]
  int min_command_steps = 2;             // fewer steps per rotor: no excitation for tau_m
  // Solver.
  int max_iterations = 50;
  int num_threads = 2;
};

// Overrides the fields present in the section (keys are the field names);
// unknown keys and values out of range throw ParamError.
void ReadIdentificationOptions(YamlSection section, IdentificationOptions* options);

}  // namespace birotor

// Options of the identification (noise levels used to whiten the residuals,
// window lengths, robust loss, acceptance thresholds). Every field has a
// documented default; ReadIdentificationOptions loads the `identification:` section.
#pragma once

#include <string>

#include "params/yaml_reader.h"

namespace birotor {

struct IdentificationOptions {
  // Sensor noise, one sigma (reference sensors of reference-vehicle.md).
  double strain_noise_rad = 2e-5;      // strain gauges [rad]
  double telemetry_noise_rad_s = 5.0;  // ESC speed telemetry [rad/s]
  double loadcell_noise_n = 0.02;      // bench load cells [N]
  double gyro_noise_rad_s = 0.005;     // IMU pitch rate [rad/s]
  double accel_noise_m_s2 = 0.05;      // IMU specific force [m/s^2]
  // Thrust regression (bench): one load-cell/telemetry pair every this many
  // seconds, so that the turbulence (correlation time 0.1 s) is nearly white
  // between pairs; the turbulence std of the base parameters is added to sigma.
  double thrust_sample_spacing_s = 0.3;
  // Output-error windows (multiple shooting, each window has its own initial state).
  double motor_window_s = 1.0;      // motor speed response [s]
  double bench_arm_window_s = 0.5;  // clamped arm response [s]
  double flight_window_s = 0.3;     // free-flight arm response [s]
  int integration_substeps = 2;     // RK4 steps per sample interval of the clamped arm (bench)
  // Free flight: RK4 steps per strain interval (1 ms at 1 kHz; the arm modes
  // near 80 Hz give a k bias of about 0.1 %, far below the flight sigma).
  int flight_integration_substeps = 1;
  // Free flight: at most this many windows, spread evenly over the logs (0:
  // every window). 40 windows of 0.3 s keep k, c_T well inside 1 % on
  // flight_id at a quarter of the cost of the whole 60 s log.
  int flight_max_windows = 40;
  // Free flight: fit the hinge damping d too. Off by default: the flight
  // windows barely constrain d (flight_id: d = 0 +- 0.23 for a truth of
  // 0.25), and a large trial d makes the 1 ms RK4 step unstable; d is then
  // held at the base value and reported as not determined.
  bool flight_fit_damping = false;
  // Robust loss: Huber with this threshold on whitened residuals [sigma].
  double huber_threshold = 3.0;
  // Static deflection-force map: polynomial degree (1..3).
  int map_degree = 1;
  // Use the IMU (gyro and accelerometer) in flight identification when present.
  bool use_imu = true;
  // Refusal thresholds.
  double min_duration_s = 5.0;  // shorter logs are refused [s]
  // A sample stamped more than this after the previous one is kept only if
  // the next sample continues from it; otherwise it is a lone stamp from the
  // future, dropped as a bad stamp. Ten intervals of the slowest stream
  // (POSE, 100 Hz) [s].
  double max_time_jump_s = 0.1;
  double max_relative_sigma = 0.2;   // above: the parameter is not determined [1]
  double command_step_rad_s = 30.0;  // a command change this large in one sample is a step [rad/s]
  int min_command_steps = 2;         // fewer steps per rotor: no excitation for tau_m
  // Solver.
  int max_iterations = 50;
  int num_threads = 2;
};

// Reads every field from the section (keys are the field names; each is
// required); unknown keys and values out of range throw ParamError.
void ReadIdentificationOptions(YamlSection section, IdentificationOptions* options);

// Loads the `identification:` section of a file (config/identification.yaml
// has every key at its default); throws ParamError naming the file and every
// missing key.
IdentificationOptions LoadIdentificationOptions(const std::string& file);

}  // namespace birotor

// Options of the force estimator (method, filter tuning, gates, timeouts),
// with the reference vehicle; every field has a documented default and is
// loaded from the `estimator:` section of a parameter file by params/.
#pragma once

#include <string>

#include "model/vehicle_params.h"

namespace birotor {

// Tuning of the extended Kalman filter (estimator/ekf_force_estimator.h).
// Spectral densities q are continuous-time: the variance added over dt is q dt.
struct EkfOptions {
  // Measurement noise (one sigma).
  double strain_noise_rad = 2e-5;        // strain-gauge deflection noise [rad]
  double motor_speed_noise_rad_s = 5.0;  // ESC telemetry noise [rad/s]
  double gyro_noise_rad_s = 0.005;       // IMU pitch-rate noise [rad/s]
  bool use_motor_telemetry = true;       // fuse omega_meas when finite
  bool use_gyro = true;                  // fuse IMU gyro_y when IMU samples arrive
  // Process noise. Thrust scale mu: random walk standing in for the
  // Gauss-Markov turbulence, q = 2 sigma^2 / tau (2e-3 /s for the reference).
  double thrust_scale_psd_1_s = 2e-3;         // [1/s]
  double deflection_rate_psd_rad2_s3 = 1e-4;  // on b_i_dot [(rad/s)^2/s]
  double pitch_rate_psd_rad2_s3 = 1e-4;       // on phi_dot [(rad/s)^2/s]
  double omega_psd_rad2_s = 100.0;            // on omega_i [(rad/s)^2/s]
  // Initial one-sigma uncertainties.
  double initial_thrust_scale_std = 0.3;            // [1]
  double initial_omega_std_rad_s = 30.0;            // [rad/s]
  double initial_deflection_rate_std_rad_s = 0.05;  // [rad/s]
  double initial_pitch_rate_std_rad_s = 0.5;        // [rad/s]
  // Chi-square gate on the 2-dof strain innovation (normalised innovation squared).
  double gate_nis_threshold = 30.0;  // [1]; p(false reject) ~ 3e-7
  // After this many consecutive gated strain samples the change is taken as
  // real (a step in thrust): the covariance is inflated and the sample fused.
  int gate_consecutive_limit = 3;
  double gate_inflation_thrust_scale_std = 0.1;  // added to std(mu_i) [1]
  // Status: kStatusConverging until both force stds fall below this [N].
  double converged_force_std_n = 0.5;
  // Rotor fault: flagged when mu_i + n_sigma std(mu_i) < fault_thrust_scale for
  // fault_persistence_s; cleared when mu_i - n_sigma std(mu_i) > fault_clear_thrust_scale.
  double fault_thrust_scale = 0.85;        // [1]
  double fault_clear_thrust_scale = 0.88;  // [1] (hysteresis)
  double fault_n_sigma = 3.0;              // [1]
  double fault_persistence_s = 0.01;       // [s]
  // Strain interval bounds: dt > max_dt_s re-initialises the filter.
  double max_dt_s = 0.1;  // [s]
  // Longer strain intervals (a gap shorter than max_dt_s) are predicted in
  // RK4 steps of at most this: one RK4 step is only stable and accurate for
  // omega_arm dt well below 2.8 (arm modes ~500 rad/s).
  double max_prediction_step_s = 0.002;  // [s]
};

// The thesis's open-loop model inversion (thesis eq. 5.1-5.2).
struct InversionOptions {
  // Samples in the causal quadratic fit giving b, b_dot, b_ddot (3 = exact
  // interpolation, for noise-free data). 63 is the best of 15, 31 and 63 at
  // the reference noise (force MAE 0.32, 0.16, 0.12 N on gentle): the
  // baseline is measured at its best, not handicapped. At most 64.
  int window_samples = 63;
  // One sigma reported as force_std_n (the inversion has no covariance) [N].
  double force_std_n = 1.0;
};

// The nominal motor map f = c_T omega^2.
struct MotorMapOptions {
  double motor_speed_noise_rad_s = 5.0;  // telemetry noise, for force_std_n [rad/s]
  double model_speed_std_rad_s = 10.0;   // omega from the motor model of the commands [rad/s]
};

// Input validation and book-keeping of EstimatorPipeline.
struct PipelineOptions {
  double reset_gap_s = 0.1;             // strain gap that re-initialises the method [s]
  double time_backwards_reset_s = 0.5;  // a jump back larger than this resets (log loop) [s]
  double motor_timeout_s = 0.05;        // newest MOTOR older than this: kStatusInputStale [s]
  double strain_timeout_s = 0.01;       // strain interval longer than this: kStatusInputStale [s]
  double max_deflection_rad = 0.2;      // |b_i| above this is an invalid sample [rad]
  double max_omega_rad_s = 1e4;         // |omega| above this is an invalid sample [rad/s]
  double max_gyro_rad_s = 100.0;        // |gyro| above this is an invalid sample [rad/s]
};

struct EstimatorConfig {
  VehicleParams vehicle;       // `vehicle:` section
  std::string method = "ekf";  // "ekf", "inversion" or "motor_map"
  EkfOptions ekf;              // `estimator.ekf:`
  InversionOptions inversion;  // `estimator.inversion:`
  MotorMapOptions motor_map;   // `estimator.motor_map:`
  PipelineOptions pipeline;    // `estimator.pipeline:`
};

}  // namespace birotor

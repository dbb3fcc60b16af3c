// Parameters of the flight controllers as plain structs with documented
// defaults: the gains of the cascaded position/pitch law (shared by the
// simulator's autopilot and birotor-controller) and the options of the
// controller service (state observer, force feedback, fallback, descent).
// params/controller_config_yaml.h loads them.
#pragma once

#include "controller/mpc_params.h"
#include "model/vehicle_params.h"

namespace birotor {

// Cascaded PD (+ integral) on the rigid-body approximation, 500 Hz. Outer
// loop: desired acceleration from the position error (critically damped,
// 3 rad/s); inner loop: desired pitch acceleration from the tilt error
// (20 rad/s, below the motor lag and far below the 65/80 Hz arm modes).
struct ControllerParams {
  double rate_hz = 500.0;
  double position_kp_1_s2 = 9.0;
  double position_kd_1_s = 6.0;
  double position_ki_1_s3 = 3.0;
  double attitude_kp_1_s2 = 400.0;
  double attitude_kd_1_s = 32.0;
  double attitude_ki_1_s3 = 600.0;
  double max_tilt_rad = 0.5;
  double max_integral_m_s2 = 3.0;              // clamp of the position integral term
  double max_attitude_integral_rad_s2 = 40.0;  // clamp of the attitude integral term
};

// Body-state observer of the controller service (it never sees TRUTH):
// position and velocity per world axis propagated with the accelerometer and
// corrected by POSE with the gains of a critically damped second-order
// observer, L = [2 w, w^2]; tilt propagated with the gyro and pulled towards
// POSE's phi with the crossover frequency below.
struct ObserverParams {
  double position_bandwidth_rad_s = 10.0;  // w of the position/velocity observer [rad/s]
  double attitude_crossover_rad_s = 5.0;   // gyro/POSE complementary-filter crossover [rad/s]
};

// What the controller service does with FORCE, and when it stops trusting
// an input.
struct SupervisionParams {
  double pose_timeout_s = 0.05;    // POSE older than this: controlled descent [s]
  double imu_timeout_s = 0.01;     // IMU older than this: propagate without it [s]
  double force_timeout_s = 0.005;  // FORCE older than this: fall back to the nominal map [s]
  double force_recovery_s = 0.05;  // FORCE healthy this long before force feedback resumes [s]
  double min_thrust_scale = 0.3;   // estimated thrust_scale used is clamped to [min, max] [1]
  double max_thrust_scale = 1.5;   // [1]
  double descent_rate_m_s = 0.3;   // sink rate of the controlled descent [m/s]
};

// What the controller accepts on SETPOINT (controller/setpoint_input.h).
struct SetpointParams {
  double timeout_s = 0.5;             // newest setpoint held this long, then hover where the vehicle is [s]
  double max_extrapolation_s = 0.05;  // a held setpoint moves on with its feed-forward this long [s]
  double future_window_s = 0.1;       // stamps later than the controller's clock plus this are refused [s]
  double min_interval_s = 0.002;      // rate limit: stamps closer than this to the newest are refused [s]
  double max_abs_position_m = 100.0;  // |x|, |z| accepted [m]
  double max_speed_m_s = 5.0;         // |velocity feed-forward| accepted, per axis [m/s]
  double max_accel_m_s2 = 10.0;       // |acceleration feed-forward| accepted, per axis [m/s^2]
  double max_jump_m = 0.5;            // distance from the reference flown now accepted [m]
};

// Everything birotor-controller (and the lock-step closed loop) needs.
struct ControllerConfig {
  VehicleParams vehicle;       // the controller's model of the vehicle
  bool force_feedback = true;  // mode: force_feedback (true) or nominal (false)
  // mode: mpc: the model predictive controller (controller/mpc_controller.h)
  // flies, the cascade (on force feedback) is its per-period fallback.
  bool model_predictive = false;
  MpcParams mpc;  // the mpc: section
  ControllerParams gains;
  ObserverParams observer;
  SupervisionParams supervision;
  SetpointParams setpoint;
};

// MOTOR_COMMAND rate [Hz]: the cascade's rate_hz, or in mode mpc the MPC's.
inline double CommandRateHz(const ControllerConfig& config) {
  return config.model_predictive ? config.mpc.rate_hz : config.gains.rate_hz;
}

}  // namespace birotor

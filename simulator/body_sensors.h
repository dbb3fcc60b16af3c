// The body's sensors as the simulators measure them (the IMU, motion capture
// and ESC telemetry of shared/spec/reference-vehicle.md, white noise): one
// copy for the birotor and the N-arm simulator. utime and seq are the caller's.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "samples/samples.h"
#include "simulator/noise.h"
#include "simulator/scenario.h"

namespace birotor {

// The rigid body's state and acceleration the sensors see (world frame).
struct BodyMotion {
  double x_m = 0, z_m = 0, phi_rad = 0;     // pose [m, rad]
  double phi_dot_rad_s = 0;                 // pitch rate [rad/s]
  double x_ddot_m_s2 = 0, z_ddot_m_s2 = 0;  // acceleration [m/s^2]
};

// Gyro phi_dot + n; specific force in body axes R(phi)^T (p_ddot + [0, g]) + n.
inline void MeasureImu(const BodyMotion& body, double gravity_m_s2, const SensorParams& sensors, GaussianSource* noise,
                       ImuSample* sample) {
  const double c = std::cos(body.phi_rad), s = std::sin(body.phi_rad);
  const double ax = body.x_ddot_m_s2;
  const double az = body.z_ddot_m_s2 + gravity_m_s2;
  sample->gyro_y_rad_s = body.phi_dot_rad_s + noise->Normal(sensors.gyro_noise_rad_s);
  sample->accel_x_m_s2 = c * ax + s * az + noise->Normal(sensors.accel_noise_m_s2);
  sample->accel_z_m_s2 = -s * ax + c * az + noise->Normal(sensors.accel_noise_m_s2);
}

// Pose + n.
inline void MeasurePose(const BodyMotion& body, const SensorParams& sensors, GaussianSource* noise,
                        PoseSample* sample) {
  sample->x_m = body.x_m + noise->Normal(sensors.pose_position_noise_m);
  sample->z_m = body.z_m + noise->Normal(sensors.pose_position_noise_m);
  sample->phi_rad = body.phi_rad + noise->Normal(sensors.pose_angle_noise_rad);
}

// ESC telemetry of one rotor: omega + n [rad/s], never negative (near 0
// while the motors are stopped); NaN when not reported (telemetry off or in
// a gap). The noise is drawn either way, so a gap does not shift the stream.
inline double MeasureRotorSpeed(double omega_rad_s, bool reported, const SensorParams& sensors, GaussianSource* noise) {
  const double n = noise->Normal(sensors.motor_speed_noise_rad_s);
  return reported ? std::max(0.0, omega_rad_s + n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace birotor

#include "controller/position_attitude_law.h"

#include <algorithm>
#include <cmath>

namespace birotor {

PositionAttitudeLaw::PositionAttitudeLaw(const BirotorParams& vehicle, const ControllerParams& gains,
                                         double hover_force_n)
    : vehicle_(vehicle),
      gains_(gains),
      hover_total_force_n_(2.0 * hover_force_n),
      dt_s_(1.0 / gains.rate_hz),
      tilt_limit_rad_(gains.max_tilt_rad) {}

void PositionAttitudeLaw::Reset() {
  position_integral_m_s_.setZero();
  tilt_integral_rad_s_ = 0.0;
}

Eigen::Vector2d PositionLoopAcceleration(const ControllerParams& gains, double dt_s, const BodyState& state,
                                         const ReferencePoint& reference, bool integrate,
                                         Eigen::Vector2d* position_integral_m_s) {
  Eigen::Vector2d& integral = *position_integral_m_s;
  const Eigen::Vector2d position_error = reference.position_m - state.position_m;
  if (integrate) integral += dt_s * position_error;
  const double integral_limit = gains.max_integral_m_s2 / std::max(gains.position_ki_1_s3, 1e-9);
  integral = integral.cwiseMax(-integral_limit).cwiseMin(integral_limit);
  return reference.acceleration_m_s2 + gains.position_kp_1_s2 * position_error +
         gains.position_kd_1_s * (reference.velocity_m_s - state.velocity_m_s) + gains.position_ki_1_s3 * integral;
}

TiltTarget TiltForAcceleration(const ControllerParams& gains, double gravity_m_s2,
                               const Eigen::Vector2d& accel_des_m_s2) {
  TiltTarget target;
  target.vertical_m_s2 = std::max(gravity_m_s2 + accel_des_m_s2.y(), 0.1 * gravity_m_s2);
  target.phi_des_rad =
      std::clamp(std::atan2(-accel_des_m_s2.x(), target.vertical_m_s2), -gains.max_tilt_rad, gains.max_tilt_rad);
  return target;
}

double TiltLoopAcceleration(const ControllerParams& gains, double dt_s, double phi_des_rad, const BodyState& state,
                            bool integrate, double* tilt_integral_rad_s) {
  const double tilt_error = phi_des_rad - state.phi_rad;
  if (integrate) *tilt_integral_rad_s += dt_s * tilt_error;
  const double tilt_limit = gains.max_attitude_integral_rad_s2 / std::max(gains.attitude_ki_1_s3, 1e-9);
  *tilt_integral_rad_s = std::clamp(*tilt_integral_rad_s, -tilt_limit, tilt_limit);
  return gains.attitude_kp_1_s2 * tilt_error - gains.attitude_kd_1_s * state.phi_dot_rad_s +
         gains.attitude_ki_1_s3 * *tilt_integral_rad_s;
}

RotorForces PositionAttitudeLaw::Update(const BodyState& state, const ReferencePoint& reference,
                                        bool integrate_position, bool integrate_tilt) {
  const BirotorParams& p = vehicle_;
  const double g = p.gravity_m_s2;
  RotorForces out;
  out.accel_des_m_s2 =
      PositionLoopAcceleration(gains_, dt_s_, state, reference, integrate_position, &position_integral_m_s_);
  TiltTarget tilt = TiltForAcceleration(gains_, g, out.accel_des_m_s2);
  tilt.phi_des_rad = std::clamp(tilt.phi_des_rad, -tilt_limit_rad_, tilt_limit_rad_);
  // Feed-forward scaled from the exact hover equilibrium: F = F_hover (g + a_z) / (g cos phi).
  const double total_force_n =
      hover_total_force_n_ * tilt.vertical_m_s2 / (g * std::cos(std::clamp(state.phi_rad, -1.2, 1.2)));
  const double alpha_des =
      TiltLoopAcceleration(gains_, dt_s_, tilt.phi_des_rad, state, integrate_tilt, &tilt_integral_rad_s_);
  const double L = p.arm_length_m;
  const double force_difference_n = RigidPitchInertiaKgM2(p) * alpha_des / L;  // f2 - f1

  out.total_force_n = total_force_n;
  out.force_difference_n = force_difference_n;
  out.force_n[0] = 0.5 * (total_force_n - force_difference_n);
  out.force_n[1] = 0.5 * (total_force_n + force_difference_n);
  return out;
}

double RotorSpeedForThrust(const BirotorParams& vehicle, double force_n, double thrust_scale, bool* saturated) {
  return RotorSpeedForThrust(vehicle.thrust_coeff_n_s2_rad2, vehicle.omega_max_rad_s, force_n, thrust_scale, saturated);
}

double RotorSpeedForThrust(double thrust_coeff_n_s2_rad2, double omega_max_rad_s, double force_n, double thrust_scale,
                           bool* saturated) {
  const double omega = std::sqrt(std::max(force_n, 0.0) / (thrust_scale * thrust_coeff_n_s2_rad2));
  const double clipped = std::min(omega, omega_max_rad_s);
  if (saturated != nullptr) *saturated = clipped != omega || force_n < 0.0;
  return clipped;
}

}  // namespace birotor

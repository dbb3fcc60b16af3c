#include "controller/position_attitude_law.h"

#include <algorithm>
#include <cmath>

namespace birotor {

PositionAttitudeLaw::PositionAttitudeLaw(const VehicleParams& vehicle, const ControllerParams& gains,
                                         double hover_force_n)
    : vehicle_(vehicle), gains_(gains), hover_total_force_n_(2.0 * hover_force_n), dt_s_(1.0 / gains.rate_hz) {}

void PositionAttitudeLaw::Reset() {
  position_integral_m_s_.setZero();
  tilt_integral_rad_s_ = 0.0;
}

RotorForces PositionAttitudeLaw::Update(const BodyState& state, const ReferencePoint& reference, bool integrate) {
  const VehicleParams& p = vehicle_;
  const double g = p.gravity_m_s2;

  // Outer loop (world frame).
  const Eigen::Vector2d position_error = reference.position_m - state.position_m;
  if (integrate) position_integral_m_s_ += dt_s_ * position_error;
  const double integral_limit = gains_.max_integral_m_s2 / std::max(gains_.position_ki_1_s3, 1e-9);
  position_integral_m_s_ = position_integral_m_s_.cwiseMax(-integral_limit).cwiseMin(integral_limit);
  RotorForces out;
  out.accel_des_m_s2 = reference.acceleration_m_s2 + gains_.position_kp_1_s2 * position_error +
                       gains_.position_kd_1_s * (reference.velocity_m_s - state.velocity_m_s) +
                       gains_.position_ki_1_s3 * position_integral_m_s_;
  const double vertical = std::max(g + out.accel_des_m_s2.y(), 0.1 * g);
  const double phi_des =
      std::clamp(std::atan2(-out.accel_des_m_s2.x(), vertical), -gains_.max_tilt_rad, gains_.max_tilt_rad);
  // Feed-forward scaled from the exact hover equilibrium: F = F_hover (g + a_z) / (g cos phi).
  const double total_force_n = hover_total_force_n_ * vertical / (g * std::cos(std::clamp(state.phi_rad, -1.2, 1.2)));

  // Inner loop (pitch).
  const double tilt_error = phi_des - state.phi_rad;
  if (integrate) tilt_integral_rad_s_ += dt_s_ * tilt_error;
  const double tilt_limit = gains_.max_attitude_integral_rad_s2 / std::max(gains_.attitude_ki_1_s3, 1e-9);
  tilt_integral_rad_s_ = std::clamp(tilt_integral_rad_s_, -tilt_limit, tilt_limit);
  const double alpha_des = gains_.attitude_kp_1_s2 * tilt_error - gains_.attitude_kd_1_s * state.phi_dot_rad_s +
                           gains_.attitude_ki_1_s3 * tilt_integral_rad_s_;
  const double L = p.arm_length_m;
  const double force_difference_n = RigidPitchInertiaKgM2(p) * alpha_des / L;  // f2 - f1

  out.total_force_n = total_force_n;
  out.force_difference_n = force_difference_n;
  out.force_n[0] = 0.5 * (total_force_n - force_difference_n);
  out.force_n[1] = 0.5 * (total_force_n + force_difference_n);
  return out;
}

double RotorSpeedForThrust(const VehicleParams& vehicle, double force_n, double thrust_scale, bool* saturated) {
  const double omega = std::sqrt(std::max(force_n, 0.0) / (thrust_scale * vehicle.thrust_coeff_n_s2_rad2));
  const double clipped = std::min(omega, vehicle.omega_max_rad_s);
  if (saturated != nullptr) *saturated = clipped != omega || force_n < 0.0;
  return clipped;
}

}  // namespace birotor

#include "simulator/flight_controller.h"

#include <algorithm>
#include <cmath>

namespace birotor {

FlightController::FlightController(const VehicleParams& vehicle, const ControllerParams& params, double hover_force_n)
    : vehicle_(vehicle), params_(params), hover_total_force_n_(2.0 * hover_force_n), dt_s_(1.0 / params.rate_hz) {}

RotorCommand FlightController::Update(const PlantState& state, const ReferencePoint& reference) {
  const VehicleParams& p = vehicle_;
  const double g = p.gravity_m_s2;
  const Eigen::Vector2d position(state(kPlantQ + kX), state(kPlantQ + kZ));
  const Eigen::Vector2d velocity(state(kPlantV + kX), state(kPlantV + kZ));
  const double phi = state(kPlantQ + kPhi);
  const double phi_dot = state(kPlantV + kPhi);

  // Outer loop (world frame).
  const Eigen::Vector2d position_error = reference.position_m - position;
  position_integral_m_s_ += dt_s_ * position_error;
  const double integral_limit = params_.max_integral_m_s2 / std::max(params_.position_ki_1_s3, 1e-9);
  position_integral_m_s_ = position_integral_m_s_.cwiseMax(-integral_limit).cwiseMin(integral_limit);
  const Eigen::Vector2d accel_des = reference.acceleration_m_s2 + params_.position_kp_1_s2 * position_error +
                                    params_.position_kd_1_s * (reference.velocity_m_s - velocity) +
                                    params_.position_ki_1_s3 * position_integral_m_s_;
  const double vertical = std::max(g + accel_des.y(), 0.1 * g);
  const double phi_des = std::clamp(std::atan2(-accel_des.x(), vertical), -params_.max_tilt_rad, params_.max_tilt_rad);
  // Feed-forward scaled from the exact hover equilibrium: F = F_hover (g + a_z) / (g cos phi).
  const double total_force_n = hover_total_force_n_ * vertical / (g * std::cos(std::clamp(phi, -1.2, 1.2)));

  // Inner loop (pitch).
  const double tilt_error = phi_des - phi;
  tilt_integral_rad_s_ += dt_s_ * tilt_error;
  const double tilt_limit = params_.max_attitude_integral_rad_s2 / std::max(params_.attitude_ki_1_s3, 1e-9);
  tilt_integral_rad_s_ = std::clamp(tilt_integral_rad_s_, -tilt_limit, tilt_limit);
  const double alpha_des = params_.attitude_kp_1_s2 * tilt_error - params_.attitude_kd_1_s * phi_dot +
                           params_.attitude_ki_1_s3 * tilt_integral_rad_s_;
  const double L = p.arm_length_m;
  const double inertia = p.body_inertia_kg_m2 + 2.0 * p.tip_mass_kg * L * L;
  const double force_difference_n = inertia * alpha_des / L;  // f2 - f1

  const double forces_n[2] = {0.5 * (total_force_n - force_difference_n), 0.5 * (total_force_n + force_difference_n)};
  RotorCommand command;
  for (int i = 0; i < 2; ++i) {
    // Nominal thrust map only: the controller does not know mu_i.
    const double omega = std::sqrt(std::max(forces_n[i], 0.0) / p.thrust_coeff_n_s2_rad2);
    command.omega_cmd_rad_s[i] = std::min(omega, p.omega_max_rad_s);
  }
  return command;
}

}  // namespace birotor

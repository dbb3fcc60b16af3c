#include "simulator/multi_arm_autopilot.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "controller/position_attitude_law.h"

namespace birotor {
namespace {

MultiArmControlMode ModeFor(const VehicleDescription& vehicle) {
  if (vehicle.arm_count < 3) return MultiArmControlMode::kTiltToMove;
  const AllocationMargin margin = ControlledAxesMargin(vehicle);
  return margin.rows == kWrenchSize && margin.ratio >= kMinAllocationSingularRatio ? MultiArmControlMode::kFullyActuated
                                                                                   : MultiArmControlMode::kTiltToMove;
}

// P = W_r^T (W_r W_r^T)^-1 on the controlled rows (all three, or F_z and
// torque), placed in the columns of those rows; once, at construction.
Eigen::MatrixXd AllocationPseudoinverse(const VehicleDescription& vehicle, MultiArmControlMode mode) {
  const AllocationMatrix allocation = WrenchAllocation(vehicle);
  const int first_row = mode == MultiArmControlMode::kFullyActuated ? kWrenchFx : kWrenchFz;
  const int rows = kWrenchSize - first_row;
  const Eigen::MatrixXd controlled = allocation.bottomRows(rows);
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(vehicle.arm_count, kWrenchSize);
  inverse.rightCols(rows) = controlled.transpose() * (controlled * controlled.transpose()).inverse();
  return inverse;
}

}  // namespace

MultiArmAutopilot::MultiArmAutopilot(const VehicleDescription& vehicle, const ControllerParams& gains,
                                     const MultiArmHover& hover)
    : vehicle_(vehicle),
      gains_(gains),
      dt_s_(1.0 / gains.rate_hz),
      mode_(ModeFor(vehicle)),
      total_mass_kg_(vehicle.TotalMass()),
      pitch_inertia_kg_m2_(vehicle.body_inertia_kg_m2),
      hover_force_n_(hover.force_n),
      max_force_n_(vehicle.arm_count),
      allocation_inverse_(AllocationPseudoinverse(vehicle, mode_)) {
  for (int i = 0; i < vehicle.arm_count; ++i) {
    const ArmDescription& arm = vehicle.arms[static_cast<size_t>(i)];
    pitch_inertia_kg_m2_ += arm.tip_mass_kg * arm.length_m * arm.length_m;
    max_force_n_(i) = arm.thrust_coeff_n_s2_rad2 * vehicle.omega_max_rad_s * vehicle.omega_max_rad_s;
  }
}

bool MultiArmAutopilot::AddAxis(int axis, double wrench_change, ArmForces<double>* force_n) const {
  ArmForces<double>& f = *force_n;
  double scale = 1.0;
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    const double change = allocation_inverse_(i, axis) * wrench_change;
    if (f(i) + change > max_force_n_(i)) scale = std::min(scale, std::max(0.0, (max_force_n_(i) - f(i)) / change));
    if (f(i) + change < 0.0) scale = std::min(scale, std::max(0.0, -f(i) / change));
  }
  f += (scale * wrench_change) * allocation_inverse_.col(axis);
  return scale < 1.0;
}

MultiArmRotorCommand MultiArmAutopilot::Update(const MultiArmPlantState& state, const ReferencePoint& reference) {
  const VehicleDescription& v = vehicle_;
  const double g = v.gravity_m_s2;
  BodyState body;
  body.position_m = Eigen::Vector2d(state(MultiArmQIndex(v, kX)), state(MultiArmQIndex(v, kZ)));
  body.velocity_m_s = Eigen::Vector2d(state(MultiArmVIndex(v, kX)), state(MultiArmVIndex(v, kZ)));
  body.phi_rad = state(MultiArmQIndex(v, kPhi));
  body.phi_dot_rad_s = state(MultiArmVIndex(v, kPhi));
  const bool integrate = !saturated_;

  const Eigen::Vector2d accel_des_m_s2 =
      PositionLoopAcceleration(gains_, dt_s_, body, reference, integrate, &position_integral_m_s_);
  const double cos_phi = std::cos(std::clamp(body.phi_rad, -1.2, 1.2));
  Eigen::Vector3d wrench;  // [F_x, F_z, torque], body frame [N, N, N m]
  double phi_des_rad = 0.0;
  if (mode_ == MultiArmControlMode::kTiltToMove) {
    const TiltTarget tilt = TiltForAcceleration(gains_, g, accel_des_m_s2);
    phi_des_rad = tilt.phi_des_rad;
    wrench(kWrenchFx) = 0.0;
    wrench(kWrenchFz) = total_mass_kg_ * tilt.vertical_m_s2 / cos_phi;
  } else {
    // [F_x; F_z] = R(phi)^T m (a_des + g e_z), R(phi) = [cos, -sin; sin, cos].
    const double sin_phi = std::sin(body.phi_rad);
    const Eigen::Vector2d world_n = total_mass_kg_ * Eigen::Vector2d(accel_des_m_s2.x(), accel_des_m_s2.y() + g);
    wrench(kWrenchFx) = std::cos(body.phi_rad) * world_n.x() + sin_phi * world_n.y();
    wrench(kWrenchFz) = -sin_phi * world_n.x() + std::cos(body.phi_rad) * world_n.y();
  }
  wrench(kWrenchTorque) =
      pitch_inertia_kg_m2_ * TiltLoopAcceleration(gains_, dt_s_, phi_des_rad, body, integrate, &tilt_integral_rad_s_);
  wrench(kWrenchFz) -= total_mass_kg_ * g;  // the hover thrusts carry the weight

  ArmForces<double> force_n = hover_force_n_;
  bool saturated = false;
  for (int axis : {kWrenchTorque, kWrenchFz, kWrenchFx}) saturated |= AddAxis(axis, wrench(axis), &force_n);
  MultiArmRotorCommand command;
  for (int i = 0; i < v.arm_count; ++i) {
    const ArmDescription& arm = v.arms[static_cast<size_t>(i)];
    const double clamped_n = std::clamp(force_n(i), 0.0, max_force_n_(i));
    saturated |= clamped_n != force_n(i);
    command.force_n[static_cast<size_t>(i)] = clamped_n;
    // Nominal thrust map only: the autopilot does not know mu_i.
    command.omega_cmd_rad_s[static_cast<size_t>(i)] =
        RotorSpeedForThrust(arm.thrust_coeff_n_s2_rad2, v.omega_max_rad_s, clamped_n, 1.0);
  }
  command.saturated = saturated;
  saturated_ = saturated;
  return command;
}

}  // namespace birotor

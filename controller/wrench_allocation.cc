#include "controller/wrench_allocation.h"

#include <Eigen/Dense>
#include <algorithm>

#include "controller/position_attitude_law.h"

namespace birotor {
namespace {

// P = W_r^T (W_r W_r^T)^-1 on the controlled rows (all three, or F_z and
// torque), placed in the columns of those rows.
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

MultiArmControlMode MultiArmControlModeFor(const VehicleDescription& vehicle) {
  if (vehicle.arm_count < 3) return MultiArmControlMode::kTiltToMove;
  const AllocationMargin margin = ControlledAxesMargin(vehicle);
  return margin.rows == kWrenchSize && margin.ratio >= kMinAllocationSingularRatio ? MultiArmControlMode::kFullyActuated
                                                                                   : MultiArmControlMode::kTiltToMove;
}

WrenchAllocator::WrenchAllocator(const VehicleDescription& vehicle, MultiArmControlMode mode)
    : mode_(mode),
      rotor_count_(vehicle.arm_count),
      omega_max_rad_s_(vehicle.omega_max_rad_s),
      nominal_max_force_n_(vehicle.arm_count),
      inverse_(AllocationPseudoinverse(vehicle, mode)) {
  for (int i = 0; i < rotor_count_; ++i) {
    const double c_t = vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2;
    thrust_coeff_n_s2_rad2_[static_cast<size_t>(i)] = c_t;
    nominal_max_force_n_(i) = c_t * omega_max_rad_s_ * omega_max_rad_s_;
  }
}

bool WrenchAllocator::AddAxis(int axis, double wrench_change, const ArmForces<double>& max_force_n,
                              ArmForces<double>* force_n) const {
  ArmForces<double>& f = *force_n;
  double scale = 1.0;
  for (int i = 0; i < rotor_count_; ++i) {
    const double change = inverse_(i, axis) * wrench_change;
    if (f(i) + change > max_force_n(i)) scale = std::min(scale, std::max(0.0, (max_force_n(i) - f(i)) / change));
    if (f(i) + change < 0.0) scale = std::min(scale, std::max(0.0, -f(i) / change));
  }
  f += (scale * wrench_change) * inverse_.col(axis);
  return scale < 1.0;
}

MultiArmRotorCommand WrenchAllocator::Allocate(const ArmForces<double>& base_force_n,
                                               const Eigen::Vector3d& wrench_change_n,
                                               const RotorEfficiencies& efficiency) const {
  ArmForces<double> max_force_n(rotor_count_);
  for (int i = 0; i < rotor_count_; ++i) max_force_n(i) = nominal_max_force_n_(i) * efficiency[static_cast<size_t>(i)];
  ArmForces<double> force_n = base_force_n;
  bool saturated = false;
  for (int axis : {kWrenchTorque, kWrenchFz, kWrenchFx}) {
    saturated |= AddAxis(axis, wrench_change_n(axis), max_force_n, &force_n);
  }
  MultiArmRotorCommand command;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double clamped_n = std::clamp(force_n(i), 0.0, max_force_n(i));
    saturated |= clamped_n != force_n(i);
    command.force_n[rotor] = clamped_n;
    command.omega_cmd_rad_s[rotor] =
        RotorSpeedForThrust(thrust_coeff_n_s2_rad2_[rotor], omega_max_rad_s_, clamped_n, efficiency[rotor]);
  }
  command.saturated = saturated;
  return command;
}

}  // namespace birotor

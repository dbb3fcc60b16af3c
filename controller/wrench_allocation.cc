#include "controller/wrench_allocation.h"

#include <Eigen/Dense>
#include <Eigen/LU>
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
      inverse_(AllocationPseudoinverse(vehicle, mode)),
      allocation_(WrenchAllocation(vehicle)),
      first_controlled_row_(mode == MultiArmControlMode::kFullyActuated ? kWrenchFx : kWrenchFz),
      spare_rotors_(std::max(0, vehicle.arm_count - (kWrenchSize - first_controlled_row_))) {
  for (int i = 0; i < rotor_count_; ++i) {
    const double c_t = vehicle.arms[static_cast<size_t>(i)].thrust_coeff_n_s2_rad2;
    thrust_coeff_n_s2_rad2_[static_cast<size_t>(i)] = c_t;
    nominal_max_force_n_(i) = c_t * omega_max_rad_s_ * omega_max_rad_s_;
  }
}

const WrenchAllocator::Pseudoinverse& WrenchAllocator::InverseFor(const ArmForces<double>& max_force_n,
                                                                  Pseudoinverse* weighted) const {
  if (spare_rotors_ == 0) return inverse_;
  bool nominal = true;
  for (int i = 0; i < rotor_count_; ++i) nominal = nominal && max_force_n(i) == nominal_max_force_n_(i);
  if (nominal) return inverse_;
  // P_C = C W_r^T (W_r C W_r^T)^-1, C = diag(e_i c_T,i omega_max^2): the
  // least sum of f_i^2 / C_i, so a weak rotor takes a share in proportion to
  // what it still makes (a dead one none).
  const int rows = kWrenchSize - first_controlled_row_;
  const auto controlled = allocation_.bottomRows(rows);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxArms, kWrenchSize> weighted_transpose =
      max_force_n.asDiagonal() * controlled.transpose();
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kWrenchSize, kWrenchSize> gram =
      controlled * weighted_transpose;
  const Eigen::FullPivLU<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kWrenchSize, kWrenchSize>> lu(gram);
  if (!lu.isInvertible()) return inverse_;
  weighted->setZero(rotor_count_, kWrenchSize);
  weighted->rightCols(rows) = weighted_transpose * lu.inverse();
  return *weighted;
}

namespace {

// The largest s in [0, 1] with 0 <= f_i + s change_i <= max_i on every
// rotor, and the rotor that sets it (-1 when s = 1).
double StepWithinBounds(const ArmForces<double>& f, const ArmForces<double>& change, const ArmForces<double>& max_n,
                        int* limiting) {
  double scale = 1.0;
  *limiting = -1;
  for (int i = 0; i < f.size(); ++i) {
    double fits = 1.0;
    if (f(i) + change(i) > max_n(i)) fits = std::max(0.0, (max_n(i) - f(i)) / change(i));
    if (f(i) + change(i) < 0.0) fits = std::max(0.0, -f(i) / change(i));
    if (fits < scale) {
      scale = fits;
      *limiting = i;
    }
  }
  return scale;
}

}  // namespace

double WrenchAllocator::AddAxis(const Pseudoinverse& inverse, int axis, double wrench_change,
                                const ArmForces<double>& max_force_n, ArmForces<double>* force_n, int* limiting) const {
  const ArmForces<double> change = inverse.col(axis) * wrench_change;
  const double scale = StepWithinBounds(*force_n, change, max_force_n, limiting);
  *force_n += (scale * wrench_change) * inverse.col(axis);
  return scale;
}

double WrenchAllocator::RedistributeAxis(int stage, double wrench_change, int first_held,
                                         const ArmForces<double>& max_force_n, ArmForces<double>* force_n) const {
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kWrenchSize, kMaxArms>;
  using Gram = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kWrenchSize, kWrenchSize>;
  const int rows = stage + 1;
  // W_RF (the rows of the axes so far) and W_RF C on the free rotors: a
  // held rotor's column of the second is zero, so it keeps its thrust.
  Rows free_rows(rows, rotor_count_);
  for (int r = 0; r < rows; ++r) free_rows.row(r) = allocation_.row(kAxisOrder[r]);
  Rows weighted = free_rows * max_force_n.asDiagonal();
  weighted.col(first_held).setZero();
  double remaining = wrench_change;
  for (int round = 0; round < rotor_count_ && remaining != 0.0; ++round) {
    const Gram gram = free_rows * weighted.transpose();
    const Eigen::FullPivLU<Gram> lu(gram);
    if (lu.rank() < rows) break;  // the free rotors cannot move this axis alone
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kWrenchSize, 1> unit = Eigen::VectorXd::Zero(rows);
    unit(stage) = remaining;
    const ArmForces<double> change = weighted.transpose() * lu.solve(unit);
    int limiting = -1;
    const double scale = StepWithinBounds(*force_n, change, max_force_n, &limiting);
    *force_n += scale * change;
    remaining *= 1.0 - scale;
    if (limiting < 0) break;
    weighted.col(limiting).setZero();
  }
  return wrench_change - remaining;
}

double WrenchAllocator::BaseFraction(const Pseudoinverse& inverse, const ArmForces<double>& base_force_n,
                                     double torque_change_n_m, const ArmForces<double>& max_force_n) const {
  double level = 1.0;  // lambda_0 = min_i f_max,i / b_i: the base's own fraction within the bounds
  for (int i = 0; i < rotor_count_; ++i) {
    if (base_force_n(i) > max_force_n(i)) level = std::min(level, max_force_n(i) / base_force_n(i));
  }
  if (level == 1.0) return level;  // a base within the bounds is kept whole
  // Attitude first: the largest torque fraction s in [0, 1] for which some
  // lambda in [0, lambda_0] keeps 0 <= lambda b_i + s t_i <= f_max,i on
  // every rotor (t_i = P(i, tau) dtau), then the largest such lambda. For a
  // given s, lambda lies in [low(s), high(s)] (rotors with b_i > 0; one
  // with b_i = 0 bounds s alone); low - high rises with s, so s is found by
  // bisection (40 halvings: 1e-12).
  const auto interval = [&](double s, double* low, double* high) {
    *low = 0.0;
    *high = level;
    bool feasible = true;
    for (int i = 0; i < rotor_count_; ++i) {
      const double torque_n = s * inverse(i, kWrenchTorque) * torque_change_n_m;
      const double b = base_force_n(i);
      if (b > 0.0) {
        *low = std::max(*low, -torque_n / b);
        *high = std::min(*high, (max_force_n(i) - torque_n) / b);
      } else {
        feasible = feasible && torque_n >= 0.0 && torque_n <= max_force_n(i);
      }
    }
    return feasible && *low <= *high;
  };
  double low = 0.0;
  double high = level;
  if (interval(1.0, &low, &high)) return high;
  double fits = 0.0;
  double fails = 1.0;
  for (int k = 0; k < 40; ++k) {
    const double s = 0.5 * (fits + fails);
    (interval(s, &low, &high) ? fits : fails) = s;
  }
  interval(fits, &low, &high);
  return std::clamp(high, 0.0, level);
}

MultiArmRotorCommand WrenchAllocator::Allocate(const ArmForces<double>& base_force_n,
                                               const Eigen::Vector3d& wrench_change_n,
                                               const RotorEfficiencies& efficiency) const {
  ArmForces<double> max_force_n(rotor_count_);
  for (int i = 0; i < rotor_count_; ++i) max_force_n(i) = nominal_max_force_n_(i) * efficiency[static_cast<size_t>(i)];
  ArmForces<double> force_n = base_force_n;
  Eigen::Vector3d change_n = wrench_change_n;
  bool saturated = false;
  Pseudoinverse weighted;
  const Pseudoinverse& inverse = InverseFor(max_force_n, &weighted);
  const double lambda = BaseFraction(inverse, base_force_n, wrench_change_n(kWrenchTorque), max_force_n);
  if (lambda < 1.0) {
    // W f_base = W (lambda f_base) + (1 - lambda) W f_base: the same wrench asked for.
    change_n += (1.0 - lambda) * (allocation_ * base_force_n);
    force_n *= lambda;
    saturated = true;
  }
  // W f_base + dw: what every axis asks for once one was redistributed.
  const Eigen::Vector3d wanted_n =
      redistribute_ ? Eigen::Vector3d(allocation_ * base_force_n + wrench_change_n) : Eigen::Vector3d::Zero();
  bool redistributed = false;
  for (int stage = 0; stage < kWrenchSize; ++stage) {
    const int axis = kAxisOrder[stage];
    if (axis < first_controlled_row_) continue;
    const double wanted_change = redistributed ? wanted_n(axis) - allocation_.row(axis).dot(force_n) : change_n(axis);
    int limiting = -1;
    const double scale = AddAxis(inverse, axis, wanted_change, max_force_n, &force_n, &limiting);
    saturated |= scale < 1.0;
    // F_x is the one that gives way: it is not re-solved (a lateral step
    // asks more of it than the rotors make, and it would cost tilt).
    if (scale < 1.0 && redistribute_ && limiting >= 0 && axis != kWrenchFx) {
      redistributed |= RedistributeAxis(stage, (1.0 - scale) * wanted_change, limiting, max_force_n, &force_n) != 0.0;
    }
  }
  MultiArmRotorCommand command;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double clamped_n = std::clamp(force_n(i), 0.0, max_force_n(i));
    saturated |= clamped_n != force_n(i);
    command.force_n[rotor] = clamped_n;
    // A rotor flown as making nothing (e_i = 0: a spare rotor retired) is not driven.
    command.omega_cmd_rad_s[rotor] =
        efficiency[rotor] > 0.0
            ? RotorSpeedForThrust(thrust_coeff_n_s2_rad2_[rotor], omega_max_rad_s_, clamped_n, efficiency[rotor])
            : 0.0;
  }
  command.saturated = saturated;
  return command;
}

}  // namespace birotor

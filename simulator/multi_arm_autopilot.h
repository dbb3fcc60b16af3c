// The simulator's autopilot for any VehicleDescription: the cascade of
// controller/position_attitude_law.h (same gains, same stages) on the TRUE
// rigid-body state, turned into thrusts through the description's wrench
// allocation and into rotor speeds through the NOMINAL map omega = sqrt(f /
// c_T,i). It knows nothing of s_i or eta_i. docs/multi-arm-model.md, "Simulator".
#pragma once

#include <Eigen/Core>
#include <array>

#include "controller/controller_params.h"
#include "controller/reference_point.h"
#include "model/multi_arm_linearization.h"
#include "model/multi_arm_plant.h"
#include "model/vehicle_description.h"

namespace birotor {

// How the vehicle makes a lateral force.
enum class MultiArmControlMode {
  // N = 2, or N >= 3 without a usable F_x axis: tilt towards a_des (the
  // birotor way), thrusts from the F_z and torque rows.
  kTiltToMove,
  // N >= 3 and the allocation's singular-value ratio on all three axes at
  // least kMinAllocationSingularRatio: hold phi = 0 and make F_x directly.
  kFullyActuated,
};

// The rotor speed commands of one control period, the thrusts they are meant
// to make [N], and whether the allocation had to give something up.
struct MultiArmRotorCommand {
  std::array<double, kMaxArms> omega_cmd_rad_s{};  // [rad/s]
  std::array<double, kMaxArms> force_n{};          // [N]
  bool saturated = false;                          // an axis scaled down or a thrust clamped
};

class MultiArmAutopilot {
 public:
  // gains: ControllerParams (acceleration gains; its defaults are the
  // birotor's); they are scaled by the description's total mass m + sum m_p,i
  // and rigid pitch inertia J + sum m_p,i L_i^2 into forces and torques.
  // hover: SolveMultiArmHover(vehicle), the thrusts' feed-forward.
  MultiArmAutopilot(const VehicleDescription& vehicle, const ControllerParams& gains, const MultiArmHover& hover);

  // One control period (1 / rate_hz) on the plant state:
  //   a_des = PositionLoopAcceleration (world),
  //   kTiltToMove:    phi_des = TiltForAcceleration, F_z = m (g + a_z) / cos(phi), F_x = 0
  //   kFullyActuated: phi_des = 0, [F_x; F_z] = R(phi)^T m (a_des + g e_z)   (body frame)
  //   torque = J_eff TiltLoopAcceleration(phi_des)
  //   f = f_hover + P (w - [0, m g, 0])
  // with P the allocation's pseudo-inverse W^T (W W^T)^-1 on the controlled
  // rows (unweighted: least sum of squared thrust changes). Saturation
  // priority: the torque increment first, then F_z, then F_x, each added at
  // the largest fraction in [0, 1] that keeps every thrust in [0, f_max,i]
  // (f_max,i = c_T,i omega_max^2) given those before; a hover thrust already
  // outside is clamped. The integrators hold in the period after one that
  // saturated (anti-windup).
  MultiArmRotorCommand Update(const MultiArmPlantState& state, const ReferencePoint& reference);

  MultiArmControlMode mode() const { return mode_; }

 private:
  using Pseudoinverse = Eigen::Matrix<double, Eigen::Dynamic, kWrenchSize, 0, kMaxArms, kWrenchSize>;

  // f += s P(:, axis) dw(axis), s in [0, 1] the largest that keeps f in bounds;
  // returns true when s < 1.
  bool AddAxis(int axis, double wrench_change, ArmForces<double>* force_n) const;

  VehicleDescription vehicle_;
  ControllerParams gains_;
  double dt_s_;
  MultiArmControlMode mode_;
  double total_mass_kg_;        // m + sum m_p,i [kg]
  double pitch_inertia_kg_m2_;  // J + sum m_p,i L_i^2 [kg m^2]
  ArmForces<double> hover_force_n_;
  ArmForces<double> max_force_n_;     // c_T,i omega_max^2 [N]
  Pseudoinverse allocation_inverse_;  // N x 3 (kTiltToMove: the F_x column zero)
  Eigen::Vector2d position_integral_m_s_ = Eigen::Vector2d::Zero();
  double tilt_integral_rad_s_ = 0.0;
  bool saturated_ = false;  // the previous period saturated
};

}  // namespace birotor

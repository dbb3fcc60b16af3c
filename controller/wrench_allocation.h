// From a body wrench [F_x, F_z, tau] to the thrust and speed of each rotor of
// any VehicleDescription: the pseudo-inverse of the description's allocation
// on the controlled rows, a saturation priority (torque, then F_z, then F_x),
// and per-rotor efficiencies e_i that set each rotor's bound and speed map.
// Shared by the simulator's autopilot and the product's MultiArmController.
// Fixed size, no allocation. docs/controller.md, "Vehicles with N rotors".
#pragma once

#include <Eigen/Core>
#include <array>

#include "model/multi_arm_dynamics.h"
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

// kFullyActuated when ControlledAxesMargin has all three rows with a ratio
// >= kMinAllocationSingularRatio and N >= 3; kTiltToMove otherwise.
MultiArmControlMode MultiArmControlModeFor(const VehicleDescription& vehicle);

// The rotor speed commands of one control period, the thrusts they are meant
// to make [N], and whether the allocation had to give something up.
struct MultiArmRotorCommand {
  std::array<double, kMaxArms> omega_cmd_rad_s{};  // [rad/s]
  std::array<double, kMaxArms> force_n{};          // [N]
  bool saturated = false;                          // an axis scaled down or a thrust clamped
};

// e_i: the thrust rotor i really makes per nominal c_T,i omega_i^2 [1]
// (1 = nominal, 0.6 after a 40 % loss). Unused entries (i >= N) are ignored.
using RotorEfficiencies = std::array<double, kMaxArms>;
inline RotorEfficiencies NominalEfficiencies() {
  RotorEfficiencies efficiency;
  efficiency.fill(1.0);
  return efficiency;
}

class WrenchAllocator {
 public:
  // P = W_r^T (W_r W_r^T)^-1 on the controlled rows of W = WrenchAllocation
  // (kFullyActuated: all three; kTiltToMove: F_z and torque, the F_x column
  // zero), once, here: unweighted, the least sum of squared thrust changes.
  // With spare rotors (N above the controlled rows) and a rotor below its
  // nominal efficiency, Allocate weighs each rotor's share by what it still
  // makes instead (InverseFor).
  WrenchAllocator(const VehicleDescription& vehicle, MultiArmControlMode mode);

  // f = f_base + P dw, with the saturation priority: the torque increment
  // first, then F_z, then F_x, each added at the largest fraction s in [0, 1]
  // that keeps every thrust in [0, f_max,i] given those before, f_max,i =
  // e_i c_T,i omega_max^2. A base above some bound (a rotor too weak for
  // its hover thrust: the infeasible hover, or a transient low estimate) is
  // first scaled to
  // lambda f_base (BaseFraction: the level descent's thrusts, lowered
  // further so the torque increment fits, attitude first as the birotor's
  // AllocateAttitudeFirst), and the wrench it loses, (1 - lambda) W f_base,
  // is added to dw (F_z and F_x then take back what fits); a base within
  // the bounds is kept whole, and a thrust still outside is clamped at the
  // end. Without the lowering, the weak rotor sat at its bound with no room
  // for the torque while the others made their hover thrusts: the trirotor
  // losing 80 % on rotor 1 tilted 1.07 rad before and during the descent
  // (0.11 rad with it, docs/controller.md). Speeds omega_i = sqrt(f_i / (e_i c_T,i)) clipped to [0, omega_max].
  // Why this order: the torque keeps the attitude (losing it loses every
  // axis), F_z keeps the altitude, F_x only moves sideways. saturated: some
  // s < 1 or a clamp. With RedistributeAtBounds, the torque or F_z stopped
  // short is finished on the other rotors (RedistributeAxis), and every axis
  // after it then asks for what the wrench still lacks, W f against
  // W f_base + dw.
  static constexpr int kAxisOrder[kWrenchSize] = {kWrenchTorque, kWrenchFz, kWrenchFx};
  MultiArmRotorCommand Allocate(const ArmForces<double>& base_force_n, const Eigen::Vector3d& wrench_change_n,
                                const RotorEfficiencies& efficiency) const;

  // Fully actuated only (off by default: the simulator's autopilot keeps
  // the fixed directions): when a rotor's bound stops the torque's or
  // F_z's increment short (s < 1), the rest of it is re-solved on the other
  // rotors, keeping the axes before it in the priority order as they are
  // (RedistributeAxis); F_x, the axis that gives way, is not. A trirotor hovering tilted with its weak rotor at
  // its bound then still makes the torque on the other two, giving up F_x
  // instead: along the fixed direction the torque needed the weak rotor
  // too, so none was made and the tilt ran away (docs/controller.md).
  void RedistributeAtBounds(bool on) { redistribute_ = on && mode_ == MultiArmControlMode::kFullyActuated; }
  bool redistributes() const { return redistribute_; }

  MultiArmControlMode mode() const { return mode_; }
  int rotor_count() const { return rotor_count_; }
  // W: thrusts to the body wrench [F_x, F_z, tau] [1, 1, m].
  const AllocationMatrix& allocation() const { return allocation_; }
  // P (N x 3; column kWrenchFx zero in kTiltToMove) [1/N, 1/N, 1/m].
  const Eigen::Matrix<double, Eigen::Dynamic, kWrenchSize, 0, kMaxArms, kWrenchSize>& inverse() const {
    return inverse_;
  }

 private:
  using Pseudoinverse = Eigen::Matrix<double, Eigen::Dynamic, kWrenchSize, 0, kMaxArms, kWrenchSize>;

  // 1 when the base fits (kept whole); else lambda in [0, lambda_0],
  // lambda_0 = min_i f_max,i / f_base,i, with room for the largest fraction
  // of the torque increment P(:, tau) dtau (the most thrust among those).
  double BaseFraction(const Pseudoinverse& inverse, const ArmForces<double>& base_force_n, double torque_change_n_m,
                      const ArmForces<double>& max_force_n) const;
  // f += s P(:, axis) dw(axis), s in [0, 1] the largest that keeps f in
  // [0, max_force_n]; returns s (1: all of it), and in *limiting the rotor
  // whose bound set s (-1 when s = 1).
  double AddAxis(const Pseudoinverse& inverse, int axis, double wrench_change, const ArmForces<double>& max_force_n,
                 ArmForces<double>* force_n, int* limiting) const;
  // The rest of axis kAxisOrder[stage]'s increment, wrench_change [N or N m],
  // on the rotors not held at a bound: d = C W_RF^T (W_RF C W_RF^T)^-1 e,
  // W_RF the allocation's rows of the axes kAxisOrder[0..stage] on the free
  // rotors, e the unit change of this axis (the axes before it unchanged),
  // C = diag(max_force_n); f += s wrench_change d with the largest s in
  // [0, 1] within the bounds, the rotor that stops it held, repeated while
  // the free rotors are at least the rows. first_held: the rotor that
  // stopped the fixed direction. Returns the part of wrench_change made.
  double RedistributeAxis(int stage, double wrench_change, int first_held, const ArmForces<double>& max_force_n,
                          ArmForces<double>* force_n) const;
  // P, or with spare rotors and some e_i != 1 the capacity-weighted
  // inverse (in *weighted): C W_r^T (W_r C W_r^T)^-1, C = diag(max_force_n).
  const Pseudoinverse& InverseFor(const ArmForces<double>& max_force_n, Pseudoinverse* weighted) const;

  MultiArmControlMode mode_;
  int rotor_count_;
  double omega_max_rad_s_;
  std::array<double, kMaxArms> thrust_coeff_n_s2_rad2_{};  // c_T,i
  ArmForces<double> nominal_max_force_n_;                  // c_T,i omega_max^2 [N]
  Pseudoinverse inverse_;
  AllocationMatrix allocation_;  // W: thrusts to the body wrench [F_x, F_z, tau]
  int first_controlled_row_;     // kWrenchFx (fully actuated) or kWrenchFz
  int spare_rotors_;             // N minus the controlled rows (0: P is W_r's inverse)
  bool redistribute_ = false;    // RedistributeAtBounds
};

}  // namespace birotor

// The hovers a vehicle's rotors can hold: every thrust vector with the
// controlled wrench of the exact hover f_hover (SolveMultiArmHover),
//   f = f_hover + Z y,   W_r Z = 0,
// W_r the allocation's controlled rows (WrenchAllocator: all three when fully
// actuated, F_z and torque when it tilts to move) and Z an orthonormal basis
// of their null space, one column per rotor the vehicle has to spare (none on
// the birotor and the trirotor, one on the quadrotor). On a vehicle with
// spare rotors a weak rotor need not make its least-norm hover thrust: the
// others can take its share (docs/controller.md, "Spare rotors").
// Fixed size (at most kMaxArms rotors), no allocation.
#pragma once

#include <Eigen/Core>

#include "controller/wrench_allocation.h"
#include "model/multi_arm_dynamics.h"
#include "model/vehicle_description.h"

namespace birotor {

class HoverSpace {
 public:
  // No rotor to spare: Nearest answers f_hover or nothing.
  HoverSpace() = default;
  // hover_force_n: f_hover,i [N] (SolveMultiArmHover's force_n), N entries.
  HoverSpace(const VehicleDescription& vehicle, MultiArmControlMode mode, const ArmForces<double>& hover_force_n);

  // N minus the controlled rows: the dimension of y [1].
  int spare_rotors() const { return spare_; }
  bool redundant() const { return spare_ > 0; }
  // A fully actuated vehicle may hover tilted (NearestTiltedWithinShares;
  // the trirotor too, without a rotor to spare: its hover thrusts at tilt
  // phi are the single point cos(phi) f_hover + sin(phi) f_lateral).
  bool tilts() const { return lateral_force_n_.size() == rotor_count_ && rotor_count_ > 0; }
  // The hover may move off f_hover: spare rotors, or a tilt.
  bool rebalances() const { return redundant() || tilts(); }

  // The hover nearest f_hover (least sum of squared thrust changes) with
  // low_i <= f_i <= high_i on every rotor; false when no hover lies in the
  // box (hover may then be null). f_hover itself, bit for bit, whenever it
  // lies in the box. Exact: the nearest point of the box's trace on the
  // hover set is the least-norm point of the affine set of its active
  // bounds, so every set of at most spare_rotors() independent bounds is
  // tried and the nearest candidate inside the box kept (at most 794 sets
  // of at most 4 bounds for six rotors; 9 for the quadrotor).
  bool Nearest(const ArmForces<double>& low_n, const ArmForces<double>& high_n, ArmForces<double>* hover_n) const;

  // Nearest with the box [min_share, max_share] x e_i c_T,i omega_max^2, e_i =
  // efficiency[i] (what rotor i makes now per nominal thrust) [1].
  bool NearestWithinShares(const double* efficiency, double min_share, double max_share,
                           ArmForces<double>* hover_n) const;

  // A fully actuated vehicle may also hover tilted: at tilt phi its body
  // force is R(phi)^T [0, m g] = m g [sin phi, cos phi] (body frame, torque
  // 0), made by f = cos(phi) f_hover + sin(phi) f_lateral + Z y, f_lateral =
  // P [m g, 0, 0] (P: the controlled rows' pseudo-inverse). The least |phi|
  // on a grid of kTiltStepRad up to max_tilt_rad (each sign, the positive
  // first) with a hover within the shares, and that hover (nearest its own
  // cos f_hover + sin f_lateral); false when none (or the vehicle tilts to
  // move: no lateral force of its own). A rotor that makes nothing leaves a
  // lateral force the others can only balance by tilting the body (the
  // quadrotor with rotor 3 dead: docs/controller.md, "Spare rotors").
  // Without a spare rotor (the trirotor), when the grid finds none, the
  // least |phi| exactly (LeastTiltWithoutSpare): a dead rotor's box has no
  // width and only its one tilt holds it at 0 N (the trirotor with rotor 2
  // dead: 0.40 rad). The grid comes first: its first tilt lies up to a step
  // inside the box, a margin the weak rotor's torque uses (rotor 3 at 12 %,
  // exact tilt: altitude deviation 0.078 -> 0.086 m, docs/controller.md).
  // from_tilt_rad: the search starts at this |phi| (a tilt a wider box holds
  // no hover below holds none in this box either) [rad].
  bool NearestTiltedWithinShares(const double* efficiency, double min_share, double max_share, double max_tilt_rad,
                                 ArmForces<double>* hover_n, double* tilt_rad, double from_tilt_rad = 0.0) const;
  static constexpr double kTiltStepRad = 0.005;

  // Whether a level hover within the shares [0, max_share] x e_i c_T,i
  // omega_max^2 can also make a pure pitch torque of +torque_n_m and of
  // -torque_n_m [N m] (f = f_hover +- torque P [0, 0, 1] + Z y in the box):
  // then the body can tilt either way from there and move sideways as a
  // birotor does. The quadrotor with rotor 1 dead: its level hovers pin rotor
  // 2 at 0 and the remaining torque is one-sided (false); with rotor 3 dead
  // rotors 1 and 2 pitch both ways (true).
  bool LevelPitchesBothWays(const double* efficiency, double max_share, double torque_n_m) const;

  const ArmForces<double>& hover_force_n() const { return hover_force_n_; }

 private:
  using NullBasis = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxArms, kMaxArms>;

  // Nearest about the particular hover `centre_n` (f_hover, or a tilted one).
  bool NearestTo(const ArmForces<double>& centre_n, const ArmForces<double>& low_n, const ArmForces<double>& high_n,
                 ArmForces<double>* hover_n) const;
  // NearestTiltedWithinShares without a spare rotor: the hover at phi is
  // the point cos(phi) f_hover + sin(phi) f_lateral, and the least |phi| in
  // [from_tilt_rad, max_tilt_rad] whose point lies in the box is one of
  // from_tilt_rad's two signs or a tilt where a rotor meets a bound (each
  // rotor's thrust r_i cos(phi - delta_i) meets a bound at two tilts at
  // most): those are tried, the positive tilt first on a tie.
  bool LeastTiltWithoutSpare(const ArmForces<double>& low_n, const ArmForces<double>& high_n, double max_tilt_rad,
                             double from_tilt_rad, ArmForces<double>* hover_n, double* tilt_rad) const;
  // The box [min_share, max_share] x e_i c_T,i omega_max^2.
  void ShareBox(const double* efficiency, double min_share, double max_share, ArmForces<double>* low_n,
                ArmForces<double>* high_n) const;

  int rotor_count_ = 0;
  int spare_ = 0;
  ArmForces<double> hover_force_n_;
  ArmForces<double> max_force_n_;      // c_T,i omega_max^2 [N]
  ArmForces<double> lateral_force_n_;  // f_lateral = P [m g, 0, 0] (fully actuated; else empty) [N]
  ArmForces<double> torque_force_n_;   // P [0, 0, 1]: thrusts making 1 N m of pitch torque alone [N per N m]
  NullBasis null_basis_;               // Z, N x spare_, orthonormal columns
};

}  // namespace birotor

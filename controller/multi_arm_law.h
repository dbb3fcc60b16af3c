// The cascade of controller/position_attitude_law.h for any VehicleDescription:
// from a body state and a position reference to the wrench [F_x, F_z, tau],
// then through WrenchAllocator to rotor thrusts and speeds. The simulator's
// autopilot runs it on the true state with nominal efficiencies; the
// product's MultiArmController on the measured state with estimated ones.
// Fixed size, no allocation. docs/controller.md, "Vehicles with N rotors".
#pragma once

#include <Eigen/Core>
#include <algorithm>

#include "controller/controller_params.h"
#include "controller/hover_space.h"
#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"
#include "controller/wrench_allocation.h"
#include "model/multi_arm_linearization.h"
#include "model/vehicle_description.h"

namespace birotor {

class MultiArmLaw {
 public:
  // gains: ControllerParams (acceleration gains; its defaults are the
  // birotor's); they are scaled by the description's total mass m + sum m_p,i
  // and rigid pitch inertia J + sum m_p,i L_i^2 into forces and torques.
  // hover: SolveMultiArmHover(vehicle), the thrusts' feed-forward. spare:
  // the spare_* shares and feasibility_margin (spare rotors only).
  MultiArmLaw(const VehicleDescription& vehicle, const ControllerParams& gains, const MultiArmHover& hover,
              const EfficiencyParams& spare = EfficiencyParams());

  // One control period (1 / rate_hz):
  //   a_des = PositionLoopAcceleration (world),
  //   kTiltToMove:    phi_des = TiltForAcceleration, F_z = m (g + a_z) / cos(phi), F_x = 0
  //   kFullyActuated: phi_des = phi_base, [F_x; F_z] = R(phi)^T m (a_des + g e_z)   (body frame);
  //                   with pins_rotor(): phi_des = phi_base + atan2(-a_x, g + a_z), no F_x
  //   torque = J_eff TiltLoopAcceleration(phi_des)
  //   f = f_base + P (w - m g [sin phi_base, cos phi_base, 0])   (WrenchAllocator::Allocate)
  // f_base = f_hover, what the vehicle needs whatever the efficiencies; with
  // spare rotors the nearest hover within the spare_* shares of what each
  // rotor makes (HoverBase), level (phi_base = 0) or, when none is, tilted. efficiency (each e_i > 0) sets the bounds
  // and the speed map. The integrators hold in the period after one that saturated (anti-windup).
  MultiArmRotorCommand Update(const BodyState& body, const ReferencePoint& reference,
                              const RotorEfficiencies& efficiency);

  // Clears both integrators and the anti-windup memory.
  void Reset();
  // Clears the position integrator only (a descent's entry: what it learnt
  // on the setpoint would tilt the descent).
  void ResetPositionIntegral() { position_integral_m_s_.setZero(); }
  // The tilt bound from now on, min(max_tilt_rad, gains' max_tilt_rad) [rad]
  // (the birotor's PositionAttitudeLaw::LimitTilt). Tilt to move: phi_des
  // within it. Fully actuated (phi_des = 0): while it is below the gains'
  // bound, the lateral acceleration within g tan(bound), what tilting to it
  // would make (0 while levelling).
  void LimitTilt(double max_tilt_rad) { tilt_limit_rad_ = std::min(max_tilt_rad, gains_.max_tilt_rad); }

  // WrenchAllocator::RedistributeAtBounds (the product's controller; the
  // simulator's autopilot keeps the fixed directions).
  void RedistributeAtBounds(bool on) { allocator_.RedistributeAtBounds(on); }

  MultiArmControlMode mode() const { return allocator_.mode(); }
  const WrenchAllocator& allocator() const { return allocator_; }
  // The world acceleration the outer loop asked for in the last period [m/s^2].
  const Eigen::Vector2d& accel_des_m_s2() const { return accel_des_m_s2_; }
  // The tilt the allocation's hover is held at: 0 but on a fully actuated
  // vehicle with spare rotors and no level hover within the shares [rad].
  double base_tilt_rad() const { return base_tilt_rad_; }
  // The thrusts that hold that hover, HoverBase's answer in the last period [N].
  const ArmForces<double>& base_force_n() const { return base_is_hover_ ? hover_force_n_ : base_force_n_; }
  // Whether a level hover within [0, 1 / feasibility_margin] x e_i c_T,i
  // omega_max^2 can pitch the body either way (HoverSpace::
  // LevelPitchesBothWays, a pitch acceleration of kPitchProbeRadS2; true
  // without spare rotors): a planner free to fly any rotor down to 0 can
  // then hold it level and tilt to move. [rad/s^2]
  static constexpr double kPitchProbeRadS2 = 1.0;
  bool LevelPitchesBothWays(const RotorEfficiencies& efficiency) const;
  // Without a spare rotor, whether a fully actuated vehicle's base may be
  // a tilted hover when no level one is within [0, 1 / margin]
  // (LevelOrTiltedBase), with every rotor within spare_max_share of what it
  // makes (room above the weak rotor for the torque and F_x: with the weak
  // rotor at 1 / margin the cascade's tilt ran away, and mode mpc drifted
  // sideways, docs/controller.md). false (the default): level only.
  void HoldTiltedHoverWithoutSpare(bool hold) { tilted_without_spare_ = hold; }
  // Rotors beyond the controlled axes (HoverSpace::spare_rotors; 1 on the quadrotor).
  int spare_rotors() const { return hover_space_.spare_rotors(); }
  // In the last period the base held a rotor that makes nothing at 0 N
  // without a spare rotor (the trirotor with rotor 2 or 3 dead: 0.40 rad
  // off level): no F_x, the cascade moves by tilting about the base
  // (docs/controller.md, "A dead rotor without a spare").
  bool pins_rotor() const { return base_pins_rotor_; }
  // The hover may move off f_hover: spare rotors or a tilt (HoverSpace::rebalances).
  bool rebalances() const { return hover_space_.rebalances(); }

 private:
  // [F_x, F_z, tau] the cascade asks for (body frame [N, N, N m]), F_z
  // including the weight.
  Eigen::Vector3d Wrench(const BodyState& body, const ReferencePoint& reference, bool integrate);

  ControllerParams gains_;
  double dt_s_;
  double gravity_m_s2_;
  double total_mass_kg_;        // m + sum m_p,i [kg]
  double pitch_inertia_kg_m2_;  // J + sum m_p,i L_i^2 [kg m^2]
  // The thrusts the allocation starts from: f_hover, or with spare rotors
  // the hover nearest it within [spare_min_share, spare_max_share] x e_i
  // c_T,i omega_max^2, else the least-tilted one within them (HoverSpace::
  // NearestTiltedWithinShares, up to spare_hover_tilt_rad and the tilt
  // limit; its tilt in base_tilt_rad_; the lower share spare_tilted_min_share
  // first, then spare_min_share), else the same within
  // [spare_min_share, 1 / margin], else f_hover (no hover held: the
  // allocator scales it, the descent's).
  const ArmForces<double>& HoverBase(const RotorEfficiencies& efficiency);
  // Whether HoverBase's widest box, [spare_min_share, max(spare_max_share,
  // 1 / margin)], holds a hover, level or tilted up to max_tilt_rad. Every
  // box HoverBase tries lies within it, so without one there is none (the
  // descent: 82 nearest-hover solves instead of the four grids' 322 on the
  // quadrotor), and no box holds a tilted hover below the least tilt found
  // here (least_tilt_rad, 0 when a level hover fits: each grid starts
  // there). HoverBase's answer is unchanged, bit for bit.
  bool AnyHover(const RotorEfficiencies& efficiency, double max_tilt_rad, double* least_tilt_rad) const;
  // HoverBase without a spare rotor (HoldTiltedHoverWithoutSpare): f_hover
  // while it lies within [0, 1 / margin] x e_i c_T,i omega_max^2 (the
  // feasibility bound); else the least-tilted hover within
  // [spare_tilted_min_share, spare_max_share], else within
  // [spare_min_share, spare_max_share], up to spare_hover_tilt_rad and the
  // tilt limit (the trirotor with rotor 2 at 20 %: 0.11 rad); else f_hover
  // (the descent).
  const ArmForces<double>& LevelOrTiltedBase(const RotorEfficiencies& efficiency);
  // Some rotor makes nothing (e_i = 0: the controller retired it).
  bool AnyRotorOut(const RotorEfficiencies& efficiency) const;
  // With base_pins_rotor_: whether the command makes the F_z and torque
  // asked for, W (f - f_base) = dw on those rows within kMadeTolerance of the
  // weight (the allocator's re-solve finishes them on the other rotors,
  // though every increment meets the pinned rotor's bounds first: that is
  // no saturation, and the integrators keep running).
  bool MakesLiftAndTorque(const ArmForces<double>& base_n, const Eigen::Vector3d& wrench_change,
                          const MultiArmRotorCommand& command) const;
  static constexpr double kMadeTolerance = 1e-9;  // [1] of m g

  ArmForces<double> hover_force_n_;
  WrenchAllocator allocator_;
  HoverSpace hover_space_;
  double spare_min_share_;          // [1]
  double spare_max_share_;          // [1]
  double feasible_share_;           // 1 / feasibility_margin [1]
  double hover_tilt_limit_rad_;     // spare_hover_tilt_rad [rad]
  double tilted_min_share_;         // max(spare_tilted_min_share, spare_min_share) [1]
  double base_tilt_rad_ = 0.0;      // the tilt HoverBase's hover is held at (fully actuated: phi_des) [rad]
  ArmForces<double> base_force_n_;  // HoverBase's answer [N], unless it was f_hover
  bool base_is_hover_ = true;       // HoverBase answered f_hover
  // The base tilts to hold a rotor that makes nothing at 0 N without a spare
  // rotor: both its bounds bind, the allocation has no F_x, and the cascade
  // moves sideways by tilting about base_tilt_rad_ (Wrench).
  bool base_pins_rotor_ = false;
  bool tilted_without_spare_ = false;  // HoldTiltedHoverWithoutSpare
  double tilt_dwell_s_;                // infeasible_s: the cascade's level hover out of reach this long first [s]
  double level_out_of_reach_s_ = 0.0;  // how long LevelOrTiltedBase has found no level hover [s]
  Eigen::Vector2d position_integral_m_s_ = Eigen::Vector2d::Zero();  // int(e_p) [m s]
  double tilt_integral_rad_s_ = 0.0;                                 // int(e_phi) [rad s]
  double tilt_limit_rad_;                                            // LimitTilt [rad]
  Eigen::Vector2d accel_des_m_s2_ = Eigen::Vector2d::Zero();
  bool saturated_ = false;  // the previous period saturated
};

}  // namespace birotor

// The controller service's flight law: body state from POSE and the IMU
// (BodyStateObserver), the shared position/pitch law, an allocation that
// keeps attitude before altitude, and the rotor speeds from the nominal map
// or from each rotor's conditioned thrust efficiency (FORCE through
// EfficiencyConditioner). It flies the setpoint (SetpointInput).
// Supervises its inputs on the caller's clock (issue 23): stamps outside the
// clock windows, a second publisher on FORCE or POSE, implausible thrust
// scales and POSE outside the innovation gate are refused and counted
// (a flagged scale below the floor is flown as the floor, a consistent run
// of gated POSEs re-acquired: ForceFloorEvidence, PoseGate); a second
// publisher drops force feedback; FORCE stale, not VALID or refused lets the
// efficiency decay towards the nominal map; a lost POSE or a hover the
// rotors cannot make (HoverFeasibility, latched with its weak rotor; a
// latch from the sink is undone once the rotors show the margin) gives a
// level controlled descent with slewed commands, levelling first (and a
// flare near the ground, controller/rotor_allocation.h); a command is never
// non-finite or outside [0, omega_max]. No LCM, no allocation, no throw
// after construction.
#pragma once

#include <cstdint>
#include <memory>

#include "controller/body_state_observer.h"
#include "controller/controller_params.h"
#include "controller/efficiency_conditioner.h"
#include "controller/force_floor_evidence.h"
#include "controller/hover_feasibility.h"
#include "controller/input_admission.h"
#include "controller/motor_lag_lead.h"
#include "controller/mpc_controller.h"
#include "controller/pose_gate.h"
#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"
#include "controller/seq_stream_lock.h"
#include "controller/setpoint_input.h"
#include "samples/motor_command.h"
#include "samples/rotor_count.h"
#include "samples/samples.h"
#include "samples/setpoint.h"

namespace birotor {

struct ControllerHealth {
  ControllerInputCounters pose, imu, force;
  int64_t commands = 0;
  int64_t fallbacks = 0;            // entries into the fallback (efficiency decaying towards the nominal map)
  int64_t descents = 0;             // entries into the controlled descent (POSE lost or hover infeasible)
  int64_t saturated = 0;            // commands whose allocation was limited (or a speed clipped)
  int64_t numerical_guards = 0;     // non-finite law outputs replaced by the last good command
  int64_t force_unhealthy = 0;      // accepted FORCE samples without VALID
  int64_t force_at_floor = 0;       // FORCE scales below the plausibility floor flown as the floor (ForceFloorEvidence)
  int64_t conflicts = 0;            // entries into STATUS_INPUT_CONFLICT
  int64_t pose_gate_resets = 0;     // observer re-initialised after pose_gate_reset_s of gated POSE
  int64_t pose_reacquisitions = 0;  // observer moved onto a consistent run of gated POSEs (PoseGate)
  int64_t infeasible = 0;  // entries into the hover-infeasible descent (latched; one from the sink may be undone)
  int64_t infeasible_by_sink = 0;  // ... of them detected from the vehicle's sink (HoverFeasibility)
  int64_t infeasible_undone = 0;   // latches from the sink undone by the rotors' measure (HoverFeasibility)
  int64_t flares = 0;              // entries into that descent's flare near the ground
  bool fallback_active = false;
  bool descending = false;
  bool flaring = false;
  bool levelling = false;  // the infeasible descent's first phase: tilt target 0
  bool conflict = false;
  double efficiency[kBirotorRotors] = {1.0, 1.0};  // efficiency used by the rotor map in the newest period [1]
};

class VehicleController {
 public:
  explicit VehicleController(const ControllerConfig& config);

  // Inputs, in any order and at any rate, each arrived when the controller's
  // clock read now_us [us]; bad samples are counted and dropped. The clock
  // is the caller's; no input moves it.
  void OnPose(const PoseSample& sample, int64_t now_us);
  void OnImu(const ImuSample& sample, int64_t now_us);
  void OnForce(const ForceEstimate& estimate, int64_t now_us);
  // A setpoint (SetpointInput: checked, counted, followed, held, then hover here).
  void OnSetpoint(const Setpoint& setpoint, int64_t now_us) { setpoint_.Offer(setpoint, now_us); }

  // One control period at vehicle time now_us [us], tracking the setpoint
  // (before any: the first POSE). The command is finite and within
  // [0, omega_max] whatever the inputs.
  MotorCommand Update(int64_t now_us);

  // The reference flown in the newest control period.
  const ReferencePoint& reference() const { return reference_; }
  const SetpointInput& setpoint() const { return setpoint_; }
  bool has_pose() const { return has_pose_; }
  const BodyState& state() const { return observer_.state(); }
  const ControllerHealth& health() const { return health_; }
  const ControllerConfig& config() const { return config_; }
  // Mode mpc: solves, fallbacks, solve times, iterations (zeros in other modes).
  MpcStats MpcStatistics() const { return mpc_ ? mpc_->Stats() : MpcStats(); }

 private:
  // True when FORCE may be flown on at now_us (fresh, on time, VALID, no conflict).
  bool ForceUsable(int64_t now_us) const;
  // FORCE VALID or not VALID by MODEL_MISMATCH alone, on time: its flagged
  // rotors' relative changes may be flown (EfficiencyParams::mismatch_relative).
  bool ChangesUsable(int64_t now_us) const;
  // Age of an input at now_us [s]; +inf before its first sample or when its
  // stamp is ahead of the clock (negative age: stale).
  double AgeS(int64_t last_utime, int64_t now_us) const;
  // Hover feasibility for this period (force feedback; use_force: FORCE is
  // flown on now), latched once lost.
  bool UpdateFeasibility(double dt_s, bool use_force);
  // The descent's target and tilt bound for this period; counts entries.
  ReferencePoint DescentTarget(bool pose_lost, bool infeasible, int32_t* status);
  // Observer: propagate with the period's IMU mean, then fuse a pending POSE.
  void UpdateState(int64_t now_us, double dt_s, int32_t* status);
  // Rotor speeds from the law's forces: allocation within the rotors'
  // limits, the map with the efficiency in use, the motor-lag lead
  // (MotorLagLead) over the period dt_s.
  // slewed: each speed within degraded_omega_rate_rad_s2 x dt_s of the last.
  void Allocate(const RotorForces& forces, bool use_efficiency, bool slewed, double dt_s, MotorCommand* command,
                int32_t* status);
  // The efficiency rotor i is flown with: the conditioned one, or the latched
  // weak rotor's once hover is infeasible [1].
  double EfficiencyInUse(int rotor, bool use_efficiency) const;
  // What each rotor can make with the efficiency in use [N].
  void MaxForces(bool use_efficiency, double (&max_force_n)[kBirotorRotors]) const;
  // The hover-infeasible descent (with POSE) near the ground: replaces the
  // law's total and difference by the flare's (FlareForcesFor) and returns
  // true while it flares; Flare also counts the flares.
  bool Flare(bool infeasible_descent, RotorForces* forces);
  bool ApplyFlare(RotorForces* forces) const;

  ControllerConfig config_;
  BirotorParams model_;  // the birotor model's parameters of config_.vehicle (BirotorModelOf)
  PositionAttitudeLaw law_;
  BodyStateObserver observer_;
  EfficiencyConditioner efficiency_;
  HoverFeasibility feasibility_;
  PoseGate pose_gate_;
  ForceFloorEvidence floor_evidence_;
  ForceRecovery force_recovery_;   // FORCE's health and its healthy run (force_recovery_s)
  ForceRecovery change_recovery_;  // ... counting a mismatched FORCE healthy too
  SeqStreamLock force_lock_, pose_lock_;
  ControllerHealth health_;
  SetpointInput setpoint_;
  ReferencePoint reference_;
  double weight_n_;

  // POSE: the newest accepted sample not yet fused; the gate's run of refusals.
  bool has_pose_ = false;
  double ground_z_m_ = 0.0;  // the first POSE's z: the take-off level the flare lands on [m]

  // IMU: sums over the samples since the last control period.
  int imu_count_ = 0;
  double gyro_sum_rad_s_ = 0.0;
  double accel_sum_m_s2_[2] = {0.0, 0.0};
  double last_specific_force_m_s2_[2] = {0.0, 0.0};

  int64_t last_update_us_ = -1;
  bool saturated_ = false;           // the previous period's allocation was limited (anti-windup)
  bool difference_limited_ = false;  // ... and its pitch torque (f2 - f1) was
  Eigen::Vector2d last_accel_des_m_s2_ = Eigen::Vector2d::Zero();
  double last_good_omega_rad_s_[kBirotorRotors] = {0.0, 0.0};
  MotorLagLead motor_lead_[kBirotorRotors];  // each rotor's lead of its motor lag
  int32_t seq_ = 0;
  std::unique_ptr<MpcController> mpc_;  // mode mpc only
};

}  // namespace birotor

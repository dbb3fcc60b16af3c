// The product's flight controller for any VehicleDescription (N = 2 .. 6
// rotors): the body state from POSE and the IMU (BodyStateObserver, as
// birotor-controller), the N-arm cascade of controller/multi_arm_law.h with
// the gains of config/controller.yaml, fully actuated (phi_des = 0, F_x made
// directly) when the allocation allows it and tilt-to-move otherwise, and N
// rotor speed commands through the nominal map or each rotor's estimated
// efficiency (RotorEfficiencyEstimate, the content of force_estimate_n_t;
// a scale outside the plausible band refused, a flagged one below the floor
// flown as the floor, the reports low-passed as sink evidence:
// ForceFloorEvidence; the plausible ones conditioned before they are flown:
// EfficiencyConditioner; both as the birotor's).
// In mode mpc (ControllerConfig::model_predictive) the N-input MPC
// (controller/multi_arm_mpc.h) flies at the mpc: section's rate on the
// observer's state, the efficiencies in use and the reference extrapolated
// over its horizon, and the cascade's command is the per-period fallback.
// No LCM, no allocation, no throw, no log per call (alglib allocates inside
// the MPC's solver, docs/mpc.md). Degrades as VehicleController does: a
// hover the rotors cannot make (HoverFeasibility on the N rotors' bounds,
// force feedback, latched) or a POSE the caller calls lost gives the level
// controlled descent (DescentReference), levelling first when infeasible,
// the tilt within degraded_max_tilt_rad, the commands slewed by
// degraded_omega_rate_rad_s2, the integrators reset on entry. Its inputs'
// streams are not supervised here (stream locks, clock, gates: the N-rotor
// node). docs/controller.md, "Vehicles with N rotors".
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "controller/body_state_observer.h"
#include "controller/controller_params.h"
#include "controller/efficiency_conditioner.h"
#include "controller/force_floor_evidence.h"
#include "controller/hover_feasibility.h"
#include "controller/motor_lag_lead.h"
#include "controller/multi_arm_flare.h"
#include "controller/multi_arm_law.h"
#include "controller/multi_arm_mpc.h"
#include "controller/pose_gate.h"
#include "controller/reference_point.h"
#include "controller/rotor_efficiency_estimate.h"
#include "controller/wrench_allocation.h"
#include "model/multi_arm_linearization.h"
#include "model/vehicle_description.h"
#include "samples/samples.h"

namespace birotor {

// The controlled descent's state and counts (the ControllerHealth fields of
// the same names).
struct MultiArmDegradation {
  bool descending = false;         // the controlled descent (POSE lost or hover infeasible)
  bool levelling = false;          // the infeasible descent's first phase: tilt target 0
  bool hover_infeasible = false;   // HoverFeasibility latched (one from the sink may be undone)
  int64_t descents = 0;            // entries into the descent
  int64_t infeasible = 0;          // entries into the hover-infeasible descent
  int64_t infeasible_by_sink = 0;  // ... of them detected from the vehicle's sink
  int64_t infeasible_undone = 0;   // latches from the sink undone by the rotors' measure
  int weak_rotor = -1;             // the latched weak rotor (0-based); -1: none
  bool flaring = false;            // the infeasible descent's flare near the ground (this period)
  int64_t flares = 0;              // entries into it
};

class MultiArmController {
 public:
  // config: gains, observer, supervision (imu_timeout_s, force_timeout_s,
  // min/max_plausible_thrust_scale), efficiency (EfficiencyConditioner's
  // keys, HoverFeasibility's) and force_feedback of config/controller.yaml; its
  // vehicle field is not used (vehicle is). hover: SolveMultiArmHover(vehicle).
  MultiArmController(const VehicleDescription& vehicle, const ControllerConfig& config, const MultiArmHover& hover);

  // A POSE the caller admitted; verdict: the caller's POSE gate's
  // (PoseGate, the N-rotor node), kReset / kReacquired move the observer
  // onto it (MoveObserverOnto), kInside (the lock-step loop) fuses it.
  void OnPose(const PoseSample& sample, PoseGate::Verdict verdict = PoseGate::Verdict::kInside);
  void OnImu(const ImuSample& sample);
  // FORCE's report (RotorEfficiencyEstimate: rotor i is arm i) as it
  // arrived when the caller's clock read now_us [us]: every report once,
  // before the caller's own checks (as VehicleController::OnForce). Noted as
  // evidence for the sink detection (ForceFloorEvidence::Note: VALID, of the
  // rotor count, within the clock windows, newer than the last, below the
  // floor included) and returned with a rotor it flags as faulty with a
  // scale below min_plausible_thrust_scale for at_floor_samples reports in
  // a row set to the floor (counted in force_at_floor()): the estimate to
  // check and hand to OnEfficiency.
  RotorEfficiencyEstimate NoteReport(const RotorEfficiencyEstimate& reported, int64_t now_us);
  // The newest estimate (NoteReport's), flown only in force_feedback mode
  // (EfficiencyInUse). One of another rotor count or with a scale
  // non-finite or outside [min, max]_plausible_thrust_scale is refused, not
  // clamped (false; counted in refused_estimates()); a refused VALID one of
  // the rotor count keeps the last plausible estimate in force (its age
  // counts from the refused one's stamp), as the birotor's fallback holds
  // its efficiency through a refused FORCE. A plausible VALID one goes to
  // the EfficiencyConditioner.
  bool OnEfficiency(const RotorEfficiencyEstimate& estimate);
  // The supervisor's verdict on the estimate (the N-rotor node's force
  // recovery rule, ForceRecovery): false is the conditioner's fallback (the
  // efficiencies decay towards 1 over efficiency.decay_s) whatever the
  // estimate says. true (the default) leaves it to the estimate's own
  // checks (EstimateUsable), as the lock-step loop flies.
  void SetForceUsable(bool usable) { force_usable_ = usable; }
  // The same verdict with a mismatched estimate counted healthy
  // (MismatchedOnly): its flagged rotors' relative changes may be flown.
  void SetChangesUsable(bool usable) { changes_usable_ = usable; }

  // One control period (1 / rate_hz()) at now_us on the reference: the
  // observer predicted with the mean IMU of the period (stale beyond
  // imu_timeout_s: the commanded acceleration and the held pitch rate
  // instead) and corrected by the newest POSE, the hover feasibility
  // (UpdateFeasibility), then MultiArmLaw::Update on the reference or, when
  // pose_lost (the caller's verdict: POSE older than pose_timeout_s) or the
  // hover is infeasible, on the descent (DescentTarget, SlewDescent); in
  // mode mpc then FlyMpc (not in a descent: the N-input MPC has no level
  // descent weights, the cascade flies it). Before the first POSE: the hover
  // thrusts through the nominal map (neither the law nor the MPC is run).
  MultiArmRotorCommand Update(int64_t now_us, const ReferencePoint& reference, bool pose_lost = false);

  // Command rate [Hz]: the cascade's rate_hz, in mode mpc the mpc: section's
  // (CommandRateHz); the law runs at it too.
  double rate_hz() const { return CommandRateHz(config_); }
  bool model_predictive() const { return mpc_ != nullptr; }
  // Mode mpc: the last period's solve (MultiArmMpcResult: outcome, CPU and
  // wall time, iterations), solves and fallbacks to the cascade since start.
  const MultiArmMpcResult& last_mpc_result() const { return last_mpc_; }
  int64_t mpc_solves() const { return mpc_solves_; }
  int64_t mpc_fallbacks() const { return mpc_fallbacks_; }

  // e_i of the newest period (before HoverFeasibility's latched weak
  // rotor): 1 in nominal mode; with force feedback the EfficiencyConditioner's
  // e_i = a_i c_i (controller/efficiency_conditioner.h: airborne test,
  // changes relative to the settled baseline mu0_i, fault_tau_s and
  // max_rate_1_s, the absolute rule), advanced in each Update with the
  // estimate usable (EstimateUsable) or decaying towards 1 over decay_s.
  RotorEfficiencies EfficiencyInUse() const;
  // The conditioner behind it (baselines, change and absolute factors).
  const EfficiencyConditioner& efficiency_conditioner() const { return efficiency_; }

  // The efficiencies flown in the newest period: EfficiencyInUse with the
  // latched weak rotor's once hover is infeasible [1].
  const RotorEfficiencies& flown_efficiency() const { return flown_efficiency_; }
  const MultiArmDegradation& degradation() const { return degradation_; }
  const HoverFeasibility& feasibility() const { return feasibility_; }
  // The low-passed reports HoverFeasibility reads (reported_scale).
  const ForceFloorEvidence& floor_evidence() const { return floor_evidence_; }
  // Scales below the floor flown as the floor (NoteReport); estimates refused (OnEfficiency).
  int64_t force_at_floor() const { return force_at_floor_; }
  int64_t refused_estimates() const { return refused_estimates_; }

  MultiArmControlMode mode() const { return law_.mode(); }
  const BodyState& body_state() const { return observer_.state(); }
  bool has_pose() const { return has_pose_; }
  int64_t saturated_periods() const { return saturated_periods_; }

 private:
  void UpdateState(int64_t now_us, double dt_s);
  // The estimate in force may be flown at now_us: force feedback,
  // SetForceUsable, VALID, FORCE alive within force_timeout_s (counted from
  // a newer refused VALID report, if any).
  bool EstimateUsable(int64_t now_us) const;
  // ... or, not VALID by MODEL_MISMATCH alone (SetChangesUsable), only its
  // flagged rotors' relative changes (EfficiencyParams::mismatch_relative).
  bool ChangesUsable(int64_t now_us) const;
  // Force feedback only (nominal mode flies no efficiency: its infeasibility
  // is not known): HoverFeasibility on the efficiencies in use, the
  // low-passed reports (ForceFloorEvidence), the last command and the state
  // against the reference; true once hover is infeasible (latched).
  bool UpdateFeasibility(int64_t now_us, const ReferencePoint& reference, const RotorEfficiencies& efficiency,
                         double dt_s);
  // The descent's reference and tilt bound for this period; counts entries
  // and resets the integrators on entry (both when infeasible: the pitch
  // integrator wound up against a rotor that could not deliver; the
  // position one otherwise), as VehicleController::DescentTarget.
  ReferencePoint DescentTarget(const ReferencePoint& reference, bool pose_lost, bool infeasible);
  // Hovers other than f_hover keep the vehicle up: spare rotors, or a tilt
  // (MultiArmLaw::rebalances: the trirotor, whose rotor 2 at 20 % leaves no
  // level hover but one 0.04 rad off level, 0.11 rad for the cascade).
  bool HoldsOtherHovers() const;
  // The efficiency rotor i is flown with: where other hovers hold
  // (HoldsOtherHovers), hover feasible, FORCE usable (EstimateUsable) and flagging the rotor
  // below the plausibility floor (at_floor_samples reports in a row), what those reports average
  // (ForceFloorEvidence::below_floor_mean) instead of the floor; the
  // cascade flies it as making nothing (0: not driven, retired) once they
  // average below spare_retire_scale, until the run of flagged reports
  // below the floor ends, the MPC at spare_retire_scale (its model needs
  // e > 0); efficiency otherwise. The other rotors then hold the hover,
  // level or tilted (docs/controller.md, "Spare rotors").
  double BelowFloorEfficiency(int rotor, double efficiency, int64_t now_us);
  // Each rotor's motor-lag lead (MotorLagLead, as the birotor's cascade) on
  // the cascade's speeds, within [0, omega_max].
  void LeadMotorLag(const RotorEfficiencies& efficiency, double dt_s, MultiArmRotorCommand* command);
  // In a descent each speed within degraded_omega_rate_rad_s2 dt_s of the
  // last command sent (never 0 <-> omega_max in one period), the thrusts
  // following.
  void SlewDescent(const RotorEfficiencies& efficiency, double dt_s, MultiArmRotorCommand* command) const;
  // The infeasible descent's flare (POSE fresh), as the birotor's
  // VehicleController::Flare: sinking faster than descent_rate_m_s, above
  // the take-off level (the first POSE's z) and lower than sink rate x
  // flare_time_s, the thrusts of MultiArmFlareForcesFor (flare_tilt_rad,
  // each rotor's e_i c_T,i omega_max^2) replace the cascade's, unslewed;
  // true while it flares (counted in degradation()). flare_tilt_rad 0: never.
  bool Flare(bool infeasible_descent, const RotorEfficiencies& efficiency, MultiArmRotorCommand* command);
  // Mode mpc, one period of dt_s [s]: MultiArmMpc::Solve from the observer's
  // state with the efficiencies in use (1 when mpc.use_thrust_scale is
  // false) and the reference extrapolated over the horizon
  // (MultiArmMpc::ExtrapolateReference); its first command when it solved in
  // time, else the cascade's (counted in mpc_fallbacks). Either is limited to
  // mpc.max_omega_rate_rad_s2 dt_s of the last command sent and to
  // [0, omega_max] (the first period plans from the MPC's rotor-speed
  // estimate and is exempt from the rate limit, as MpcController::Fly); the
  // MPC's motor model is then advanced on it. It plans about the cascade's
  // hover (MultiArmLaw::base_tilt_rad, base_force_n) when MpcPlansTilted,
  // else about the level f_hover.
  MultiArmRotorCommand FlyMpc(const ReferencePoint& reference, const RotorEfficiencies& efficiency,
                              const MultiArmRotorCommand& cascade, double dt_s);
  // The cascade holds a tilted hover and no level one can pitch the body
  // either way (MultiArmLaw::LevelPitchesBothWays), a rotor at or below
  // spare_retire_scale counted as making nothing: the MPC, free to fly any
  // rotor down to 0, holds a level hover and tilts to move whenever one can
  // (the quadrotor with rotor 3 or 4 dead), else it drifts sideways on a
  // one-sided F_x (rotor 1 or 2 dead: RMS 0.49 m level, 0.12 m about the
  // tilted hover; docs/controller.md, "Spare rotors").
  bool MpcPlansTilted(const RotorEfficiencies& efficiency) const;

  VehicleDescription vehicle_;
  ControllerConfig config_;
  MultiArmLaw law_;
  BodyStateObserver observer_;
  MultiArmRotorCommand hover_command_;           // before the first POSE
  RotorEfficiencyEstimate efficiency_estimate_;  // the newest plausible one
  int64_t force_alive_utime_ = -1;               // its stamp, or a newer refused VALID report's [us]
  bool force_usable_ = true;                     // SetForceUsable
  bool changes_usable_ = true;                   // SetChangesUsable
  EfficiencyConditioner efficiency_;             // e_i from the plausible estimates
  ForceFloorEvidence floor_evidence_;
  std::array<bool, kMaxArms> retired_{};  // BelowFloorEfficiency's retired rotors (this run below the floor)
  int64_t force_at_floor_ = 0;
  int64_t refused_estimates_ = 0;
  bool has_pose_ = false;
  double ground_z_m_ = 0.0;           // the take-off level: the first POSE's z [m]
  MultiArmFlareLimits flare_limits_;  // the flare's geometry (FlareGeometryOf)
  int64_t last_imu_utime_ = -1;
  int imu_count_ = 0;
  double gyro_sum_rad_s_ = 0.0;
  Eigen::Vector2d specific_force_sum_m_s2_ = Eigen::Vector2d::Zero();  // body x, z
  Eigen::Vector2d last_specific_force_m_s2_ = Eigen::Vector2d::Zero();
  int64_t saturated_periods_ = 0;
  HoverFeasibility feasibility_;
  MultiArmDegradation degradation_;
  RotorEfficiencies flown_efficiency_ = NominalEfficiencies();
  std::array<double, kMaxArms> last_command_rad_s_{};  // the command returned last [rad/s]
  bool last_saturated_ = false;                        // ... and whether its allocation was limited
  std::array<MotorLagLead, kMaxArms> motor_lead_{};    // each rotor's lead of its motor lag
  // Mode mpc (null otherwise).
  std::unique_ptr<MultiArmMpc> mpc_;
  std::vector<ReferencePoint> horizon_;  // mpc.horizon_steps samples, sized once
  MultiArmMpcInputs last_sent_rad_s_;    // the command in force
  bool mpc_flown_ = false;               // FlyMpc has sent a command
  MultiArmMpcResult last_mpc_;
  MultiArmHoverBase mpc_base_;  // the cascade's hover, the MPC's plan about it (FlyMpc)
  int64_t mpc_solves_ = 0;
  int64_t mpc_fallbacks_ = 0;
};

}  // namespace birotor

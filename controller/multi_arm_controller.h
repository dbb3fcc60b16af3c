// The product's flight controller for any VehicleDescription (N = 2 .. 6
// rotors): the body state from POSE and the IMU (BodyStateObserver, as
// birotor-controller), the N-arm cascade of controller/multi_arm_law.h with
// the gains of config/controller.yaml, fully actuated (phi_des = 0, F_x made
// directly) when the allocation allows it and tilt-to-move otherwise, and N
// rotor speed commands through the nominal map or each rotor's estimated
// efficiency (RotorEfficiencyEstimate, the content of force_estimate_n_t).
// No LCM, no allocation, no throw, no log per call. Not supervised as
// VehicleController is (no stream locks, gates or controlled descent): the
// lock-step loop's controller. docs/controller.md, "Vehicles with N rotors".
#pragma once

#include <array>
#include <cstdint>

#include "controller/body_state_observer.h"
#include "controller/controller_params.h"
#include "controller/multi_arm_law.h"
#include "controller/reference_point.h"
#include "controller/wrench_allocation.h"
#include "model/multi_arm_linearization.h"
#include "model/vehicle_description.h"
#include "samples/samples.h"

namespace birotor {

// Each rotor's thrust efficiency as an estimator reports it (the content of
// force_estimate_n_t: thrust_scale, its one-sigma, STATUS_VALID,
// rotor_fault_bits). Rotor i is arm i of the description.
struct RotorEfficiencyEstimate {
  int64_t utime = -1;                               // vehicle clock [us]; -1: none
  int n_rotors = 0;                                 // must be the vehicle's arm_count
  std::array<double, kMaxArms> thrust_scale{};      // real thrust / c_T,i omega_i^2 [1]
  std::array<double, kMaxArms> thrust_scale_std{};  // its one-sigma [1]
  bool valid = false;                               // the estimator's STATUS_VALID
  int32_t rotor_fault_bits = 0;                     // bit i: rotor i + 1 faulty
};

class MultiArmController {
 public:
  // config: gains, observer, supervision (imu_timeout_s, force_timeout_s,
  // min/max_plausible_thrust_scale), efficiency (change_threshold,
  // max_relative_sigma) and force_feedback of config/controller.yaml; its
  // vehicle field is not used (vehicle is). hover: SolveMultiArmHover(vehicle).
  MultiArmController(const VehicleDescription& vehicle, const ControllerConfig& config, const MultiArmHover& hover);

  void OnPose(const PoseSample& sample);
  void OnImu(const ImuSample& sample);
  // The newest estimate; used only in force_feedback mode (EfficiencyInUse).
  void OnEfficiency(const RotorEfficiencyEstimate& estimate) { efficiency_estimate_ = estimate; }

  // One control period at now_us on the reference: the observer predicted
  // with the mean IMU of the period (stale beyond imu_timeout_s: the
  // commanded acceleration and the held pitch rate instead) and corrected by
  // the newest POSE, then MultiArmLaw::Update. Before the first POSE: the
  // hover thrusts through the nominal map (the law is not run).
  MultiArmRotorCommand Update(int64_t now_us, const ReferencePoint& reference);

  // e_i flown at now_us: 1 in nominal mode, without an estimate, with one
  // older than force_timeout_s, not VALID or for another rotor count; else
  // rotor i's thrust_scale clamped to [min, max]_plausible_thrust_scale when
  // it is flagged faulty or |scale - 1| > efficiency.change_threshold, and
  // its sigma / scale <= efficiency.max_relative_sigma; 1 otherwise.
  RotorEfficiencies EfficiencyInUse(int64_t now_us) const;

  MultiArmControlMode mode() const { return law_.mode(); }
  const BodyState& body_state() const { return observer_.state(); }
  bool has_pose() const { return has_pose_; }
  int64_t saturated_periods() const { return saturated_periods_; }

 private:
  void UpdateState(int64_t now_us, double dt_s);

  VehicleDescription vehicle_;
  ControllerConfig config_;
  MultiArmLaw law_;
  BodyStateObserver observer_;
  MultiArmRotorCommand hover_command_;  // before the first POSE
  RotorEfficiencyEstimate efficiency_estimate_;
  bool has_pose_ = false;
  PoseSample pending_pose_;
  bool pose_pending_ = false;
  int64_t last_fused_pose_utime_ = -1;
  int64_t last_imu_utime_ = -1;
  int imu_count_ = 0;
  double gyro_sum_rad_s_ = 0.0;
  Eigen::Vector2d specific_force_sum_m_s2_ = Eigen::Vector2d::Zero();  // body x, z
  Eigen::Vector2d last_specific_force_m_s2_ = Eigen::Vector2d::Zero();
  int64_t saturated_periods_ = 0;
};

}  // namespace birotor

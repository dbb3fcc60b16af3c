// The controller service's flight law: body state from POSE and the IMU
// (BodyStateObserver), the shared position/pitch law, and the rotor speeds
// from the nominal map or from each rotor's estimated thrust_scale (FORCE).
// Supervises its inputs: falls back to the nominal map within one control
// period when FORCE is stale, not VALID or not finite (and returns when it is
// healthy again), flies a controlled descent when POSE is lost, and never
// emits a command that is not finite or outside [0, omega_max]. No LCM, no
// allocation, no throw after construction.
#pragma once

#include <cstdint>
#include <memory>

#include "controller/body_state_observer.h"
#include "controller/controller_params.h"
#include "controller/motor_command.h"
#include "controller/mpc_controller.h"
#include "controller/position_attitude_law.h"
#include "controller/reference_point.h"
#include "controller/setpoint.h"
#include "controller/setpoint_input.h"
#include "samples/samples.h"

namespace birotor {

// Counters of one input since start-up.
struct ControllerInputCounters {
  int64_t received = 0;
  int64_t accepted = 0;
  int64_t rejected_invalid = 0;       // non-finite or implausible fields
  int64_t rejected_out_of_order = 0;  // utime not newer than the newest accepted
  int64_t last_utime = -1;            // newest accepted [us]; -1 if none
};

struct ControllerHealth {
  ControllerInputCounters pose, imu, force;
  int64_t commands = 0;
  int64_t fallbacks = 0;         // entries into the nominal-map fallback
  int64_t descents = 0;          // entries into the controlled descent
  int64_t saturated = 0;         // commands with a clipped rotor speed
  int64_t numerical_guards = 0;  // non-finite law outputs replaced by the last good command
  int64_t force_unhealthy = 0;   // accepted FORCE samples without VALID or with a non-finite scale
  bool fallback_active = false;
  bool descending = false;
};

class VehicleController {
 public:
  explicit VehicleController(const ControllerConfig& config);

  // Inputs, in any order and at any rate; bad samples are counted and dropped.
  void OnPose(const PoseSample& sample);
  void OnImu(const ImuSample& sample);
  void OnForce(const ForceEstimate& estimate);
  // A setpoint arrived when the controller's clock read now_us [us]
  // (SetpointInput: checked, counted, followed, held, then hover here).
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
  // True when FORCE may be flown on at now_us (fresh, VALID, finite scales).
  bool ForceHealthy(int64_t now_us) const;
  // Age of an input at now_us [s]; +inf before its first sample.
  double AgeS(int64_t last_utime, int64_t now_us) const;

  ControllerConfig config_;
  PositionAttitudeLaw law_;
  BodyStateObserver observer_;
  ControllerHealth health_;
  SetpointInput setpoint_;
  ReferencePoint reference_;

  // POSE: the newest accepted sample not yet fused.
  bool has_pose_ = false;
  bool pose_pending_ = false;
  PoseSample pending_pose_;
  int64_t last_fused_pose_utime_ = -1;

  // IMU: sums over the samples since the last control period.
  int imu_count_ = 0;
  double gyro_sum_rad_s_ = 0.0;
  double accel_sum_m_s2_[2] = {0.0, 0.0};
  double last_specific_force_m_s2_[2] = {0.0, 0.0};

  // FORCE: the thrust scales of the newest healthy estimate.
  bool newest_force_healthy_ = false;
  double thrust_scale_[2] = {1.0, 1.0};
  int64_t force_healthy_since_us_ = -1;  // start of the current healthy run; -1 while unhealthy

  int64_t last_update_us_ = -1;
  Eigen::Vector2d last_accel_des_m_s2_ = Eigen::Vector2d::Zero();
  double last_good_omega_rad_s_[2] = {0.0, 0.0};
  int32_t seq_ = 0;
  std::unique_ptr<MpcController> mpc_;  // mode mpc only
};

}  // namespace birotor

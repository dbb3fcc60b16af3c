#include "controller/vehicle_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "model/equilibrium.h"

namespace birotor {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Plausibility limits of the inputs: beyond them a sample is a corrupt one,
// not a state of this vehicle (dropped and counted as invalid).
constexpr double kMaxPositionM = 1e4;          // |x|, |z| of POSE [m]
constexpr double kMaxAngleRad = 10.0;          // |phi| of POSE [rad]
constexpr double kMaxRateRadS = 100.0;         // |gyro| [rad/s]
constexpr double kMaxSpecificForceM_S2 = 1e3;  // |accel| [m/s^2]
constexpr double kMaxThrustScale = 100.0;      // thrust_scale of FORCE [1]

bool Within(double value, double limit) { return std::isfinite(value) && std::fabs(value) <= limit; }

// Accepts a sample newer than the newest accepted one.
bool Admit(ControllerInputCounters* counters, int64_t utime, bool valid) {
  ++counters->received;
  if (!valid) {
    ++counters->rejected_invalid;
    return false;
  }
  if (counters->last_utime >= 0 && utime <= counters->last_utime) {
    ++counters->rejected_out_of_order;
    return false;
  }
  ++counters->accepted;
  counters->last_utime = utime;
  return true;
}

// The law's gains at the rate it runs (mode mpc: the MPC's, for the fallback).
ControllerParams LawGains(const ControllerConfig& config) {
  ControllerParams gains = config.gains;
  gains.rate_hz = CommandRateHz(config);
  return gains;
}

double HoverForce(const VehicleParams& vehicle) {
  const Equilibrium hover = SolveHoverEquilibrium(vehicle);
  return 0.5 * (hover.force_n[0] + hover.force_n[1]);
}

}  // namespace

VehicleController::VehicleController(const ControllerConfig& config)
    : config_(config),
      law_(config.vehicle, LawGains(config), HoverForce(config.vehicle)),
      observer_(config.observer),
      setpoint_(config.setpoint) {
  if (config.model_predictive) mpc_ = std::make_unique<MpcController>(config.vehicle, config.mpc);
  // Force feedback starts in the fallback until FORCE has been healthy for
  // force_recovery_s; that start is not counted as a fallback.
  health_.fallback_active = config.force_feedback;
}

void VehicleController::OnPose(const PoseSample& sample) {
  const bool valid = Within(sample.x_m, kMaxPositionM) && Within(sample.z_m, kMaxPositionM) &&
                     Within(sample.phi_rad, kMaxAngleRad) && sample.utime >= 0;
  if (!Admit(&health_.pose, sample.utime, valid)) return;
  if (!has_pose_) {
    has_pose_ = true;
    const Eigen::Vector2d position_m(sample.x_m, sample.z_m);
    observer_.Initialize(position_m, sample.phi_rad);
    setpoint_.SetStart(position_m);
    last_fused_pose_utime_ = sample.utime;
    return;
  }
  pending_pose_ = sample;
  pose_pending_ = true;
}

void VehicleController::OnImu(const ImuSample& sample) {
  const bool valid = Within(sample.gyro_y_rad_s, kMaxRateRadS) && Within(sample.accel_x_m_s2, kMaxSpecificForceM_S2) &&
                     Within(sample.accel_z_m_s2, kMaxSpecificForceM_S2) && sample.utime >= 0;
  if (!Admit(&health_.imu, sample.utime, valid)) return;
  ++imu_count_;
  gyro_sum_rad_s_ += sample.gyro_y_rad_s;
  accel_sum_m_s2_[0] += sample.accel_x_m_s2;
  accel_sum_m_s2_[1] += sample.accel_z_m_s2;
}

void VehicleController::OnForce(const ForceEstimate& estimate) {
  if (!Admit(&health_.force, estimate.utime, estimate.utime >= 0)) return;
  const bool healthy = (estimate.status & kStatusValid) != 0 && Within(estimate.thrust_scale[0], kMaxThrustScale) &&
                       Within(estimate.thrust_scale[1], kMaxThrustScale) && estimate.thrust_scale[0] > 0.0 &&
                       estimate.thrust_scale[1] > 0.0;
  newest_force_healthy_ = healthy;
  if (!healthy) {
    ++health_.force_unhealthy;
    force_healthy_since_us_ = -1;
    return;
  }
  if (force_healthy_since_us_ < 0) force_healthy_since_us_ = estimate.utime;
  const SupervisionParams& s = config_.supervision;
  for (int i = 0; i < 2; ++i)
    thrust_scale_[i] = std::clamp(estimate.thrust_scale[i], s.min_thrust_scale, s.max_thrust_scale);
}

double VehicleController::AgeS(int64_t last_utime, int64_t now_us) const {
  return last_utime < 0 ? kInf : 1e-6 * static_cast<double>(now_us - last_utime);
}

bool VehicleController::ForceHealthy(int64_t now_us) const {
  const SupervisionParams& s = config_.supervision;
  return newest_force_healthy_ && AgeS(health_.force.last_utime, now_us) <= s.force_timeout_s &&
         force_healthy_since_us_ >= 0 && AgeS(force_healthy_since_us_, now_us) >= s.force_recovery_s;
}

MotorCommand VehicleController::Update(int64_t now_us) {
  const SupervisionParams& s = config_.supervision;
  const VehicleParams& vehicle = config_.vehicle;
  MotorCommand command;
  command.utime = now_us;
  command.seq = seq_++;
  ++health_.commands;
  const double nominal_dt_s = 1.0 / CommandRateHz(config_);
  const double dt_s = last_update_us_ < 0
                          ? nominal_dt_s
                          : std::clamp(1e-6 * static_cast<double>(now_us - last_update_us_), 0.0, 10.0 * nominal_dt_s);
  last_update_us_ = now_us;
  // Mode mpc: the rotors have run the last command for dt_s.
  if (mpc_) mpc_->Advance(Eigen::Vector2d(last_good_omega_rad_s_[0], last_good_omega_rad_s_[1]), dt_s);

  if (!has_pose_) {
    command.mode = kModeNominal;
    command.status = kCommandNoPoseYet | kCommandInputStale;
    imu_count_ = 0;
    gyro_sum_rad_s_ = accel_sum_m_s2_[0] = accel_sum_m_s2_[1] = 0.0;
    return command;  // rotors at 0: nothing to fly on yet
  }

  // State: propagate with the mean IMU reading of the period, then fuse POSE.
  int32_t status = 0;
  const bool imu_fresh = AgeS(health_.imu.last_utime, now_us) <= s.imu_timeout_s;
  double pitch_rate_rad_s = std::numeric_limits<double>::quiet_NaN();
  if (imu_count_ > 0) {
    last_specific_force_m_s2_[0] = accel_sum_m_s2_[0] / imu_count_;
    last_specific_force_m_s2_[1] = accel_sum_m_s2_[1] / imu_count_;
    pitch_rate_rad_s = gyro_sum_rad_s_ / imu_count_;
  } else if (imu_fresh) {
    pitch_rate_rad_s = observer_.state().phi_dot_rad_s;  // no sample this period: hold the last rate
  }
  imu_count_ = 0;
  gyro_sum_rad_s_ = accel_sum_m_s2_[0] = accel_sum_m_s2_[1] = 0.0;
  // Without the IMU the commanded acceleration stands in for the measured one.
  const Eigen::Vector2d accel_world_m_s2 =
      imu_fresh ? WorldAcceleration(observer_.state().phi_rad, last_specific_force_m_s2_[0],
                                    last_specific_force_m_s2_[1], vehicle.gravity_m_s2)
                : last_accel_des_m_s2_;
  if (!imu_fresh) status |= kCommandInputStale;
  observer_.Predict(dt_s, accel_world_m_s2, imu_fresh ? pitch_rate_rad_s : std::numeric_limits<double>::quiet_NaN());
  if (pose_pending_) {
    const double interval_s = 1e-6 * static_cast<double>(pending_pose_.utime - last_fused_pose_utime_);
    observer_.CorrectPose(Eigen::Vector2d(pending_pose_.x_m, pending_pose_.z_m), pending_pose_.phi_rad, interval_s,
                          imu_fresh);
    last_fused_pose_utime_ = pending_pose_.utime;
    pose_pending_ = false;
  }

  // POSE lost: a level descent at a fixed sink rate on the propagated state
  // (the position error is held at zero, so the integrators stay put).
  const bool pose_lost = AgeS(health_.pose.last_utime, now_us) > s.pose_timeout_s;
  reference_ = setpoint_.At(now_us, observer_.state().position_m);
  ReferencePoint target = reference_;
  if (pose_lost) {
    target.position_m = observer_.state().position_m;
    target.velocity_m_s = Eigen::Vector2d(0.0, -s.descent_rate_m_s);
    target.acceleration_m_s2.setZero();
    status |= kCommandDescending | kCommandInputStale;
    if (!health_.descending) ++health_.descents;
  }
  health_.descending = pose_lost;

  const RotorForces forces = law_.Update(observer_.state(), target);
  last_accel_des_m_s2_ = forces.accel_des_m_s2;
  if (!last_accel_des_m_s2_.allFinite()) last_accel_des_m_s2_.setZero();

  // Rotor speeds: nominal map, or each rotor's estimated thrust scale.
  bool use_force = false;
  if (config_.force_feedback) {
    use_force = ForceHealthy(now_us);
    if (!use_force) {
      status |= kCommandFallbackActive;
      if (AgeS(health_.force.last_utime, now_us) > s.force_timeout_s) status |= kCommandInputStale;
      if (!health_.fallback_active) ++health_.fallbacks;
    }
    health_.fallback_active = !use_force;
  }
  command.mode = config_.force_feedback ? kModeForceFeedback : kModeNominal;
  bool saturated = false;
  double omega_rad_s[2];
  for (int i = 0; i < 2; ++i) {
    bool clipped = false;
    omega_rad_s[i] = RotorSpeedForThrust(vehicle, forces.force_n[i], use_force ? thrust_scale_[i] : 1.0, &clipped);
    saturated = saturated || clipped;
  }
  if (!std::isfinite(omega_rad_s[0]) || !std::isfinite(omega_rad_s[1])) {
    // Cannot happen with finite inputs; if it does, repeat the last good
    // command and start the integrators afresh.
    ++health_.numerical_guards;
    law_.Reset();
    omega_rad_s[0] = last_good_omega_rad_s_[0];
    omega_rad_s[1] = last_good_omega_rad_s_[1];
  }
  if (mpc_) {
    // Mode mpc: the MPC flies; the cascade's speeds above are its fallback.
    MpcPlanInput in;
    in.state = observer_.state();
    in.reference = target;
    if (use_force) in.thrust_scale = Eigen::Vector2d(thrust_scale_[0], thrust_scale_[1]);
    in.last_command_rad_s = Eigen::Vector2d(last_good_omega_rad_s_[0], last_good_omega_rad_s_[1]);
    in.period_s = nominal_dt_s;
    const MpcPeriod period = mpc_->Fly(in, Eigen::Vector2d(omega_rad_s[0], omega_rad_s[1]), !pose_lost);
    omega_rad_s[0] = period.omega_cmd_rad_s(0);
    omega_rad_s[1] = period.omega_cmd_rad_s(1);
    command.mode = kModeMpc;
    if (period.fell_back) status |= kCommandMpcFallback;
  }
  for (int i = 0; i < 2; ++i) {
    command.omega_cmd_rad_s[i] = std::clamp(omega_rad_s[i], 0.0, vehicle.omega_max_rad_s);
    last_good_omega_rad_s_[i] = command.omega_cmd_rad_s[i];
  }
  if (saturated) {
    status |= kCommandSaturated;
    ++health_.saturated;
  }
  command.status = status;
  return command;
}

}  // namespace birotor

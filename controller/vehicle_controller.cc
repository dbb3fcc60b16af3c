#include "controller/vehicle_controller.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "controller/rotor_allocation.h"
#include "model/equilibrium.h"
#include "numerics/time_units.h"
#include "samples/rotor_count.h"

namespace birotor {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The law's gains at the rate it runs (mode mpc: the MPC's, for the fallback).
ControllerParams LawGains(const ControllerConfig& config) {
  ControllerParams gains = config.gains;
  gains.rate_hz = CommandRateHz(config);
  return gains;
}

double HoverForce(const BirotorParams& vehicle) {
  const Equilibrium hover = SolveHoverEquilibrium(vehicle);
  return 0.5 * (hover.force_n[0] + hover.force_n[1]);
}

// What one rotor makes at omega_max with the nominal map, c_T omega_max^2 [N].
double MaxRotorForceN(const BirotorParams& vehicle) {
  return vehicle.thrust_coeff_n_s2_rad2 * vehicle.omega_max_rad_s * vehicle.omega_max_rad_s;
}

}  // namespace

VehicleController::VehicleController(const ControllerConfig& config)
    : config_(config),
      model_(BirotorModelOf(config.vehicle)),
      law_(model_, LawGains(config), HoverForce(model_)),
      observer_(config.observer),
      efficiency_(config.efficiency, 2.0 * HoverForce(model_)),
      feasibility_(config.efficiency, MaxRotorForceN(model_), 2.0 * HoverForce(model_)),
      pose_gate_(config.supervision),
      floor_evidence_(config.supervision, config.efficiency.infeasible_s, kBirotorRotors),
      force_recovery_(config.supervision),
      change_recovery_(config.supervision),
      force_lock_(StreamLockParams(config.supervision, config.supervision.force_stream_max_rate_hz)),
      pose_lock_(StreamLockParams(config.supervision, config.supervision.pose_stream_max_rate_hz)),
      setpoint_(config.setpoint),
      weight_n_(2.0 * HoverForce(model_)) {
  feasibility_.MeasureRecovery(model_.omega_max_rad_s, model_.gravity_m_s2);
  if (config.model_predictive) mpc_ = std::make_unique<MpcController>(model_, config.mpc);
  // Force feedback starts in the fallback until FORCE has been healthy for
  // force_recovery_s; that start is not counted as a fallback.
  health_.fallback_active = config.force_feedback;
}

void VehicleController::OnPose(const PoseSample& sample, int64_t now_us) {
  const bool valid = PlausiblePose(sample);
  const double values[3] = {sample.x_m, sample.z_m, sample.phi_rad};
  const StreamMessage message{sample.seq, sample.utime, PayloadDigest(values, 3)};
  // The stream first (a copied seq is found whatever the pose says), then
  // the gate against the observer, then newest: a refused sample does not
  // become the newest.
  if (!AdmitToStream(config_.supervision, message, valid, now_us, &pose_lock_, &health_.pose)) return;
  if (!has_pose_) {
    if (!AcceptNewest(sample.utime, &health_.pose)) return;
    has_pose_ = true;
    const Eigen::Vector2d position_m(sample.x_m, sample.z_m);
    observer_.Initialize(position_m, sample.phi_rad);
    setpoint_.SetStart(position_m);
    ground_z_m_ = sample.z_m;
    observer_.PoseUsedAt(sample.utime);
    return;
  }
  const PoseGate::Verdict verdict = pose_gate_.Check(sample, observer_.state(), now_us);
  if (verdict == PoseGate::Verdict::kRefused) {
    ++health_.pose.rejected_gate;
    return;
  }
  if (!AcceptNewest(sample.utime, &health_.pose)) return;
  health_.pose_gate_resets += verdict == PoseGate::Verdict::kReset ? 1 : 0;
  health_.pose_reacquisitions += verdict == PoseGate::Verdict::kReacquired ? 1 : 0;
  if (!MoveObserverOnto(verdict, sample, &observer_)) observer_.HoldPose(sample);
}

void VehicleController::OnImu(const ImuSample& sample, int64_t now_us) {
  const bool valid = PlausibleImu(sample);
  const StreamMessage message{sample.seq, sample.utime, 0};
  if (!AdmitToStream(config_.supervision, message, valid, now_us, nullptr, &health_.imu) ||
      !AcceptNewest(sample.utime, &health_.imu))
    return;
  ++imu_count_;
  gyro_sum_rad_s_ += sample.gyro_y_rad_s;
  accel_sum_m_s2_[0] += sample.accel_x_m_s2;
  accel_sum_m_s2_[1] += sample.accel_z_m_s2;
}

void VehicleController::OnForce(const ForceEstimate& reported, int64_t now_us) {
  const SupervisionParams& s = config_.supervision;
  // A rotor FORCE keeps flagging as faulty with a scale below the floor is
  // at most the floor: flown as the floor (hover then infeasible), not refused.
  ForceEstimate estimate = reported;
  health_.force_at_floor += floor_evidence_.FlyAtTheFloor(&estimate);
  // A scale outside the plausible band is refused, not clamped.
  bool plausible = estimate.utime >= 0;
  for (int i = 0; i < kBirotorRotors; ++i) {
    plausible = plausible && std::isfinite(estimate.force_n[i]) && std::isfinite(estimate.force_std_n[i]) &&
                estimate.thrust_scale[i] >= s.min_plausible_thrust_scale &&
                estimate.thrust_scale[i] <= s.max_plausible_thrust_scale;
  }
  const double baseline[kBirotorRotors] = {efficiency_.baseline(0), efficiency_.baseline(1)};
  floor_evidence_.Note(reported, now_us, baseline);
  const int64_t previous_utime = health_.force.last_utime;
  const double values[7] = {estimate.force_n[0],
                            estimate.force_n[1],
                            estimate.thrust_scale[0],
                            estimate.thrust_scale[1],
                            estimate.force_std_n[0],
                            estimate.force_std_n[1],
                            static_cast<double>(estimate.status)};
  const StreamMessage message{estimate.seq, estimate.utime, PayloadDigest(values, 7)};
  if (!AdmitToStream(s, message, plausible, now_us, &force_lock_, &health_.force) ||
      !AcceptNewest(estimate.utime, &health_.force)) {
    // An implausible estimate is refused and falls back at once, but it is
    // an outlier, not the end of the healthy run: the estimate rings to mu
    // 0.08 for one sample right after a 70 % loss, and restarting the run
    // there cost force_recovery_s (50 ms) of following at the worst moment
    // (loss_70 tilt 0.20 -> 0.088 rad). The next good sample on time resumes
    // the run; a run of refused ones makes the next good one late, and a late
    // one starts a new run.
    force_recovery_.OnRefused(plausible);
    change_recovery_.OnRefused(plausible);
    return;
  }
  // A late FORCE starts a new healthy run: recovery needs force_recovery_s
  // of on-time samples (ForceRecovery, shared with the N-rotor node).
  const bool healthy = (estimate.status & kStatusValid) != 0;
  const bool mismatched = !healthy && MismatchedOnly(estimate.status);
  force_recovery_.OnAccepted(estimate.utime, previous_utime, healthy);
  change_recovery_.OnAccepted(estimate.utime, previous_utime, healthy || mismatched);
  if (!healthy) {
    ++health_.force_unhealthy;
    if (mismatched) efficiency_.OnMismatchedForce(estimate);
    return;
  }
  efficiency_.OnForce(estimate);
}

double VehicleController::AgeS(int64_t last_utime, int64_t now_us) const {
  if (last_utime < 0 || now_us < last_utime) return kInf;
  return ElapsedSeconds(now_us, last_utime);
}

bool VehicleController::ForceUsable(int64_t now_us) const {
  return !health_.conflict && force_recovery_.Usable(now_us, health_.force.last_utime);
}

bool VehicleController::ChangesUsable(int64_t now_us) const {
  return !health_.conflict && change_recovery_.Usable(now_us, health_.force.last_utime);
}

void VehicleController::UpdateState(int64_t now_us, double dt_s, int32_t* status) {
  const SupervisionParams& s = config_.supervision;
  const bool imu_fresh = AgeS(health_.imu.last_utime, now_us) <= s.imu_timeout_s;
  double pitch_rate_rad_s = kNaN;
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
                                    last_specific_force_m_s2_[1], model_.gravity_m_s2)
                : last_accel_des_m_s2_;
  if (!imu_fresh) *status |= kCommandInputStale;
  observer_.Predict(dt_s, accel_world_m_s2, imu_fresh ? pitch_rate_rad_s : kNaN);
  observer_.FuseHeldPose(imu_fresh);
}

void VehicleController::Allocate(const RotorForces& forces, bool use_efficiency, bool slewed, double dt_s,
                                 MotorCommand* command, int32_t* status) {
  const BirotorParams& vehicle = model_;
  double efficiency[kBirotorRotors] = {1.0, 1.0};
  double max_force_n[kBirotorRotors];
  MaxForces(use_efficiency, max_force_n);
  for (int i = 0; i < kBirotorRotors; ++i) {
    efficiency[i] = EfficiencyInUse(i, use_efficiency);
    health_.efficiency[i] = efficiency[i];
  }
  const RotorAllocation allocation =
      AllocateAttitudeFirst(forces.total_force_n, forces.force_difference_n, max_force_n);
  bool clipped = allocation.total_limited || allocation.difference_limited;
  difference_limited_ = allocation.difference_limited;
  double omega_rad_s[kBirotorRotors];
  for (int i = 0; i < kBirotorRotors; ++i) {
    bool clip = false;
    omega_rad_s[i] = RotorSpeedForThrust(vehicle, allocation.force_n[i], efficiency[i], &clip);
    clipped = clipped || (clip && allocation.force_n[i] > 0.0);
    // Clipped to [0, omega_max] below, not counted as saturation.
    omega_rad_s[i] =
        motor_lead_[i].Lead(config_.efficiency, RotorMap{model_.thrust_coeff_n_s2_rad2, model_.omega_max_rad_s},
                            omega_rad_s[i], allocation.force_n[i], efficiency[i], dt_s);
  }
  if (!std::isfinite(omega_rad_s[0]) || !std::isfinite(omega_rad_s[1])) {
    // Cannot happen with finite inputs; if it does, repeat the last good
    // command and start the integrators afresh.
    ++health_.numerical_guards;
    law_.Reset();
    omega_rad_s[0] = last_good_omega_rad_s_[0];
    omega_rad_s[1] = last_good_omega_rad_s_[1];
  }
  // A controlled descent slews its commands: never 0 <-> omega_max in one period.
  const double max_step_rad_s = slewed ? config_.supervision.degraded_omega_rate_rad_s2 * dt_s : kInf;
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double slewed_rad_s = std::clamp(omega_rad_s[i], last_good_omega_rad_s_[i] - max_step_rad_s,
                                           last_good_omega_rad_s_[i] + max_step_rad_s);
    command->omega_cmd_rad_s[i] = std::clamp(slewed_rad_s, 0.0, vehicle.omega_max_rad_s);
    last_good_omega_rad_s_[i] = command->omega_cmd_rad_s[i];
  }
  saturated_ = clipped;
  if (clipped) {
    *status |= kCommandSaturated;
    ++health_.saturated;
  }
}

double VehicleController::EfficiencyInUse(int rotor, bool use_efficiency) const {
  return use_efficiency ? feasibility_.EfficiencyFor(rotor, efficiency_.efficiency(rotor)) : 1.0;
}

void VehicleController::MaxForces(bool use_efficiency, double (&max_force_n)[kBirotorRotors]) const {
  for (int i = 0; i < kBirotorRotors; ++i) max_force_n[i] = EfficiencyInUse(i, use_efficiency) * MaxRotorForceN(model_);
}

bool VehicleController::Flare(bool infeasible_descent, RotorForces* forces) {
  const bool flare = infeasible_descent && ApplyFlare(forces);
  if (flare && !health_.flaring) ++health_.flares;
  health_.flaring = flare;
  return flare;
}

bool VehicleController::ApplyFlare(RotorForces* forces) const {
  const EfficiencyParams& e = config_.efficiency;
  const FlareState state = FlareStateOf(observer_.state(), ground_z_m_);
  const bool flare = InFlareWindow(state, e.flare_tilt_rad, config_.supervision.descent_rate_m_s, e.flare_time_s);
  if (!flare) return false;
  FlareLimits limits;
  limits.tilt_budget_rad = e.flare_tilt_rad;
  limits.min_time_to_go_s = model_.motor_time_constant_s;
  limits.pitch_inertia_kg_m2 = RigidPitchInertiaKgM2(model_);
  limits.arm_length_m = model_.arm_length_m;
  MaxForces(config_.force_feedback, limits.max_force_n);
  const FlareForces flare_forces = FlareForcesFor(state, limits);
  forces->total_force_n = flare_forces.total_force_n;
  forces->force_difference_n = flare_forces.force_difference_n;
  return true;
}

bool VehicleController::UpdateFeasibility(double dt_s, bool use_force) {
  // Nominal mode flies no efficiency: its infeasibility is not known.
  if (!config_.force_feedback) return false;
  const BodyState& body = observer_.state();
  FeasibilityInputs in;
  in.following_force = use_force;
  in.relative_efficiency = efficiency_.relative_since_usable();
  for (int i = 0; i < kBirotorRotors; ++i) {
    in.efficiency[i] = efficiency_.efficiency(i);
    in.reported_scale[i] = floor_evidence_.reported_scale(i);
    in.command_rad_s[i] = last_good_omega_rad_s_[i];
  }
  in.allocation_limited = saturated_;
  SetTrackingInputs(reference_, body, &in);
  feasibility_.Update(in, dt_s);
  health_.infeasible_by_sink = feasibility_.entries_by_sink();
  health_.infeasible_undone = feasibility_.recoveries();
  health_.levelling = feasibility_.phase() == HoverFeasibility::Phase::kLevelling;
  return feasibility_.infeasible();
}

ReferencePoint VehicleController::DescentTarget(bool pose_lost, bool infeasible, int32_t* status) {
  const SupervisionParams& s = config_.supervision;
  ReferencePoint target = reference_;
  const bool descend = pose_lost || infeasible;
  if (descend) {
    target = DescentReference(observer_.state().position_m, s.descent_rate_m_s);
    *status |= kCommandDescending;
    if (pose_lost) *status |= kCommandInputStale;
    if (!health_.descending) {
      ++health_.descents;
      // What the position integrator learnt on the setpoint would tilt the
      // descent; when hover is infeasible the pitch integrator has wound up
      // against a rotor that could not deliver, now known and latched.
      if (infeasible) {
        law_.Reset();
      } else {
        law_.ResetPositionIntegral();
      }
    }
    if (infeasible && !health_.descending) ++health_.infeasible;
  }
  health_.descending = descend;
  // Level: tilt target 0 while levelling, within degraded_max_tilt_rad in any descent.
  law_.LimitTilt(!descend ? config_.gains.max_tilt_rad : health_.levelling ? 0.0 : s.degraded_max_tilt_rad);
  return target;
}

MotorCommand VehicleController::Update(int64_t now_us) {
  const SupervisionParams& s = config_.supervision;
  MotorCommand command;
  command.utime = now_us;
  command.seq = seq_++;
  command.mode = config_.force_feedback ? kModeForceFeedback : kModeNominal;
  ++health_.commands;
  const double nominal_dt_s = 1.0 / CommandRateHz(config_);
  const double dt_s = last_update_us_ < 0
                          ? nominal_dt_s
                          : std::clamp(ElapsedSeconds(now_us, last_update_us_), 0.0, 10.0 * nominal_dt_s);
  last_update_us_ = now_us;
  // Mode mpc: the rotors have run the last command for dt_s.
  if (mpc_) mpc_->Advance(Eigen::Vector2d(last_good_omega_rad_s_[0], last_good_omega_rad_s_[1]), dt_s);

  if (!has_pose_) {
    command.status = kCommandNoPoseYet | kCommandInputStale;
    imu_count_ = 0;
    gyro_sum_rad_s_ = accel_sum_m_s2_[0] = accel_sum_m_s2_[1] = 0.0;
    return command;  // rotors at 0: nothing to fly on yet
  }
  int32_t status = 0;
  UpdateState(now_us, dt_s, &status);

  // A second publisher on FORCE or POSE: force feedback is dropped.
  const bool conflict = force_lock_.InConflict(now_us) || pose_lock_.InConflict(now_us);
  if (conflict && !health_.conflict) ++health_.conflicts;
  health_.conflict = conflict;
  if (conflict) status |= kCommandInputConflict;

  // The efficiency: follows FORCE while it is usable, decays towards 1 when not.
  bool use_force = false;
  if (config_.force_feedback) {
    use_force = ForceUsable(now_us);
    if (!use_force) {
      status |= kCommandFallbackActive;
      if (AgeS(health_.force.last_utime, now_us) > s.force_timeout_s) status |= kCommandInputStale;
      if (!health_.fallback_active) ++health_.fallbacks;
    }
    health_.fallback_active = !use_force;
    efficiency_.Advance(dt_s, use_force, ChangesUsable(now_us));
  }

  reference_ = setpoint_.At(now_us, observer_.state().position_m);
  const bool infeasible = UpdateFeasibility(dt_s, use_force);
  if (infeasible) status |= kCommandHoverInfeasible;
  // POSE lost or hover impossible: a level descent at a fixed sink rate on
  // the propagated state (the position error is held at zero).
  const bool pose_lost = AgeS(health_.pose.last_utime, now_us) > s.pose_timeout_s;
  const bool descend = pose_lost || infeasible;
  const ReferencePoint target = DescentTarget(pose_lost, infeasible, &status);

  // Anti-windup: the integrators hold while the previous allocation was
  // limited; in a descent (whose total is limited throughout when hover is
  // infeasible) the pitch integrator holds only while the pitch torque was.
  RotorForces forces =
      law_.Update(observer_.state(), target, !saturated_, descend ? !difference_limited_ : !saturated_);
  const bool flare = Flare(infeasible && !pose_lost, &forces);
  last_accel_des_m_s2_ = forces.accel_des_m_s2;
  if (!last_accel_des_m_s2_.allFinite()) last_accel_des_m_s2_.setZero();
  const Eigen::Vector2d last_rad_s(last_good_omega_rad_s_[0], last_good_omega_rad_s_[1]);
  Allocate(forces, config_.force_feedback, descend && !flare, dt_s, &command, &status);
  if (mpc_) {
    // Mode mpc: the MPC flies (the descent too, not without POSE nor the
    // flare); the cascade's speeds just allocated are its fallback.
    MpcPlanInput in;
    in.state = observer_.state();
    in.reference = target;
    in.thrust_scale = Eigen::Vector2d(health_.efficiency[0], health_.efficiency[1]);
    in.last_command_rad_s = last_rad_s;
    in.period_s = nominal_dt_s;
    in.level_descent = infeasible;
    const MpcPeriod period =
        mpc_->Fly(in, Eigen::Vector2d(command.omega_cmd_rad_s[0], command.omega_cmd_rad_s[1]), !pose_lost && !flare);
    for (int i = 0; i < kBirotorRotors; ++i)
      command.omega_cmd_rad_s[i] = last_good_omega_rad_s_[i] = period.omega_cmd_rad_s(i);
    command.mode = kModeMpc;
    if (period.fell_back) status |= kCommandMpcFallback;
  }
  command.status = status;
  return command;
}

}  // namespace birotor

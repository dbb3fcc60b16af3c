// The N-rotor controller node: supervised inputs, the own clock and timer,
// MOTOR_COMMAND_N and CONTROLLER_STATUS.
#include "nodes/multi_arm_controller_service.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/setpoint_t.hpp"
#include "model/multi_arm_linearization.h"
#include "model/plant.h"
#include "model/vehicle_description_checksum.h"
#include "nodes/controller_rotors_message.h"
#include "nodes/controller_status_message.h"
#include "nodes/guard_status_message.h"
#include "numerics/time_units.h"
#include "samples/motor_command.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// Age of a stamp at now_us [s]; infinite before any or from the future.
double AgeS(int64_t stamp_us, int64_t now_us) {
  if (stamp_us < 0 || now_us < stamp_us) return std::numeric_limits<double>::infinity();
  return ElapsedSeconds(now_us, stamp_us);
}

}  // namespace

static_assert(kCommandFallbackActive == motor_command_n_t::STATUS_FALLBACK_ACTIVE &&
                  kCommandInputStale == motor_command_n_t::STATUS_INPUT_STALE &&
                  kCommandInputConflict == motor_command_n_t::STATUS_INPUT_CONFLICT &&
                  kCommandSaturated == motor_command_n_t::STATUS_SATURATED &&
                  kCommandMpcFallback == motor_command_n_t::STATUS_MPC_FALLBACK &&
                  kCommandDescending == motor_command_n_t::STATUS_DESCENDING &&
                  kCommandHoverInfeasible == motor_command_n_t::STATUS_HOVER_INFEASIBLE,
              "MOTOR_COMMAND_N's status bits are MOTOR_COMMAND's");

MultiArmControllerService::MultiArmControllerService(const VehicleDescription& vehicle, const ControllerConfig& config,
                                                     const ChannelNames& channels, MessageSink* sink,
                                                     HostClockUs host_clock)
    : vehicle_(vehicle),
      config_(config),
      controller_(vehicle, config, SolveMultiArmHover(vehicle)),
      setpoint_(config.setpoint),
      channels_(channels),
      sink_(sink),
      host_clock_(host_clock ? std::move(host_clock) : HostClockUs(SteadyClockUs)),
      clock_(config.supervision),
      grid_(std::max<int64_t>(1, std::llround(1e6 / controller_.rate_hz()))),
      pose_lock_(StreamLockParams(config.supervision, config.supervision.pose_stream_max_rate_hz)),
      force_lock_(StreamLockParams(config.supervision, config.supervision.force_stream_max_rate_hz)),
      pose_gate_(config.supervision),
      force_recovery_(config.supervision),
      change_recovery_(config.supervision) {
  routes_.Add(channels_.pose, Channel::kPose);
  routes_.Add(channels_.imu, Channel::kImu);
  routes_.Add(channels_.force_n, Channel::kForce);
  routes_.Add(channels_.setpoint, Channel::kSetpoint);
  const size_t n = static_cast<size_t>(vehicle_.arm_count);
  command_.n_rotors = static_cast<int8_t>(vehicle_.arm_count);
  command_.omega_cmd_rad_s.assign(n, 0.0);
  force_message_.force_n.reserve(kMaxArms);
  force_message_.force_std_n.reserve(kMaxArms);
  force_message_.thrust_scale.reserve(kMaxArms);
  PrepareControllerRotors(vehicle_.arm_count, DescriptionChecksum(vehicle_), &rotors_message_);
  buffer_.reserve(512);
  // Force feedback starts in the fallback until FORCE_N has been healthy for
  // force_recovery_s; that start is not counted as a fallback (as the birotor's).
  health_.fallback_active = config.force_feedback;
}

void MultiArmControllerService::HandlePacket(std::string_view channel, const void* data, size_t size,
                                             int64_t /*receive_wall_utime*/) {
  Channel routed;
  if (routes_.Find(channel, &routed)) Dispatch(routed, data, size, host_clock_());
}

void MultiArmControllerService::Dispatch(Channel channel, const void* data, size_t size, int64_t host_us) {
  switch (channel) {
    case Channel::kSetpoint: {
      setpoint_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) {
        ++setpoint_decode_errors_;
      } else if (clock_.set()) {  // a planner's clock is not the vehicle's: it never sets the clock
        setpoint_.Offer(FromMessage(message), clock_.VehicleTimeUs(host_us));
      }
      return;
    }
    case Channel::kPose: {
      pose_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kPose), message.utime, host_us);
      const int64_t accepted = health_.pose.accepted;
      if (now_us >= 0) OnPose(FromMessage(message), now_us);  // nothing to judge it by before
      if (health_.pose.accepted > accepted) clock_.NoteAccepted(host_us);
      return;
    }
    case Channel::kImu: {
      imu_t message;
      if (DecodeMessage(data, size, &message) != DecodeError::kNone) break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kImu), message.utime, host_us);
      const int64_t accepted = health_.imu.accepted;
      if (now_us >= 0) OnImu(FromMessage(message), now_us);
      if (health_.imu.accepted > accepted) clock_.NoteAccepted(host_us);
      return;
    }
    case Channel::kForce: {
      // Another rotor count is another vehicle's estimate: refused whole, counted.
      if (DecodeMessage(data, size, &force_message_) != DecodeError::kNone ||
          !CountMatches(force_message_, vehicle_, &force_count_refusals_))
        break;
      const int64_t now_us = clock_.ForInput(static_cast<int>(ControllerInput::kForce), force_message_.utime, host_us);
      const int64_t accepted = health_.force.accepted;
      if (now_us >= 0) OnForce(force_message_, now_us);
      if (health_.force.accepted > accepted) clock_.NoteAccepted(host_us);
      return;
    }
  }
  ++decode_errors_[static_cast<int>(channel)];  // kPose, kImu, kForce: ControllerInput's order
}

void MultiArmControllerService::OnPose(const PoseSample& sample, int64_t now_us) {
  const double values[3] = {sample.x_m, sample.z_m, sample.phi_rad};
  const StreamMessage message{sample.seq, sample.utime, PayloadDigest(values, 3)};
  // The stream, then the gate against the observer (from the second POSE
  // on), then newest: a refused sample does not become the newest (as the birotor's).
  if (!AdmitToStream(config_.supervision, message, PlausiblePose(sample), now_us, &pose_lock_, &health_.pose)) return;
  const PoseGate::Verdict verdict =
      controller_.has_pose() ? pose_gate_.Check(sample, controller_.body_state(), now_us) : PoseGate::Verdict::kInside;
  if (verdict == PoseGate::Verdict::kRefused) {
    ++health_.pose.rejected_gate;
    return;
  }
  if (!AcceptNewest(sample.utime, &health_.pose)) return;
  health_.pose_gate_resets += verdict == PoseGate::Verdict::kReset ? 1 : 0;
  health_.pose_reacquisitions += verdict == PoseGate::Verdict::kReacquired ? 1 : 0;
  if (!controller_.has_pose()) setpoint_.SetStart(Eigen::Vector2d(sample.x_m, sample.z_m));
  controller_.OnPose(sample, verdict);
}

void MultiArmControllerService::OnImu(const ImuSample& sample, int64_t now_us) {
  const StreamMessage message{sample.seq, sample.utime, 0};
  if (!AdmitToStream(config_.supervision, message, PlausibleImu(sample), now_us, nullptr, &health_.imu) ||
      !AcceptNewest(sample.utime, &health_.imu))
    return;
  controller_.OnImu(sample);
}

void MultiArmControllerService::OnForce(const force_estimate_n_t& m, int64_t now_us) {
  const SupervisionParams& s = config_.supervision;
  const int n = vehicle_.arm_count;
  RotorEfficiencyEstimate reported;
  reported.utime = m.utime;
  reported.n_rotors = n;
  for (int i = 0; i < n; ++i) {
    reported.thrust_scale[static_cast<size_t>(i)] = m.thrust_scale[i];
    reported.force_n[static_cast<size_t>(i)] = m.force_n[i];
    reported.force_std_n[static_cast<size_t>(i)] = m.force_std_n[i];
    // thrust_scale's sigma from the force's: sigma_e = sigma_f e / f (f > 0).
    reported.thrust_scale_std[static_cast<size_t>(i)] =
        m.force_n[i] > 0.0 ? m.force_std_n[i] * m.thrust_scale[i] / m.force_n[i] : 0.0;
  }
  reported.valid = (m.status & force_estimate_n_t::STATUS_VALID) != 0;
  reported.status = m.status;
  reported.rotor_fault_bits = m.rotor_fault_bits;
  // Before the checks (as the birotor's): a rotor FORCE_N keeps flagging
  // below the floor is flown as the floor, and every report is evidence for
  // the sink detection (MultiArmController::NoteReport).
  const RotorEfficiencyEstimate estimate = controller_.NoteReport(reported, now_us);
  health_.force_at_floor = controller_.force_at_floor();
  bool plausible = m.utime >= 0;
  for (int i = 0; i < n; ++i) {
    const double scale = estimate.thrust_scale[static_cast<size_t>(i)];
    plausible = plausible && std::isfinite(m.force_n[i]) && std::isfinite(m.force_std_n[i]) &&
                scale >= s.min_plausible_thrust_scale && scale <= s.max_plausible_thrust_scale;
  }
  // The payload digest over the scales and the status: an exact re-send is not news.
  double values[kMaxArms + 1] = {};
  for (int i = 0; i < n; ++i) values[i] = m.thrust_scale[i];
  values[n] = static_cast<double>(m.status);
  const StreamMessage message{m.seq, m.utime, PayloadDigest(values, n + 1)};
  const int64_t previous_utime = health_.force.last_utime;
  if (!AdmitToStream(s, message, plausible, now_us, &force_lock_, &health_.force) ||
      !AcceptNewest(m.utime, &health_.force)) {
    force_recovery_.OnRefused(plausible);
    change_recovery_.OnRefused(plausible);
    return;
  }
  force_recovery_.OnAccepted(m.utime, previous_utime, estimate.valid);
  change_recovery_.OnAccepted(m.utime, previous_utime, estimate.valid || MismatchedOnly(estimate.status));
  if (!estimate.valid) ++health_.force_unhealthy;
  controller_.OnEfficiency(estimate);
}

int64_t MultiArmControllerService::NextPeriodHostUs() const {
  return controller_.has_pose() ? grid_.Next() : std::numeric_limits<int64_t>::max();
}

void MultiArmControllerService::RunIfDue(int64_t host_us) {
  if (!controller_.has_pose() || host_us < NextPeriodHostUs()) return;
  RunControlPeriod(host_us);
  grid_.Ran(host_us);
}

bool MultiArmControllerService::SuperviseForce(int64_t now_us) {
  // A second publisher on POSE or FORCE_N drops force feedback (as the birotor's).
  const bool conflict = pose_lock_.InConflict(now_us) || force_lock_.InConflict(now_us);
  if (conflict && !health_.conflict) ++health_.conflicts;
  health_.conflict = conflict;
  // Force feedback wanted but FORCE_N stale, not VALID, refused or not yet
  // healthy for force_recovery_s: the nominal map.
  const bool usable = !conflict && force_recovery_.Usable(now_us, health_.force.last_utime);
  const bool fallback = config_.force_feedback && !usable;
  if (fallback && !health_.fallback_active) ++health_.fallbacks;
  health_.fallback_active = fallback;
  return usable;
}

CommandStatusFacts MultiArmControllerService::PeriodFacts(int64_t now_us, const MultiArmRotorCommand& command) {
  const SupervisionParams& s = config_.supervision;
  CommandStatusFacts facts;
  facts.fallback_active = health_.fallback_active;
  facts.input_stale = AgeS(health_.pose.last_utime, now_us) > s.pose_timeout_s;
  facts.input_conflict = health_.conflict;
  facts.saturated = command.saturated;
  health_.saturated += command.saturated ? 1 : 0;
  return facts;
}

void MultiArmControllerService::RunControlPeriod(int64_t host_us) {
  // The clock is monotonic; the guard keeps a command's stamp from going back.
  const int64_t vehicle_us = std::max(clock_.VehicleTimeUs(host_us), last_period_vehicle_us_);
  const BodyState& state = controller_.body_state();
  // POSE lost or a hover the rotors cannot make: the controller's level
  // controlled descent (MultiArmController::Update: DescentReference on the
  // propagated state, tilt bound, slew, integrator reset, levelling).
  const bool pose_lost = AgeS(health_.pose.last_utime, vehicle_us) > config_.supervision.pose_timeout_s;
  const ReferencePoint reference = setpoint_.At(vehicle_us, state.position_m);
  const int64_t mpc_fallbacks = controller_.mpc_fallbacks();
  const int64_t mpc_solves = controller_.mpc_solves();
  controller_.SetForceUsable(SuperviseForce(vehicle_us));
  controller_.SetChangesUsable(!health_.conflict && change_recovery_.Usable(vehicle_us, health_.force.last_utime));
  MultiArmRotorCommand command = controller_.Update(vehicle_us, reference, pose_lost);
  const MultiArmDegradation& degradation = controller_.degradation();
  health_.descending = degradation.descending;
  health_.levelling = degradation.levelling;
  health_.descents = degradation.descents;
  health_.infeasible = degradation.infeasible;
  health_.infeasible_by_sink = degradation.infeasible_by_sink;
  health_.flaring = degradation.flaring;
  health_.flares = degradation.flares;
  CommandStatusFacts facts = PeriodFacts(vehicle_us, command);
  facts.mpc_fallback = controller_.mpc_fallbacks() > mpc_fallbacks;
  facts.descending = degradation.descending;
  facts.hover_infeasible = degradation.hover_infeasible;
  if (controller_.mpc_solves() > mpc_solves) RecordMpcSolve(controller_.last_mpc_result());
  // Never a non-finite command or one outside [0, omega_max]: the last good one instead.
  bool finite = true;
  for (int i = 0; i < vehicle_.arm_count; ++i) finite = finite && std::isfinite(command.omega_cmd_rad_s[i]);
  if (!finite) {
    ++health_.numerical_guards;
    command = last_good_;
  }
  last_good_ = command;
  command_.utime = vehicle_us;
  ++command_.seq;
  command_.mode = config_.model_predictive ? kModeMpc : config_.force_feedback ? kModeForceFeedback : kModeNominal;
  command_.status = ComposeCommandStatus(facts);
  const RotorEfficiencies& efficiency = controller_.flown_efficiency();
  for (int i = 0; i < vehicle_.arm_count; ++i) {
    command_.omega_cmd_rad_s[i] = ClampCommand(vehicle_.omega_max_rad_s, command.omega_cmd_rad_s[i]);
    if (i < kBirotorRotors) health_.efficiency[i] = efficiency[static_cast<size_t>(i)];
  }
  ++health_.commands;
  EncodeMessage(command_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.motor_command_n, command_.utime, buffer_.data(), buffer_.size());
  grid_.NoteLoopTime(host_us, SteadyClockUs());
  last_period_vehicle_us_ = vehicle_us;
}

void MultiArmControllerService::RecordMpcSolve(const MultiArmMpcResult& result) {
  // On the deadline's clock, as the birotor's MpcController: wall time for
  // deadline_clock wall, this thread's CPU time otherwise.
  const bool wall = config_.mpc.deadline_clock == MpcDeadlineClock::kWall;
  mpc_solve_times_.Record(wall ? result.solve_time_s : result.solve_cpu_s);
  mpc_max_iterations_ = std::max(mpc_max_iterations_, result.iterations);
}

MpcStats MultiArmControllerService::MpcCounters() const {
  MpcStats stats;  // every fallback of the N-input MPC is counted as solver_failed
  stats.solves = controller_.mpc_solves();
  stats.solver_failed = controller_.mpc_fallbacks();
  stats.last_iterations = controller_.last_mpc_result().iterations;
  stats.max_iterations = mpc_max_iterations_;
  mpc_solve_times_.Fill(&stats);
  return stats;
}

void MultiArmControllerService::PublishStatus(int64_t wall_utime, int64_t host_us) {
  ControllerStatusContext context;
  context.now_us = clock_.VehicleTimeUs(host_us);
  context.wall_utime = wall_utime;
  context.last_status = command_.status;
  for (int i = 0; i < kNumControllerInputs; ++i) context.decode_errors[i] = decode_errors_[i];
  context.setpoint_decode_errors = setpoint_decode_errors_;
  context.clock_relatches = clock_.relatches();
  grid_.TakeLoopTimes(&context.loop_time_p99_us, &context.loop_time_max_us);
  context.udp_fragments_dropped = udp_counters_ != nullptr ? udp_counters_->fragments_dropped : 0;
  context.udp_malformed_dropped = udp_counters_ != nullptr ? udp_counters_->malformed_dropped : 0;
  ++status_message_.seq;
  BuildControllerStatus(health_, config_, setpoint_, MpcCounters(), context, &status_message_);
  EncodeMessage(status_message_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.controller_status, context.now_us, buffer_.data(), buffer_.size());
  FillControllerRotors(controller_, context.now_us, status_message_.seq, &rotors_message_);
  EncodeMessage(rotors_message_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.controller_rotors_n, context.now_us, buffer_.data(), buffer_.size());
  ++guard_status_.seq;
  const SetpointCounters setpoint = setpoint_.counters();
  BuildGuardStatus(guard_status_t::PROGRAM_CONTROLLER, context.now_us, wall_utime, signing_, authentication_, &setpoint,
                   &guard_status_);
  EncodeMessage(guard_status_, &buffer_);
  if (!buffer_.empty()) sink_->Publish(channels_.guard_status, context.now_us, buffer_.data(), buffer_.size());
}

}  // namespace birotor

// The controller node for a vehicle with N rotors (birotor-controller
// --vehicle FILE): a PacketHandler for POSE, IMU, FORCE_N and SETPOINT over
// MultiArmController (cascade or mode mpc), with the birotor node's input
// supervision (controller/input_admission.h: plausibility, clock windows,
// one seq stream on POSE and FORCE_N, newest only; SetpointInput), its clock
// and control-period grid (nodes/controller_clock.h), MOTOR_COMMAND_N,
// CONTROLLER_STATUS and with it CONTROLLER_ROTORS_N (per-rotor efficiency,
// feasibility bound, weak rotor). A FORCE_N of another rotor count is refused whole and
// counted (a decode error of FORCE, by reason in force_count_refusals()).
// FORCE_N stale (force_timeout_s), not VALID, refused, a second publisher
// on POSE or FORCE_N, or not yet healthy and on time for force_recovery_s
// (ForceRecovery, the birotor's rule): the nominal map
// (MultiArmController::SetForceUsable), STATUS_FALLBACK_ACTIVE. Every
// command is finite and within [0, omega_max]. The POSE innovation gate
// (PoseGate); a POSE older than pose_timeout_s or a hover the rotors cannot
// make (HoverFeasibility, latched): MultiArmController's level controlled
// descent, STATUS_DESCENDING (and STATUS_HOVER_INFEASIBLE), its entries in
// descents / infeasible of CONTROLLER_STATUS (docs/controller.md, "The
// daemon for N rotors").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "birotor/controller_rotors_n_t.hpp"
#include "birotor/controller_status_t.hpp"
#include "birotor/force_estimate_n_t.hpp"
#include "birotor/guard_status_t.hpp"
#include "birotor/motor_command_n_t.hpp"
#include "controller/command_status.h"
#include "controller/controller_params.h"
#include "controller/input_admission.h"
#include "controller/multi_arm_controller.h"
#include "controller/pose_gate.h"
#include "controller/setpoint_input.h"
#include "controller/vehicle_controller.h"
#include "model/vehicle_description.h"
#include "nodes/controller_clock.h"
#include "nodes/controller_service.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/channel_routes.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/counted_messages.h"

namespace birotor {

class MultiArmControllerService : public PacketHandler {
 public:
  // vehicle: the description flown (its arm_count is the rotor count of
  // FORCE_N and MOTOR_COMMAND_N); config: gains, supervision, efficiency,
  // setpoint, mode (config.vehicle is not used). sink must outlive the
  // service; host_clock as ControllerService's.
  MultiArmControllerService(const VehicleDescription& vehicle, const ControllerConfig& config,
                            const ChannelNames& channels, MessageSink* sink, HostClockUs host_clock = {});

  // The full names of POSE, IMU, FORCE_N and SETPOINT, to subscribe to.
  std::vector<std::string> InputChannels() const { return routes_.Names(); }
  void AttachUdpCounters(const UdpReceiveCounters* counters) { udp_counters_ = counters; }
  void AttachAuthentication(const SigningSink* signing, const AuthenticatingHandler* handler) {
    signing_ = signing;
    authentication_ = handler;
  }
  // PacketHandler, the one way in (as ControllerService::HandlePacket).
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  // Host time [us] of the next control period (none before the first POSE).
  int64_t NextPeriodHostUs() const;
  // Runs a control period at host_us if it is due: MOTOR_COMMAND_N.
  void RunIfDue(int64_t host_us);
  // CONTROLLER_STATUS, CONTROLLER_ROTORS_N and GUARD_STATUS; starts a new
  // reporting period.
  void PublishStatus(int64_t wall_utime, int64_t host_us);

  int64_t VehicleTimeUs(int64_t host_us) const { return clock_.VehicleTimeUs(host_us); }
  const ControllerHealth& health() const { return health_; }
  const CountRefusals& force_count_refusals() const { return force_count_refusals_; }
  int64_t decode_errors(ControllerInput input) const { return decode_errors_[static_cast<int>(input)]; }
  const MultiArmController& controller() const { return controller_; }
  SetpointCounters setpoint_counters() const { return setpoint_.counters(); }
  // The newest MOTOR_COMMAND_N sent (n_rotors 0 before any).
  const motor_command_n_t& last_command() const { return command_; }

 private:
  enum class Channel : int { kPose, kImu, kForce, kSetpoint };
  void Dispatch(Channel channel, const void* data, size_t size, int64_t host_us);
  void OnPose(const PoseSample& sample, int64_t now_us);
  void OnImu(const ImuSample& sample, int64_t now_us);
  // A decoded FORCE_N of the right count: the controller's evidence first
  // (MultiArmController::NoteReport: sink evidence, a flagged scale below
  // the floor flown as the floor), then plausible (finite, thrust scales
  // within [min, max]_plausible_thrust_scale), in the clock windows, of the
  // locked seq stream, newest; then the controller's efficiency estimate.
  void OnForce(const force_estimate_n_t& message, int64_t now_us);
  void RunControlPeriod(int64_t host_us);
  // FORCE_N's verdict for the period at now_us: usable (ForceRecovery, no
  // conflict on the seq streams); counts entries into the fallback and the conflict.
  bool SuperviseForce(int64_t now_us);
  // The facts of a period at now_us for its status bits (ComposeCommandStatus).
  CommandStatusFacts PeriodFacts(int64_t now_us, const MultiArmRotorCommand& command);
  // Mode mpc: a period's solve into the solve-time window and the iteration maximum.
  void RecordMpcSolve(const MultiArmMpcResult& result);
  // CONTROLLER_STATUS's mpc_* fields: counts, iterations, solve times.
  MpcStats MpcCounters() const;

  VehicleDescription vehicle_;
  ControllerConfig config_;
  MultiArmController controller_;
  SetpointInput setpoint_;
  ChannelNames channels_;
  MessageSink* sink_;
  HostClockUs host_clock_;
  ChannelRoutes<Channel> routes_;
  ControllerClock clock_;
  ControlPeriodGrid grid_;
  SeqStreamLock pose_lock_, force_lock_;
  PoseGate pose_gate_;
  ControllerHealth health_;
  CountRefusals force_count_refusals_;
  MpcSolveTimes mpc_solve_times_;  // mode mpc, on the deadline's clock
  int32_t mpc_max_iterations_ = 0;
  int64_t decode_errors_[kNumControllerInputs] = {0, 0, 0};
  int64_t setpoint_decode_errors_ = 0;
  ForceRecovery force_recovery_;   // FORCE_N's health and its healthy run (force_recovery_s)
  ForceRecovery change_recovery_;  // ... counting a mismatched FORCE_N healthy too (MismatchedOnly)
  int64_t last_period_vehicle_us_ = -1;
  MultiArmRotorCommand last_good_;  // the last finite command (the numerical guard)
  motor_command_n_t command_{};
  force_estimate_n_t force_message_{};
  std::vector<uint8_t> buffer_;
  controller_status_t status_message_{};
  controller_rotors_n_t rotors_message_{};  // sized for the vehicle at construction
  guard_status_t guard_status_{};
  const UdpReceiveCounters* udp_counters_ = nullptr;
  const SigningSink* signing_ = nullptr;
  const AuthenticatingHandler* authentication_ = nullptr;
};

}  // namespace birotor

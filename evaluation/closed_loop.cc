#include "evaluation/closed_loop.h"

#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "nodes/controller_status_message.h"
#include "nodes/estimator_service.h"
#include "simulator/simulator.h"
#include "sinks/wire_sample_sink.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

// The estimator node's FORCE as it publishes it: into the log unchanged and,
// decoded, to the controller at the simulator's time.
class ForceToController : public MessageSink {
 public:
  ForceToController(VehicleController* controller, const Simulator* simulator, const std::string& force_channel,
                    MessageSink* log)
      : controller_(controller), simulator_(simulator), force_channel_(force_channel), log_(log) {}

  void Publish(const std::string& channel, int64_t utime, const void* data, size_t size) override {
    if (log_ != nullptr) log_->Publish(channel, utime, data, size);
    if (channel != force_channel_ || DecodeMessage(data, size, &message_) != DecodeError::kNone) return;
    controller_->OnForce(FromMessage(message_), simulator_->utime());
  }

 private:
  VehicleController* controller_;
  const Simulator* simulator_;
  const std::string force_channel_;
  MessageSink* log_;
  force_estimate_t message_;
};

// CONTROLLER_STATUS into the log on the vehicle clock, by the controller
// node's encoder (nodes/controller_status_message.h).
class ControllerStatusLog {
 public:
  ControllerStatusLog(const VehicleController* controller, const std::string& channel, double rate_hz, MessageSink* log)
      : controller_(controller),
        channel_(channel),
        period_us_(rate_hz > 0 ? std::llround(1e6 / rate_hz) : 0),
        next_utime_(period_us_),
        log_(log) {}

  // At vehicle time now_us with the newest command's status bits.
  void PublishIfDue(int64_t now_us, int32_t last_status) {
    if (log_ == nullptr || period_us_ <= 0 || now_us < next_utime_) return;
    next_utime_ += period_us_;
    ControllerStatusContext context;
    context.now_us = context.wall_utime = now_us;
    context.last_status = last_status;
    context.report_solve_times = false;
    ++message_.seq;
    BuildControllerStatus(*controller_, context, &message_);
    EncodeMessage(message_, &buffer_);
    if (!buffer_.empty()) log_->Publish(channel_, now_us, buffer_.data(), buffer_.size());
  }

 private:
  const VehicleController* controller_;
  const std::string channel_;
  const int64_t period_us_;
  int64_t next_utime_;
  MessageSink* log_;
  controller_status_t message_{};  // seq from 0
  std::vector<uint8_t> buffer_;
};

// Routes each simulated sample to the estimator (encoded, through its node's
// one way in, as the daemon receives it), the controller and the log.
class LockStepSink : public SampleSink {
 public:
  LockStepSink(EstimatorService* estimator, VehicleController* controller, WireSampleSink* wire,
               const Simulator* simulator, ClosedLoopRun* run)
      : estimator_(estimator),
        channels_(estimator->channels()),
        controller_(controller),
        wire_(wire),
        simulator_(simulator),
        run_(run) {}

  void OnStrain(const StrainSample& sample) override {
    if (wire_ != nullptr) wire_->OnStrain(sample);
    ToEstimator(channels_.strain, ToMessage(sample));  // FORCE reaches the controller via ForceToController
  }
  void OnMotor(const MotorSample& sample) override {
    if (wire_ != nullptr) wire_->OnMotor(sample);
    ToEstimator(channels_.motor, ToMessage(sample));
  }
  void OnImu(const ImuSample& sample) override {
    if (wire_ != nullptr) wire_->OnImu(sample);
    ToEstimator(channels_.imu, ToMessage(sample));
    controller_->OnImu(sample, simulator_->utime());
  }
  void OnPose(const PoseSample& sample) override {
    if (wire_ != nullptr) wire_->OnPose(sample);
    ToEstimator(channels_.pose, ToMessage(sample));
    controller_->OnPose(sample, simulator_->utime());
  }
  void OnSetpoint(const Setpoint& setpoint) override {
    if (wire_ != nullptr) wire_->OnSetpoint(setpoint);
    run_->figures.AddSetpoint(setpoint);
    controller_->OnSetpoint(setpoint, simulator_->utime());
  }
  void OnLoadCell(const LoadCellSample& sample) override {
    if (wire_ != nullptr) wire_->OnLoadCell(sample);
  }
  void OnTruth(const TruthSample& sample) override {
    if (wire_ != nullptr) wire_->OnTruth(sample);
    run_->samples.push_back({sample, simulator_->reference().position_m});
    run_->figures.AddTruth(sample);
  }

 private:
  template <class Message>
  void ToEstimator(const std::string& channel, const Message& message) {
    EncodeMessage(message, &buffer_);
    estimator_->HandlePacket(channel, buffer_.data(), buffer_.size(), -1);  // no host arrival time
  }

  EstimatorService* estimator_;
  const ChannelNames& channels_;
  VehicleController* controller_;
  WireSampleSink* wire_;
  const Simulator* simulator_;
  ClosedLoopRun* run_;
  std::vector<uint8_t> buffer_;
};

}  // namespace

ClosedLoopRun RunClosedLoop(const Scenario& scenario, const EstimatorConfig& estimator_config,
                            const ControllerConfig& controller_config, const ClosedLoopOptions& options,
                            MessageSink* log) {
  const Stopwatch stopwatch;
  ClosedLoopRun run;
  Simulator simulator(scenario);
  simulator.UseExternalCommands(options.command_timeout_s);
  if (options.setpoint_rate_hz > 0) simulator.EmitSetpoints(options.setpoint_rate_hz);
  // The virtual clock stands still during a solve: the MPC's deadline is a
  // work budget, so that the same seed flies the same on any machine.
  ControllerConfig lock_step_config = controller_config;
  lock_step_config.mpc.deadline_clock = MpcDeadlineClock::kWork;
  VehicleController controller(lock_step_config);
  const ChannelNames channels = MakeChannelNames(options.prefix);
  WireSampleSink wire(channels, log);
  ForceToController force_route(&controller, &simulator, channels.force, log);
  EstimatorServiceOptions service_options;
  service_options.report_processing_time = false;  // deterministic, as replay
  service_options.status_rate_hz = options.status_rate_hz;
  ControllerStatusLog controller_status(&controller, channels.controller_status, options.status_rate_hz, log);
  EstimatorService estimator(estimator_config, channels, service_options, &force_route);
  LockStepSink sink(&estimator, &controller, log != nullptr ? &wire : nullptr, &simulator, &run);
  run.samples.reserve(static_cast<size_t>(simulator.total_steps() / 4 + 1));

  // The controller runs on the samples of the steps before this one (a
  // quarter-step sensor latency at 4 kHz) and its command holds until the next.
  const int64_t control_every =
      std::max<int64_t>(1, std::llround(1.0 / (CommandRateHz(controller_config) * scenario.step_s)));
  int64_t step = 0;
  while (!simulator.done()) {
    if (options.before_step) options.before_step(&simulator, &controller);
    if (step % control_every == 0) {
      const int64_t now_us = simulator.utime();
      const MotorCommand command = controller.Update(now_us);
      simulator.OfferMotorCommand(command.seq, command.utime, command.omega_cmd_rad_s);
      if (log != nullptr) wire.OnMotorCommand(command);
      run.commands.push_back(command);
      run.figures.AddCommand(command.status);
    }
    simulator.Step(&sink);
    if (log != nullptr) estimator.PublishStatusOnVehicleClock();  // ESTIMATOR_STATUS, as replay publishes it
    controller_status.PublishIfDue(simulator.utime(), run.commands.empty() ? 0 : run.commands.back().status);
    ++step;
  }
  for (const FaultEvent& event : simulator.fault_events()) {
    if (event.kind == FaultKind::kThrustStep) {
      run.fault_utime = event.utime;
      break;
    }
  }
  run.liftoff_utime = simulator.liftoff_utime();
  run.has_ground = scenario.ground.enabled;
  run.ground_z_m = scenario.start_position_m[1];
  run.arm_length_m = BirotorModelOf(scenario.vehicle).arm_length_m;
  run.controller = controller.health();
  run.setpoint = controller.setpoint().counters();
  run.mpc = controller.MpcStatistics();
  run.estimator = estimator.health();
  run.command_timeouts = simulator.command_timeouts();
  run.esc_foreign = simulator.esc_counters().foreign;
  run.esc_held = simulator.esc_counters().held;
  run.esc_conflicts = simulator.esc_counters().conflicts;
  run.simulated_s = simulator.time_s();
  run.wall_s = stopwatch.ElapsedS();
  return run;
}

}  // namespace birotor

#include "evaluation/closed_loop.h"

#include "simulator/simulator.h"
#include "sinks/wire_sample_sink.h"
#include "transport/channels.h"
#include "transport/host_clock.h"

namespace birotor {
namespace {

// Routes each simulated sample to the estimator, the controller and the log.
class LockStepSink : public SampleSink {
 public:
  LockStepSink(EstimatorPipeline* estimator, VehicleController* controller, WireSampleSink* wire,
               const Simulator* simulator, ClosedLoopRun* run)
      : estimator_(estimator), controller_(controller), wire_(wire), simulator_(simulator), run_(run) {}

  void OnStrain(const StrainSample& sample) override {
    if (wire_ != nullptr) wire_->OnStrain(sample);
    estimator_->CountReceived(InputChannel::kStrain);
    ForceEstimate estimate;
    if (!estimator_->OnStrain(sample, &estimate)) return;
    if (wire_ != nullptr) wire_->OnForce(estimate);
    controller_->OnForce(estimate, simulator_->utime());
  }
  void OnMotor(const MotorSample& sample) override {
    if (wire_ != nullptr) wire_->OnMotor(sample);
    estimator_->CountReceived(InputChannel::kMotor);
    estimator_->OnMotor(sample);
  }
  void OnImu(const ImuSample& sample) override {
    if (wire_ != nullptr) wire_->OnImu(sample);
    estimator_->CountReceived(InputChannel::kImu);
    estimator_->OnImu(sample);
    controller_->OnImu(sample, simulator_->utime());
  }
  void OnPose(const PoseSample& sample) override {
    if (wire_ != nullptr) wire_->OnPose(sample);
    estimator_->CountReceived(InputChannel::kPose);
    estimator_->OnPose(sample);
    controller_->OnPose(sample, simulator_->utime());
  }
  void OnSetpoint(const Setpoint& setpoint) override {
    if (wire_ != nullptr) wire_->OnSetpoint(setpoint);
    controller_->OnSetpoint(setpoint, simulator_->utime());
  }
  void OnLoadCell(const LoadCellSample& sample) override {
    if (wire_ != nullptr) wire_->OnLoadCell(sample);
  }
  void OnTruth(const TruthSample& sample) override {
    if (wire_ != nullptr) wire_->OnTruth(sample);
    run_->samples.push_back({sample, simulator_->reference().position_m});
  }

 private:
  EstimatorPipeline* estimator_;
  VehicleController* controller_;
  WireSampleSink* wire_;
  const Simulator* simulator_;
  ClosedLoopRun* run_;
};

}  // namespace

ClosedLoopRun RunClosedLoop(const Scenario& scenario, const EstimatorConfig& estimator_config,
                            const ControllerConfig& controller_config, const ClosedLoopOptions& options,
                            MessageSink* log) {
  const Stopwatch stopwatch;
  ClosedLoopRun run;
  Simulator simulator(scenario);
  simulator.UseExternalCommands(options.command_timeout_s);
  simulator.EmitSetpoints(options.setpoint_rate_hz);
  EstimatorPipeline estimator(estimator_config);
  // The virtual clock stands still during a solve: the MPC's deadline is a
  // work budget, so that the same seed flies the same on any machine.
  ControllerConfig lock_step_config = controller_config;
  lock_step_config.mpc.deadline_clock = MpcDeadlineClock::kWork;
  VehicleController controller(lock_step_config);
  const ChannelNames channels = MakeChannelNames(options.prefix);
  WireSampleSink wire(channels, log);
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
    }
    simulator.Step(&sink);
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
  run.arm_length_m = scenario.vehicle.arm_length_m;
  run.controller = controller.health();
  run.mpc = controller.MpcStatistics();
  run.estimator = estimator.health();
  run.command_timeouts = simulator.command_timeouts();
  run.simulated_s = simulator.time_s();
  run.wall_s = stopwatch.ElapsedS();
  return run;
}

}  // namespace birotor

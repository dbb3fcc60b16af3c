// birotor-sim: runs a scenario of simulator/ and puts its samples on LCM, live
// (paced by the wall clock times --speed) or offline (as fast as possible into
// an LCM log file whose event timestamps are the sample times, so lcm-logplayer
// replays it at the right pace). --loop repeats the scenario until stopped,
// time continuing. --controller flies the lock-step closed loop (simulator,
// estimator and controller in one process) into the log. SIGINT/SIGTERM stop
// it with the log closed. --external-controller (live) makes the simulator
// the vehicle's ESCs: it runs MOTOR_COMMAND from LCM instead of its autopilot;
// --publish-setpoints sends the scenario's trajectory on SETPOINT for it.
// --vehicle FILE flies a vehicle description with N arms instead (any
// scenario kind, live or offline: birotor_sim_vehicle.h) on the counted channels.
#include <spdlog/spdlog.h>

#include <memory>
#include <string>
#include <vector>

#include "evaluation/closed_loop.h"
#include "evaluation/control_metrics.h"
#include "nodes/esc_command_node.h"
#include "nodes/guard_status_message.h"
#include "numerics/time_units.h"
#include "params/controller_config_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/scenario_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "program/channel_security.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "security/replay_guard.h"
#include "services/birotor_sim_vehicle.h"
#include "services/live_pacer.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sinks/wire_sample_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/dropped_datagram_log.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/lcm_session.h"
#include "transport/log_io.h"
#include "transport/output_file.h"

namespace birotor {
namespace {

struct SimOptions {
  CommonOptions common;
  std::string scenario_file;             // scenario YAML (config/scenarios/*.yaml)
  std::vector<std::string> param_files;  // --params: partial scenario files, applied in order
  std::vector<std::string> overrides;    // --set section.key=value, applied in order after them
  std::string output;                    // log file (offline mode); empty: live on LCM
  std::string vehicle_file;              // --vehicle: a description with N arms; empty: the birotor
  ChannelSecurityOptions security;       // live: the site key and the unsigned channels
  double speed = 1.0;                    // live mode: simulated seconds per wall second
  bool wall_clock = false;               // utime = wall clock at start + simulated time
  bool loop = false;                     // repeat the scenario until stopped, time continuing
  bool no_truth = false;                 // do not publish TRUTH (stands in for a real vehicle)
  // Lock-step closed loop (--controller): simulator, estimator and controller
  // in one process; empty: the built-in autopilot.
  std::string controller_mode;
  std::string controller_params;     // default: the installed config/controller.yaml
  std::string estimator_params;      // default: the installed config/estimator.yaml
  double command_timeout_s = 0.1;    // ESCs command 0 after this long without MOTOR_COMMAND [s]
  bool external_controller = false;  // live: the ESCs run MOTOR_COMMAND from LCM
  bool publish_setpoints = false;    // the trajectory on SETPOINT (an external controller flies it)
  double setpoint_rate_hz = 100.0;   // SETPOINT rate [Hz]
  int realtime_priority = 0;         // live: SCHED_FIFO priority and locked memory; 0: the normal scheduler
};

// Opens the log (a temporary file next to path until FinishLog); false, said
// why, when it cannot.
bool OpenLog(LogWriter* writer, const std::string& path) {
  std::string error;
  if (writer->Open(path, &error)) return true;
  ReportError("cannot open the output log: " + error);
  return false;
}

// Closes the log (renamed into place) unless writing failed; otherwise
// abandons it, so no partial log is left behind, and says why. True when the
// log is complete.
bool FinishLog(LogWriter* writer, bool failed, const std::string& path) {
  if (!failed && writer->Close()) return true;
  writer->Abandon();
  ReportError("writing " + path + " failed" + (writer->error().empty() ? "" : ": " + writer->error()) +
              "; no log is left behind");
  return false;
}

// Offline lock-step closed loop: every channel, FORCE and MOTOR_COMMAND
// included, into the log.
bool RunClosedLoopOffline(const Scenario& scenario, const SimOptions& options, const ChannelNames& channels) {
  ControllerConfig controller;
  EstimatorConfig estimator;
  try {
    controller = LoadControllerConfig(options.controller_params);
    estimator = LoadEstimatorConfig(options.estimator_params);
  } catch (const ParamError& e) {
    ReportError(e.what());
    return false;
  }
  controller.force_feedback = options.controller_mode != "nominal";
  controller.model_predictive = options.controller_mode == "mpc";
  LogWriter writer;
  if (!OpenLog(&writer, options.output)) return false;
  LogSink log_sink(&writer);
  ClosedLoopOptions loop;
  loop.command_timeout_s = options.command_timeout_s;
  loop.prefix = channels.prefix;
  loop.setpoint_rate_hz = options.setpoint_rate_hz;
  const ClosedLoopRun run = RunClosedLoop(scenario, estimator, controller, loop, &log_sink);
  if (!FinishLog(&writer, log_sink.failed(), options.output)) return false;
  const ControlMetrics metrics = EvaluateControl(run);
  spdlog::info(
      "closed loop ({}): {:.3f} s simulated in {:.3f} s wall; {} commands, {} descents; peak altitude loss {:.4f} "
      "m; wrote {} events to {}",
      options.controller_mode, run.simulated_s, run.wall_s, run.controller.commands, run.controller.descents,
      metrics.peak_altitude_loss_m, writer.events_written(), options.output);
  // The flight's figures by the one definition birotor-eval and birotor-review print (docs/review.md).
  spdlog::info("figures: {}", run.figures.Result().Line());
  spdlog::info("verdict: {}", metrics.verdict.Line());
  if (controller.model_predictive) {
    spdlog::info(
        "mpc: {} solves, {} fallbacks ({} failed, {} non-finite, {} infeasible, {} late); solve time p50 "
        "{:.0f} us, p99 {:.0f} us, max {:.0f} us; iterations max {}",
        run.mpc.solves, run.mpc.Fallbacks(), run.mpc.solver_failed, run.mpc.non_finite, run.mpc.infeasible,
        run.mpc.late, 1e6 * run.mpc.solve_p50_s, 1e6 * run.mpc.solve_p99_s, 1e6 * run.mpc.solve_max_s,
        run.mpc.max_iterations);
  }
  return true;
}

// Offline: every sample into the log, as fast as possible.
bool RunOffline(Simulator* sim, const ChannelNames& channels, const std::string& path, bool publish_truth) {
  // A temporary file next to path, renamed when the log is complete.
  LogWriter writer;
  if (!OpenLog(&writer, path)) return false;
  LogSink log_sink(&writer);
  WireSampleSink sink(channels, &log_sink, publish_truth);
  while (!log_sink.failed() && !ShutdownRequested() && sim->Step(&sink)) {
  }
  if (!FinishLog(&writer, log_sink.failed() || sink.encode_failures() > 0, path)) return false;
  if (ShutdownRequested()) {
    spdlog::warn("stopped by a signal at t = {:.3f} s; {} is complete up to there", sim->time_s(), path);
  }
  spdlog::info("wrote {} events to {}", writer.events_written(), path);
  return true;
}

// --external-controller: MOTOR_COMMAND from the message source to the
// simulator's ESCs (nodes/esc_command_node.h), every queued command offered
// at each step (the ESCs' rules are Simulator::OfferMotorCommand's); the
// command time-out, a second commander and refused commands said in the log
// (refusals at most once a second).
class EscCommandInput {
 public:
  // MOTOR_COMMAND only authenticated (MOTOR_COMMAND_AUTH) unless the site
  // lets it through unsigned.
  EscCommandInput(MessageSource* source, const ChannelNames& channels, const ChannelSecurity& security, Simulator* sim)
      : source_(source),
        node_(channels.motor_command, sim),
        authenticated_(&node_, SealedMessages::kVerify, security.authenticator.get(), channels,
                       {AuthenticatedChannel::kMotorCommand}, security.unsigned_channels),
        sim_(sim) {
    std::string error;
    if (!source_->Subscribe(authenticated_.WithSealedChannels(node_.InputChannels()), &authenticated_, &error))
      spdlog::error("{}", error);
  }
  // Handles every command already queued.
  void Poll() {
    while (source_->DeliverOne()) {
    }
    if (sim_->command_timed_out() != timed_out_) {
      timed_out_ = sim_->command_timed_out();
      if (timed_out_) {
        spdlog::warn("no MOTOR_COMMAND for the command timeout at t = {:.3f} s: the ESCs spool the motors down",
                     sim_->time_s());
      } else {
        spdlog::info("MOTOR_COMMAND back at t = {:.3f} s", sim_->time_s());
      }
    }
    NoteRefused();
    dropped_.Check(source_->udp_counters());
  }
  const EscCommandNode& node() const { return node_; }
  const AuthenticatingHandler& authentication() const { return authenticated_; }

 private:
  // A line when the ESCs refused commands since the last one (at most once a second).
  void NoteRefused() {
    const EscCounters& n = sim_->esc_counters();
    const int64_t refused = n.received - n.accepted;
    if (refused == reported_refused_) return;
    const int64_t now_us = SteadyClockUs();
    if (last_warning_us_ >= 0 && now_us - last_warning_us_ < 1000000) return;
    last_warning_us_ = now_us;
    reported_refused_ = refused;
    spdlog::warn(
        "ESCs at t = {:.3f} s refused MOTOR_COMMAND: {} from a second commander (another seq stream, ignored; {} "
        "conflicts, {} of the locked commander held), {} with a speed not finite or outside [0, omega_max], {} "
        "stamped ahead of their clock, {} stale",
        sim_->time_s(), n.foreign, n.conflicts, n.held, n.out_of_range, n.future, n.stale);
  }

  MessageSource* source_;
  EscCommandNode node_;
  AuthenticatingHandler authenticated_;
  Simulator* sim_;
  bool timed_out_ = false;  // the start state's speeds count as a command
  DroppedDatagramLog dropped_;
  int64_t reported_refused_ = 0;
  int64_t last_warning_us_ = -1;  // host time of the last refusal warning
};

// Live: publish on LCM, paced so that simulated time runs at speed x wall time.
// GUARD_STATUS once a second of simulated time: what was sealed and refused.
class GuardStatusPublisher {
 public:
  GuardStatusPublisher(const ChannelNames& channels, MessageSink* sink)
      : channel_(channels.guard_status), sink_(sink) {}
  void MaybePublish(const Simulator& sim, const SigningSink& signing, const AuthenticatingHandler* handler) {
    if (sim.utime() < next_utime_) return;
    next_utime_ = sim.utime() + 1000000;
    ++message_.seq;
    BuildGuardStatus(guard_status_t::PROGRAM_SIM, sim.utime(), WallClockUs(), &signing, handler, nullptr, &message_);
    EncodeMessage(message_, &buffer_);
    if (!buffer_.empty()) sink_->Publish(channel_, sim.utime(), buffer_.data(), buffer_.size());
  }

 private:
  std::string channel_;
  MessageSink* sink_;
  guard_status_t message_{};
  std::vector<uint8_t> buffer_;
  int64_t next_utime_ = 0;
};

// POSE and SETPOINT sealed (their _AUTH channels) unless the site lets them
// through unsigned.
bool RunLive(Simulator* sim, const ChannelNames& channels, lcm::LCM* lcm, MessageSource* source,
             const ChannelSecurity& security, double speed, bool publish_truth) {
  LcmSink lcm_sink(lcm);
  SigningSink signing_sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(),
                           RandomPublisherId());
  WireSampleSink sink(channels, &signing_sink, publish_truth);
  std::unique_ptr<EscCommandInput> commands;
  if (source != nullptr) commands = std::make_unique<EscCommandInput>(source, channels, security, sim);
  LivePacer pacer(speed, sim->scenario().step_s);
  GuardStatusPublisher guard_status(channels, &lcm_sink);
  while (!ShutdownRequested() && sim->Step(&sink)) {
    if (commands) commands->Poll();
    guard_status.MaybePublish(*sim, signing_sink, commands ? &commands->authentication() : nullptr);
    pacer.AfterStep(sim->time_s());
  }
  if (lcm_sink.failures() > 0) spdlog::warn("{} LCM publish calls failed", lcm_sink.failures());
  if (commands) {
    const UdpReceiveCounters* udp = source->udp_counters();
    spdlog::info("MOTOR_COMMAND received {}, decode errors {}; udp fragments dropped {} malformed {} kernel drops {}",
                 commands->node().received(), commands->node().decode_errors(), udp ? udp->fragments_dropped : 0,
                 udp ? udp->malformed_dropped : 0, udp ? udp->kernel_dropped : 0);
    spdlog::info("authentication: {}", commands->authentication().Summary());
  }
  if (ShutdownRequested()) spdlog::info("stopped by a signal at t = {:.3f} s", sim->time_s());
  return true;
}

void AddSimOptions(CLI::App& app, SimOptions* options) {
  AddCommonOptions(app, &options->common);
  AddChannelSecurityOptions(app, &options->security);
  app.add_option("--scenario", options->scenario_file,
                 "Scenario file, or a scenario name such as hover (" + ConfigSearchText("scenarios/<name>.yaml") + ")")
      ->required();
  app.add_option("--params", options->param_files, "Partial scenario file applied on top of --scenario (repeatable)");
  app.add_option("--set", options->overrides, "Override section.key=value (YAML value; repeatable)");
  app.add_option("--output", options->output, "Write an LCM log file as fast as possible instead of publishing live");
  app.add_option("--vehicle", options->vehicle_file,
                 "Fly the vehicle description in FILE (config/vehicles/*.yaml) instead of the scenario's birotor, "
                 "changed as the scenario's vehicle: section differs from the reference birotor (ratios: "
                 "mismatch_stiffness_plus20 flies every arm 20 % stiffer), "
                 "any scenario (per-arm lists: one number per arm), live or with --output: STRAIN_N, MOTOR_N, "
                 "LOADCELL_N, IMU, POSE, TRUTH_N and VEHICLE (at the start and every simulated second)");
  app.add_option("--speed", options->speed, "Live mode: simulated seconds per wall-clock second")
      ->check(CLI::Range(1e-3, 1e6));
  app.add_flag("--wall-clock", options->wall_clock,
               "Stamp samples with the wall clock instead of simulated time from 0");
  app.add_flag("--loop", options->loop,
               "Repeat the scenario until stopped (SIGINT/SIGTERM), time continuing: run n starts at n x duration");
  app.add_flag("--no-truth", options->no_truth,
               "Do not publish TRUTH, as a real vehicle (tests the monitor's vehicle view)");
  app.add_option("--controller", options->controller_mode,
                 "Lock-step closed loop (with --output): fly the scenario with the controller of "
                 "birotor-controller in this mode, on the estimator's FORCE, and log every channel (mpc: the "
                 "model predictive controller of the mpc: section, the force-feedback cascade its fallback)")
      ->check(CLI::IsMember({"nominal", "force_feedback", "mpc"}));
  options->controller_params = FindConfigFile("controller.yaml");
  options->estimator_params = FindConfigFile("estimator.yaml");
  app.add_option("--controller-params", options->controller_params,
                 "Controller parameter file for --controller; default: the " + ConfigSearchText("controller.yaml"));
  app.add_option("--estimator-params", options->estimator_params,
                 "Estimator parameter file for --controller; default: the " + ConfigSearchText("estimator.yaml"));
  app.add_flag("--external-controller", options->external_controller,
               "Live: the ESCs run MOTOR_COMMAND from LCM (birotor-controller) instead of the built-in autopilot");
  app.add_flag("--publish-setpoints", options->publish_setpoints,
               "Publish the scenario's trajectory on SETPOINT (birotor-controller flies it; the lock-step "
               "--controller loop always sends it into the log)");
  app.add_option("--setpoint-rate-hz", options->setpoint_rate_hz, "SETPOINT rate with --publish-setpoints [Hz]")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_option("--command-timeout-s", options->command_timeout_s,
                 "With a controller: the ESCs spool the motors down after this long without MOTOR_COMMAND [s]")
      ->check(CLI::Range(1e-3, 10.0));
  AddRealtimeOption(app, &options->realtime_priority);
}

// The scenario with the --params files and --set overrides on top (the
// scenario's name resolved to its file in options); an error message, empty on success.
// arm_count: the vehicle's (the per-arm lists and the rotors a fault may name).
std::string LoadSimScenario(SimOptions* options, int arm_count, Scenario* scenario) {
  try {
    std::vector<std::string> overrides;
    for (const std::string& file : options->param_files) {
      const std::vector<std::string> from_file = OverridesFromFile(file);
      overrides.insert(overrides.end(), from_file.begin(), from_file.end());
    }
    overrides.insert(overrides.end(), options->overrides.begin(), options->overrides.end());
    std::string scenario_error;  // a misspelt name lists the scenarios (issue 24)
    if (!FindScenario(options->scenario_file, &options->scenario_file, &scenario_error)) return scenario_error;
    *scenario = LoadScenario(options->scenario_file, overrides, arm_count);
  } catch (const ParamError& e) {
    return e.what();
  }
  spdlog::info(
      "scenario '{}' from {} (checksum {}), {:.3f} s, seed {}, step {} s{}", scenario->name, options->scenario_file,
      FileChecksum(options->scenario_file), scenario->duration_s, scenario->seed, scenario->step_s,
      options->overrides.empty() && options->param_files.empty()
          ? ""
          : fmt::format(", {} parameter files, {} --set", options->param_files.size(), options->overrides.size()));
  return "";
}

// Options that do not go together; an error message (a usage error), empty if none.
std::string ModeConflict(const SimOptions& options) {
  if (!options.controller_mode.empty() && (options.output.empty() || options.loop)) {
    return "--controller runs the lock-step closed loop offline: it needs --output and no --loop";
  }
  if (options.external_controller && (!options.output.empty() || options.speed != 1.0)) {
    return "--external-controller is live and real time (MOTOR_COMMAND from LCM, a controller on the wall clock: "
           "--speed 1); offline or faster use --controller";
  }
  if (!options.vehicle_file.empty() &&
      (!options.controller_mode.empty() || options.loop || (options.publish_setpoints && !options.output.empty()))) {
    return "--vehicle runs the scenario's own autopilot (or, live, --external-controller with --publish-setpoints), "
           "without --controller or --loop";
  }
  if (options.loop && !options.output.empty()) {
    return "--loop runs until stopped: it is for live mode, not with --output (see --help)";
  }
  return "";
}

// What the runs emitted, summed.
struct SimTotals {
  double simulated_s = 0.0;
  ChannelCounts n;
  size_t fault_events = 0;

  void Add(const Simulator& sim) {
    simulated_s += sim.time_s();
    const ChannelCounts& emitted = sim.emitted();
    n.strain += emitted.strain;
    n.motor += emitted.motor;
    n.imu += emitted.imu;
    n.pose += emitted.pose;
    n.loadcell += emitted.loadcell;
    n.truth += emitted.truth;
    fault_events += sim.fault_events().size();
  }
};

// The scenario once, or with --loop until stopped, live or into the log.
// Each run starts where the previous one ended on the clock (the state
// starts over from the scenario's initial state); the live pacing of run k
// is relative to its own start, which is when run k - 1 ended.
bool RunScenario(const SimOptions& options, const Scenario& scenario, const ChannelNames& channels, lcm::LCM* lcm,
                 MessageSource* source, const ChannelSecurity& security, SimTotals* totals) {
  const int64_t start_utime = options.wall_clock ? WallClockUs() : 0;
  bool ok = true;
  for (int64_t run = 0; ok && (run == 0 || (options.loop && !ShutdownRequested())); ++run) {
    Simulator sim(scenario);
    sim.set_utime_offset_us(start_utime + run * sim.total_steps() * std::llround(scenario.step_s * 1e6));
    if (options.external_controller) sim.UseExternalCommands(options.command_timeout_s);
    if (options.publish_setpoints) sim.EmitSetpoints(options.setpoint_rate_hz);
    ok = options.output.empty() ? RunLive(&sim, channels, lcm, source, security, options.speed, !options.no_truth)
                                : RunOffline(&sim, channels, options.output, !options.no_truth);
    totals->Add(sim);
  }
  return ok;
}

int Main(int argc, char** argv) {
  SimOptions options;
  CLI::App app{"birotor-sim: simulated birotor sensors and truth over LCM, live or into a log file"};
  AddSimOptions(app, &options);
  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-sim", options.common.log_level);

  // --vehicle: the description first, so the scenario's per-arm lists are read for its arms.
  VehicleDescription vehicle;
  if (!options.vehicle_file.empty()) {
    try {
      vehicle = LoadVehicleDescription(options.vehicle_file);
    } catch (const ParamError& e) {
      return ReportError(e.what());
    }
  }
  Scenario scenario;
  std::string error = LoadSimScenario(&options, vehicle.arm_count, &scenario);
  if (!error.empty()) return ReportError(error);
  error = ModeConflict(options);
  if (!error.empty()) return ReportError(error, kExitUsage);
  std::vector<std::string> inputs = options.param_files;
  inputs.push_back(options.scenario_file);
  if (!options.controller_mode.empty()) {
    inputs.push_back(options.controller_params);
    inputs.push_back(options.estimator_params);
  }
  if (!options.vehicle_file.empty()) inputs.push_back(options.vehicle_file);
  if (!CheckOutputs({options.output}, inputs, &error)) return ReportError(error);
  if (!options.controller_mode.empty()) {
    InstallShutdownHandlers();
    return RunClosedLoopOffline(scenario, options, MakeChannelNames(options.common.prefix)) ? 0 : kExitFailure;
  }

  // Live, the key before anything is opened: POSE, SETPOINT and
  // MOTOR_COMMAND (N rotors: MOTOR_COMMAND_N) are authenticated unless let
  // through unsigned.
  ChannelSecurity security;
  const bool birotor = options.vehicle_file.empty();
  const bool external = options.external_controller;
  const ChannelSet used{external && birotor, options.publish_setpoints, true, false, external && !birotor, false};
  if (options.output.empty() && !LoadChannelSecurity(options.security, used, &security, &error)) {
    return ReportError(error);
  }
  std::unique_ptr<lcm::LCM> lcm;
  RealtimeOutcome realtime;
  if (options.output.empty()) {
    realtime = ApplyRealtimePriority(options.realtime_priority);  // before LCM starts a thread
    lcm = OpenLcm(options.common.lcm_url, &error);
    if (!lcm) return ReportError("cannot open LCM: " + error);
  }
  // --external-controller: MOTOR_COMMAND through the shared message source
  // (on udpm our own LC02 reader, which drops and counts fragments).
  std::unique_ptr<MessageSource> source;
  if (options.external_controller) {
    source = OpenLiveSource(options.common.lcm_url, lcm.get(), &error);
    if (!source) return ReportError(error);
  }
  InstallShutdownHandlers();
  LogRealtimeOutcome(realtime);
  if (!options.vehicle_file.empty()) {
    VehicleRunOptions run;
    run.vehicle_file = options.vehicle_file;
    run.output = options.output;
    run.speed = options.speed;
    run.wall_clock = options.wall_clock;
    run.publish_truth = !options.no_truth;
    run.external_controller = options.external_controller;
    run.command_timeout_s = options.command_timeout_s;
    run.publish_setpoints = options.publish_setpoints;
    run.setpoint_rate_hz = options.setpoint_rate_hz;
    return RunVehicleScenario(run, vehicle, scenario, MakeChannelNames(options.common.prefix), lcm.get(), source.get(),
                              security)
               ? 0
               : kExitFailure;
  }
  const Stopwatch stopwatch;
  SimTotals totals;
  const bool ok = RunScenario(options, scenario, MakeChannelNames(options.common.prefix), lcm.get(), source.get(),
                              security, &totals);
  const double wall_s = stopwatch.ElapsedS();
  const ChannelCounts& n = totals.n;
  spdlog::info(
      "simulated {:.3f} s in {:.3f} s wall ({:.0f}x real time); samples: strain {}, motor {}, imu {}, "
      "pose {}, loadcell {}, truth {}{}; {} fault events",
      totals.simulated_s, wall_s, wall_s > 0 ? totals.simulated_s / wall_s : 0.0, n.strain, n.motor, n.imu, n.pose,
      n.loadcell, n.truth, options.no_truth ? " (not published: --no-truth)" : "", totals.fault_events);
  return ok ? 0 : kExitFailure;
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) { return birotor::Main(argc, argv); }

// birotor-controller: the flight-controller daemon. Subscribes to POSE, IMU,
// FORCE and SETPOINT, flies the setpoint (before one: holds the first POSE;
// after setpoint.timeout_s without one: hovers where it is), publishes
// MOTOR_COMMAND at the controller's rate on its own timer (500 Hz) and
// CONTROLLER_STATUS at --status-rate-hz (host clock); stops on SIGINT/SIGTERM.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <string>

#include "nodes/controller_service.h"
#include "params/controller_config_yaml.h"
#include "program/channel_security.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "security/replay_guard.h"
#include "services/birotor_controller_vehicle.h"
#include "services/controller_serve_loop.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_session.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{
      "birotor-controller: flight controller on POSE, IMU and the estimated rotor forces (FORCE) over LCM, "
      "flying SETPOINT"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  std::string params_file = FindConfigFile("controller.yaml");
  std::string mode;
  std::string vehicle_file;  // --vehicle: a description with N rotors (FORCE_N, MOTOR_COMMAND_N); empty: the birotor
  double status_rate_hz = 5.0;
  int realtime_priority = 0;  // SCHED_FIFO priority and locked memory; 0: the normal scheduler
  app.add_option("--params", params_file,
                 "Controller parameter file (vehicle: and controller:, every key); default: the " +
                     ConfigSearchText("controller.yaml"));
  app.add_option("--mode", mode, "Controller mode, overrides the file")
      ->check(CLI::IsMember({"nominal", "force_feedback", "mpc"}));
  app.add_option("--vehicle", vehicle_file,
                 "A vehicle description with N rotors (e.g. config/vehicles/trirotor.yaml): the N-rotor controller "
                 "on FORCE_N, publishing MOTOR_COMMAND_N (docs/controller.md, \"Vehicles with N rotors\")")
      ->check(CLI::ExistingFile);
  app.add_option("--status-rate-hz", status_rate_hz, "CONTROLLER_STATUS rate [Hz]")->check(CLI::Range(0.1, 100.0));
  AddRealtimeOption(app, &realtime_priority);
  ChannelSecurityOptions security_options;
  AddChannelSecurityOptions(app, &security_options);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-controller", common.log_level);

  ControllerConfig config;
  try {
    config = LoadControllerConfig(params_file);
  } catch (const ParamError& error) {
    return ReportError(error.what());
  }
  if (!mode.empty()) {
    config.force_feedback = mode != "nominal";  // mpc falls back to the force-feedback cascade
    config.model_predictive = mode == "mpc";
  }

  // The key before anything is opened: without it nothing authenticated flies.
  std::string error;
  ChannelSecurity security;
  // The birotor: MOTOR_COMMAND out, SETPOINT, POSE, FORCE in; N rotors:
  // MOTOR_COMMAND_N out, SETPOINT, POSE, FORCE_N in.
  const bool birotor = vehicle_file.empty();
  const ChannelSet used{birotor, true, true, birotor, !birotor, !birotor};
  if (!LoadChannelSecurity(security_options, used, &security, &error)) return ReportError(error);
  if (!birotor) {
    return RunVehicleController(
        {vehicle_file, params_file, common.lcm_url, common.prefix, status_rate_hz, realtime_priority}, config,
        security);
  }
  const RealtimeOutcome realtime = ApplyRealtimePriority(realtime_priority);  // before LCM starts a thread
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(common.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  LogRealtimeOutcome(realtime);
  const ChannelNames channels = MakeChannelNames(common.prefix);
  LcmSink lcm_sink(lcm.get());
  // MOTOR_COMMAND sealed (MOTOR_COMMAND_AUTH) unless the site lets it through unsigned.
  SigningSink sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(), RandomPublisherId());
  ControllerService service(config, channels, &sink);
  // SETPOINT, POSE and FORCE only authenticated (their _AUTH twins), unless
  // the site lets them through unsigned; IMU passes.
  AuthenticatingHandler authenticated(
      &service, SealedMessages::kVerify, security.authenticator.get(), channels,
      {AuthenticatedChannel::kSetpoint, AuthenticatedChannel::kPose, AuthenticatedChannel::kForce},
      security.unsigned_channels);
  service.AttachAuthentication(&sink, &authenticated);
  const std::vector<std::string> subscribed = authenticated.WithSealedChannels(service.InputChannels());
  // Inputs through the shared message source: on udpm our own LC02 reader,
  // which drops and counts fragments instead of reassembling them.
  std::unique_ptr<MessageSource> source = OpenLiveSource(common.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(subscribed, &authenticated, &error)) return ReportError(error);
  service.AttachUdpCounters(source->udp_counters());
  spdlog::info("birotor-controller {} mode {} params {} (checksum {})", BIROTOR_VERSION,
               config.model_predictive ? "mpc"
               : config.force_feedback ? "force_feedback"
                                       : "nominal",
               params_file, FileChecksum(params_file));
  spdlog::info("lcm {}: in {} {} {} {} ({}), out {} {}; unsigned: {}", common.lcm_url, channels.pose, channels.imu,
               channels.force, channels.setpoint, source->Describe(), channels.motor_command,
               channels.controller_status, security_options.unsigned_channels);

  // Control periods on the controller's own timer, CONTROLLER_STATUS on the host clock.
  const bool source_ok = ServeController(source.get(), status_rate_hz, &service);
  if (!source_ok) spdlog::error("{}; stopping", source->error());
  const ControllerHealth& h = service.health();
  spdlog::info("stopped: {} MOTOR_COMMAND published; {} fallbacks, {} descents, {} saturated; FORCE received {}",
               h.commands, h.fallbacks, h.descents, h.saturated, h.force.received);
  spdlog::info("authentication: {}", authenticated.Summary());
  const MpcStats mpc = service.mpc_statistics();
  if (mpc.solves > 0) {
    spdlog::info(
        "mpc: {} solves, {} late, {} failed; solve time p50 {:.0f} us, p99 {:.0f} us, max {:.0f} us "
        "(last {} solves, {} clock)",
        mpc.solves, mpc.late, mpc.solver_failed + mpc.non_finite + mpc.infeasible, 1e6 * mpc.solve_p50_s,
        1e6 * mpc.solve_p99_s, 1e6 * mpc.solve_max_s, std::min<int64_t>(mpc.solves, kMpcTimeWindow),
        config.mpc.deadline_clock == MpcDeadlineClock::kWall ? "wall" : "thread CPU");
  }
  return source_ok ? 0 : kExitFailure;
}

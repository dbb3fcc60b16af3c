// birotor-controller: the flight-controller daemon. Subscribes to POSE, IMU
// and FORCE, holds the position of the first POSE, publishes MOTOR_COMMAND at
// the controller's rate (500 Hz; each period triggered by FORCE, or by the
// timer when FORCE stops) and CONTROLLER_STATUS at --status-rate-hz (host
// clock); stops on SIGINT/SIGTERM.
#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstring>
#include <memory>
#include <string>

#include "nodes/controller_service.h"
#include "params/controller_config_yaml.h"
#include "sinks/message_sink.h"
#include "transport/channels.h"
#include "transport/config_files.h"
#include "transport/host_clock.h"
#include "transport/lcm_session.h"
#include "transport/logging.h"
#include "transport/program_options.h"
#include "transport/shutdown.h"

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-controller: flight controller on POSE, IMU and the estimated rotor forces (FORCE) over LCM"};
  CommonOptions common;
  AddCommonOptions(app, &common);
  std::string params_file = FindConfigFile("controller.yaml");
  std::string mode;
  double status_rate_hz = 5.0;
  app.add_option("--params", params_file,
                 "Controller parameter file (vehicle: and controller:, every key); default: the " +
                     ConfigSearchText("controller.yaml"));
  app.add_option("--mode", mode, "Controller mode, overrides the file")
      ->check(CLI::IsMember({"nominal", "force_feedback", "mpc"}));
  app.add_option("--status-rate-hz", status_rate_hz, "CONTROLLER_STATUS rate [Hz]")->check(CLI::Range(0.1, 100.0));
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

  std::string error;
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(common.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(common.prefix);
  LcmSink sink(lcm.get());
  ControllerService service(config, channels, &sink);
  service.Subscribe(lcm.get());
  spdlog::info("birotor-controller {} mode {} params {} (checksum {})", BIROTOR_VERSION,
               config.model_predictive ? "mpc"
               : config.force_feedback ? "force_feedback"
                                       : "nominal",
               params_file, FileChecksum(params_file));
  spdlog::info("lcm {}: in {} {} {}, out {} {}", common.lcm_url, channels.pose, channels.imu, channels.force,
               channels.motor_command, channels.controller_status);

  const int64_t status_period_us = std::llround(1e6 / status_rate_hz);
  int64_t last_status_us = SteadyClockUs();
  while (!ShutdownRequested()) {
    const int64_t now_us = SteadyClockUs();
    const int64_t deadline_us = std::min(service.NextPeriodHostUs(), last_status_us + status_period_us);
    const int handled =
        HandleFor(*lcm, 1e-6 * static_cast<double>(std::clamp<int64_t>(deadline_us - now_us, 0, 100000)));
    if (handled < 0) {
      if (ShutdownRequested() || errno == EINTR) continue;
      spdlog::error("lcm handle failed: {}; stopping", std::strerror(errno));
      break;
    }
    const int64_t after_us = SteadyClockUs();
    service.RunIfDue(after_us);
    if (after_us - last_status_us >= status_period_us) {
      service.PublishStatus(WallClockUs(), after_us);
      last_status_us = after_us;
    }
  }
  service.Unsubscribe();
  const ControllerHealth& h = service.health();
  spdlog::info("stopped: {} MOTOR_COMMAND published; {} fallbacks, {} descents, {} saturated; FORCE received {}",
               h.commands, h.fallbacks, h.descents, h.saturated, h.force.received);
  return 0;
}

#include "services/birotor_controller_vehicle.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <memory>
#include <vector>

#include "model/vehicle_description.h"
#include "nodes/multi_arm_controller_service.h"
#include "params/vehicle_description_yaml.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "security/replay_guard.h"
#include "services/controller_serve_loop.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/lcm_session.h"

namespace birotor {

int RunVehicleController(const VehicleControllerOptions& options, const ControllerConfig& config,
                         const ChannelSecurity& security) {
  VehicleDescription vehicle;
  try {  // the description before anything is opened
    vehicle = LoadVehicleDescription(options.vehicle_file);
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
  std::string error;
  const RealtimeOutcome realtime = ApplyRealtimePriority(options.realtime_priority);  // before LCM starts a thread
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  LogRealtimeOutcome(realtime);
  const ChannelNames channels = MakeChannelNames(options.prefix);
  LcmSink lcm_sink(lcm.get());
  // MOTOR_COMMAND_N sealed (MOTOR_COMMAND_N_AUTH) unless the site lets it through unsigned.
  SigningSink sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(), RandomPublisherId());
  std::unique_ptr<MultiArmControllerService> service;
  try {
    service = std::make_unique<MultiArmControllerService>(vehicle, config, channels, &sink);
  } catch (const std::exception& e) {
    return ReportError(options.vehicle_file + ": " + e.what());
  }
  AuthenticatingHandler authenticated(
      service.get(), SealedMessages::kVerify, security.authenticator.get(), channels,
      {AuthenticatedChannel::kSetpoint, AuthenticatedChannel::kPose, AuthenticatedChannel::kForceN},
      security.unsigned_channels);
  service->AttachAuthentication(&sink, &authenticated);
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(authenticated.WithSealedChannels(service->InputChannels()), &authenticated, &error))
    return ReportError(error);
  service->AttachUdpCounters(source->udp_counters());
  spdlog::info("birotor-controller {} vehicle '{}' ({} rotors) from {}, mode {}, params {}", BIROTOR_VERSION,
               vehicle.name, vehicle.arm_count, options.vehicle_file,
               config.model_predictive ? "mpc"
               : config.force_feedback ? "force_feedback"
                                       : "nominal",
               options.params_file);
  spdlog::info("lcm {}: in {} {} {} {} ({}), out {} {}", options.lcm_url, channels.pose, channels.imu, channels.force_n,
               channels.setpoint, source->Describe(), channels.motor_command_n, channels.controller_status);
  const bool source_ok = ServeController(source.get(), options.status_rate_hz, service.get());
  if (!source_ok) spdlog::error("{}; stopping", source->error());
  const ControllerHealth& h = service->health();
  const CountRefusals& counts = service->force_count_refusals();
  spdlog::info(
      "stopped: {} MOTOR_COMMAND_N published; {} fallbacks, {} saturated, {} numerical guards; FORCE_N received {} "
      "accepted {}, refused: {} rotor count, {} invalid, {} future, {} past, {} out of order, {} foreign",
      h.commands, h.fallbacks, h.saturated, h.numerical_guards,
      h.force.received + service->decode_errors(ControllerInput::kForce), h.force.accepted, counts.Total(),
      h.force.rejected_invalid, h.force.rejected_future, h.force.rejected_past, h.force.rejected_out_of_order,
      h.force.rejected_foreign);
  const SetpointCounters sc = service->setpoint_counters();
  spdlog::info(
      "SETPOINT received {} accepted {}, refused: {} invalid, {} stamp, {} out of order, {} rate, {} jump, {} "
      "inconsistent, {} conflict; {} timeouts",
      sc.received, sc.accepted, sc.rejected_invalid, sc.rejected_stamp, sc.rejected_out_of_order, sc.rejected_rate,
      sc.rejected_jump, sc.rejected_inconsistent, sc.rejected_conflict, sc.timeouts);
  spdlog::info("authentication: {}", authenticated.Summary());
  return source_ok ? 0 : kExitFailure;
}

}  // namespace birotor

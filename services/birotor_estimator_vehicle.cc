#include "services/birotor_estimator_vehicle.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <memory>
#include <vector>

#include "nodes/multi_arm_estimator_service.h"
#include "nodes/multi_arm_state_persistence.h"
#include "params/vehicle_description_yaml.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "security/replay_guard.h"
#include "services/estimator_serve_loop.h"
#include "services/state_file_access.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/message_source.h"
#include "transport/channels.h"
#include "transport/lcm_session.h"

namespace birotor {

int RunVehicleEstimator(const VehicleEstimatorOptions& options, EstimatorConfig config,
                        const ChannelSecurity& security) {
  std::unique_ptr<MultiArmEstimatorService> service;
  const ChannelNames channels = MakeChannelNames(options.prefix);
  std::string error;
  try {  // the description before anything is opened
    config.vehicle = LoadVehicleDescription(options.vehicle_file);
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
  const RealtimeOutcome realtime = ApplyRealtimePriority(options.realtime_priority);  // before LCM starts a thread
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.lcm_url, &error);
  if (!lcm) return ReportError(error);
  LcmSink lcm_sink(lcm.get());
  // FORCE_N sealed (FORCE_N_AUTH) unless the site lets it through unsigned.
  SigningSink sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(), RandomPublisherId());
  try {
    service = std::make_unique<MultiArmEstimatorService>(config, channels, options.service, &sink);
  } catch (const std::exception& e) {
    return ReportError(e.what());
  }
  InstallShutdownHandlers();
  LogRealtimeOutcome(realtime);
  // The gauge state file (tare.state_file), as the birotor daemon's: read
  // before the first packet, written at a clean stop, under the site key.
  const MessageAuthenticator* authenticator = StateFileAuthenticator(security, config.tare.state_file);
  if (authenticator != nullptr) RestoreVehicleGaugeState(config.tare.state_file, config, *authenticator, service.get());
  const std::string state_file = authenticator ? WritableStateFile(config.tare.state_file) : "";
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.lcm_url, lcm.get(), &error);
  const std::vector<std::string> inputs = {channels.strain_n, channels.motor_n, channels.imu};
  if (!source || !source->Subscribe(inputs, service.get(), &error)) return ReportError(error);
  spdlog::info("birotor-estimator {} vehicle '{}' ({} arms) from {}, estimator: of {}", BIROTOR_VERSION,
               config.vehicle.name, config.vehicle.arm_count, options.vehicle_file, options.params_file);
  const bool sealed = security.signed_channels()[static_cast<int>(AuthenticatedChannel::kForceN)];
  spdlog::info("lcm {}: in {} {} {} ({}), out {} ({}) {} {}", options.lcm_url, channels.strain_n, channels.motor_n,
               channels.imu, source->Describe(), channels.force_n, sealed ? "sealed" : "plain: --unsigned",
               channels.estimator_status, channels.estimator_learned_n);
  if (!ServeEstimator(source.get(), options.service.status_rate_hz, service.get())) {
    spdlog::error("{}; stopping", source->error());
  }
  const InputCounters& strain = service->health().inputs[static_cast<int>(InputChannel::kStrain)];
  spdlog::info("stopped: {} FORCE_N published; strain received {} decode errors {} out of order {}; resets {}",
               service->forces_published(), strain.received, strain.decode_errors, strain.out_of_order,
               service->health().resets);
  if (!state_file.empty() && !PersistVehicleGaugeState(state_file, *service, *authenticator, &error)) {
    return ReportError("gauge state: " + error);
  }
  return 0;
}

}  // namespace birotor

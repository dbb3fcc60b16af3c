// birotor-estimator: the live rotor-force estimation daemon. Subscribes to
// STRAIN, MOTOR, IMU and POSE, publishes one FORCE per accepted strain sample
// and ESTIMATOR_STATUS at --status-rate-hz (wall clock); stops on SIGINT/SIGTERM.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "nodes/estimator_service.h"
#include "nodes/gauge_state_file.h"
#include "params/estimator_config_yaml.h"
#include "params/vehicle_section_update.h"
#include "params/yaml_reader.h"
#include "program/channel_security.h"
#include "program/config_files.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "security/message_authenticator.h"
#include "security/replay_guard.h"
#include "services/birotor_estimator_vehicle.h"
#include "services/estimator_serve_loop.h"
#include "services/state_file_access.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/authenticating_handler.h"
#include "sources/message_source.h"
#include "sources/receive_loop.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_session.h"

namespace birotor {
namespace {

struct DaemonOptions {
  CommonOptions common;
  std::string params_file = FindConfigFile("estimator.yaml");
  std::string vehicle_file;  // --vehicle: a description with N arms (the counted channels); empty: the birotor
  std::string method;        // overrides the file's; empty: the file's
  EstimatorServiceOptions service;
  int realtime_priority = 0;  // SCHED_FIFO priority and locked memory; 0: normal scheduler
  // The site key that authenticates POSE, FORCE and the gauge state file
  // (docs/deploy.md); the systemd unit passes its LoadCredential= copy.
  ChannelSecurityOptions security;
};

void AddDaemonOptions(CLI::App& app, DaemonOptions* options) {
  AddCommonOptions(app, &options->common);
  app.add_option("--params", options->params_file,
                 "Estimator parameter file (vehicle: and estimator:, every key); default: the " +
                     ConfigSearchText("estimator.yaml"));
  app.add_option("--method", options->method, "Estimation method, overrides the file")
      ->check(CLI::IsMember(EstimationMethodNames()));
  app.add_option("--status-rate-hz", options->service.status_rate_hz, "ESTIMATOR_STATUS rate [Hz]")
      ->check(CLI::Range(0.1, 100.0));
  app.add_option("--overload-max-delay-s", options->service.overload_max_delay_s,
                 "Strain packets queued longer than this are dropped and counted [s]")
      ->check(CLI::Range(0.001, 60.0));
  app.add_option("--stale-input-s", options->service.stale_input_wall_s,
                 "No strain packet for this long (host clock): ESTIMATOR_STATUS says INPUT_STALE [s]")
      ->check(CLI::Range(0.001, 60.0));
  app.add_option("--vehicle", options->vehicle_file,
                 "A vehicle description with N arms (e.g. config/vehicles/trirotor.yaml): the N-arm EKF on STRAIN_N, "
                 "MOTOR_N and IMU, FORCE_N out (plain: the counted types have no sealed twin yet), with the "
                 "estimator: section of --params")
      ->check(CLI::ExistingFile);
  AddChannelSecurityOptions(app, &options->security);
  AddRealtimeOption(app, &options->realtime_priority);
}

// The parameter file, with --method over the file's; an error message, empty on success.
std::string LoadConfig(const DaemonOptions& options, EstimatorConfig* config) {
  try {
    *config = LoadEstimatorConfig(options.params_file);
  } catch (const ParamError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return options.params_file + ": " + error.what();
  }
  if (!options.method.empty()) config->method = options.method;
  return "";
}

// Whether the state file's learned tip mass is flown (tip-mass learning on:
// learning resumes from it) or not (the file's m_p).
void LogResumedTipMass(const GaugeCalibration& persisted, const PipelineHealth& health, const std::string& file) {
  if (health.tip_mass_from_state_file) {
    spdlog::info("tip mass {:.6g} +- {:.3g} kg from the state file {}: flown, learning resumes from it",
                 persisted.tip_mass_kg, persisted.tip_mass_std_kg, file);
  } else {
    spdlog::info(
        "tip mass {:.6g} +- {:.3g} kg in the state file {} not flown (model_consistency arm_mode_learn_tip_mass "
        "off, or learn_strain_scale on without the arm-mode test): the parameter file's {:.6g} kg; deploy it with "
        "birotor-identify "
        "--learned",
        persisted.tip_mass_kg, persisted.tip_mass_std_kg, file, health.tip_mass_kg);
  }
}

// The learned gauge offsets of the last run, from the state file. A missing
// file is a first start; a corrupt, foreign or unauthenticated one is refused.
void RestoreGaugeOffsets(const EstimatorConfig& config, const std::string& vehicle_checksum,
                         const MessageAuthenticator* authenticator, EstimatorService* service) {
  const std::string& state_file = config.tare.state_file;
  if (state_file.empty() || authenticator == nullptr) return;
  GaugeCalibration persisted = GaugeCalibration::FromVehicle(BirotorModelOf(config.vehicle));
  std::string error;
  if (access(state_file.c_str(), F_OK) != 0) {
    spdlog::info("gauge state file {} absent: gauge offsets from the parameter file", state_file);
  } else if (ReadGaugeState(state_file, vehicle_checksum, config.tare.max_offset_rad, *authenticator, &persisted,
                            &error)) {
    service->SetGaugeOffsets(persisted);
    spdlog::info("gauge offsets {:.3e} {:.3e} rad from the state file {}", persisted.offset_rad[0],
                 persisted.offset_rad[1], state_file);
    if (persisted.has_tip_mass) LogResumedTipMass(persisted, service->health(), state_file);
  } else {
    spdlog::warn("gauge state file refused: {}; gauge offsets from the parameter file", error);
  }
}

// What runs: version, method, parameter file and its stamp, channels, the
// socket's receive buffer.
void LogStartup(const DaemonOptions& options, const EstimatorConfig& config, const std::string& vehicle_checksum,
                const ChannelNames& channels, const MessageSource& source) {
  spdlog::info("birotor-estimator {} method {} params {} (checksum {})", BIROTOR_VERSION, config.method,
               options.params_file, FileChecksum(options.params_file));
  const std::string stamp = ReadIdentificationStamp(options.params_file);
  spdlog::info("vehicle checksum {}, identified {}", vehicle_checksum,
               stamp.empty() ? "never (no birotor-identify stamp in the vehicle section)" : stamp);
  spdlog::info("lcm {}: in {} {} {} {} ({}), out {} {} {}", options.common.lcm_url, channels.strain, channels.motor,
               channels.imu, channels.pose, source.Describe(), channels.force, channels.estimator_status,
               channels.estimator_learned_n);
  bool buffer_ok = true;
  const std::string buffer_report = ReceiveBufferReport(options.common.lcm_url, ReadRmemMax(), &buffer_ok);
  if (buffer_ok) {
    spdlog::info("{}", buffer_report);
  } else {
    spdlog::warn("{}", buffer_report);
  }
}

void LogStopped(const EstimatorService& service, const MessageSource& source) {
  const PipelineHealth& health = service.health();
  const InputCounters& strain = health.inputs[static_cast<int>(InputChannel::kStrain)];
  const UdpReceiveCounters* udp = source.udp_counters();
  spdlog::info(
      "stopped: {} FORCE published; strain received {} fused {} decode errors {} out of order {} "
      "overload drops {}; resets {}; udp fragments dropped {} malformed {} kernel drops {}",
      service.forces_published(), strain.received, strain.fused, strain.decode_errors, strain.out_of_order,
      strain.dropped_overload, health.resets, udp ? udp->fragments_dropped : 0, udp ? udp->malformed_dropped : 0,
      udp ? udp->kernel_dropped : 0);
}

}  // namespace
}  // namespace birotor

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-estimator: rotor-force estimation daemon (EKF or baselines) over LCM"};
  DaemonOptions options;
  AddDaemonOptions(app, &options);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-estimator", options.common.log_level);

  // The parameter file and the key are checked before anything is subscribed.
  EstimatorConfig config;
  std::string error = LoadConfig(options, &config);
  if (!error.empty()) return ReportError(error);
  ChannelSecurity security;
  // The birotor reads POSE and publishes FORCE; N arms publish FORCE_N.
  const bool birotor = options.vehicle_file.empty();
  const ChannelSet used{false, false, birotor, birotor, false, !birotor};
  if (!LoadChannelSecurity(options.security, used, &security, &error)) return ReportError(error);
  if (!birotor) {
    return RunVehicleEstimator({options.vehicle_file, options.params_file, options.common.lcm_url,
                                options.common.prefix, options.service, options.realtime_priority},
                               config, security);
  }
  const RealtimeOutcome realtime = ApplyRealtimePriority(options.realtime_priority);  // before LCM starts a thread
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.common.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  LogRealtimeOutcome(realtime);

  const ChannelNames channels = MakeChannelNames(options.common.prefix);
  LcmSink lcm_sink(lcm.get());
  // FORCE sealed (FORCE_AUTH) unless the site lets it through unsigned.
  SigningSink sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(), RandomPublisherId());
  EstimatorService service(config, channels, options.service, &sink);
  // POSE only authenticated (POSE_AUTH) unless let through unsigned. FORCE
  // too: the daemon's check for a second estimator on the prefix compares
  // what arrives on FORCE with what it published, so its own sealed FORCE
  // comes back opened, and a forged one is refused before it.
  AuthenticatingHandler authenticated(&service, SealedMessages::kVerify, security.authenticator.get(), channels,
                                      {AuthenticatedChannel::kPose, AuthenticatedChannel::kForce},
                                      security.unsigned_channels);
  service.AttachAuthentication(&sink, &authenticated);
  const std::string vehicle_checksum = VehicleChecksum(BirotorModelOf(config.vehicle));
  const MessageAuthenticator* authenticator = StateFileAuthenticator(security, config.tare.state_file);
  RestoreGaugeOffsets(config, vehicle_checksum, authenticator, &service);
  const std::string state_file = authenticator ? WritableStateFile(config.tare.state_file) : "";
  // Inputs through the shared message source. On udpm our own small-message
  // reader, and LCM only publishes (it opens no receive socket until
  // something subscribes): LCM's fragment reassembly, which two crafted
  // datagrams crash, is never reached (docs/lcm-udpm-fragment-bug.md). Other
  // providers (memq:// in tests) go through LCM's subscription.
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.common.lcm_url, lcm.get(), &error);
  std::vector<std::string> subscribed = authenticated.WithSealedChannels(service.InputChannels());
  if (!security.unsigned_channels[static_cast<int>(AuthenticatedChannel::kForce)]) {
    // FORCE sealed: its own check needs FORCE_AUTH only, and a plain FORCE is
    // refused by every reader that flies (one packet less per sample here).
    subscribed.erase(std::remove(subscribed.begin(), subscribed.end(), channels.force), subscribed.end());
  }
  if (!source || !source->Subscribe(subscribed, &authenticated, &error)) return ReportError(error);
  service.AttachUdpCounters(source->udp_counters());
  LogStartup(options, config, vehicle_checksum, channels, *source);

  if (!ServeEstimator(source.get(), options.service.status_rate_hz, &service))
    spdlog::error("{}; stopping", source->error());
  LogStopped(service, *source);
  spdlog::info("authentication: {}", authenticated.Summary());
  if (!state_file.empty()) {
    const GaugeCalibration state = PersistedGaugeState(service.health());
    if (!WriteGaugeState(state_file, state, vehicle_checksum, *authenticator, &error)) {
      return ReportError("gauge state: " + error);
    }
    spdlog::info("gauge offsets ({}){}{} written to {}", GaugeOffsetSourceName(state.source),
                 state.has_strain_scale ? ", learned strain scales" : "",
                 state.has_tip_mass ? ", learned tip mass" : "", state_file);
  }
  return 0;
}

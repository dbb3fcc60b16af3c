// birotor-latency-probe: publishes synthetic STRAIN (and MOTOR at half rate)
// samples on LCM at a fixed rate, listens for the daemon's FORCE messages,
// pairs them by seq and prints the publish-to-FORCE latency distribution and
// the samples that never got a FORCE. Run birotor-estimator with the same
// --lcm-url and --prefix. --through-controller also publishes IMU and POSE
// and measures STRAIN published -> MOTOR_COMMAND of a running
// birotor-controller (paired by utime: a command carries the utime of the
// FORCE, hence of the strain sample, that triggered it).

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/motor_command_t.hpp"
#include "birotor/motor_t.hpp"
#include "birotor/pose_t.hpp"
#include "birotor/strain_t.hpp"
#include "numerics/percentile.h"
#include "program/channel_security.h"
#include "program/logging.h"
#include "program/program_options.h"
#include "program/realtime.h"
#include "program/shutdown.h"
#include "samples/rotor_count.h"
#include "security/replay_guard.h"
#include "sinks/message_sink.h"
#include "sinks/signing_sink.h"
#include "sources/dropped_datagram_log.h"
#include "sources/message_source.h"
#include "sources/receive_loop.h"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/lcm_session.h"

namespace {

// Reference hover (shared/spec/reference-vehicle.md).
constexpr double kHoverDeflectionRad = 0.0018664;
constexpr double kHoverOmegaRadS = 698.55;

struct Probe {
  std::vector<int64_t> publish_ns;  // per seq; 0 before publication
  std::vector<int64_t> latency_ns;  // per seq; -1 until FORCE arrives
  std::atomic<int64_t> received{0};
  std::atomic<int64_t> unmatched{0};  // FORCE with an unknown seq or not decodable
  std::atomic<int64_t> duplicates{0};
  // --through-controller: per seq, STRAIN published -> MOTOR_COMMAND with its utime.
  int64_t utime0 = 0;
  int64_t period_us = 1;
  std::vector<int64_t> command_latency_ns;  // -1 until a command with that utime arrives
  std::atomic<int64_t> commands{0};
  std::atomic<int64_t> commands_unmatched{0};  // timer-triggered commands (no FORCE) and others
};

void OnCommand(const void* data, size_t size, Probe* probe) {
  const int64_t now_ns = birotor::SteadyClockNs();
  birotor::motor_command_t message;
  ++probe->commands;
  if (birotor::DecodeMessage(data, size, &message) != birotor::DecodeError::kNone ||
      (message.utime - probe->utime0) % probe->period_us != 0) {
    ++probe->commands_unmatched;
    return;
  }
  const int64_t k = (message.utime - probe->utime0) / probe->period_us;
  if (k < 0 || static_cast<size_t>(k) >= probe->publish_ns.size() || probe->publish_ns[k] == 0 ||
      probe->command_latency_ns[k] >= 0) {
    ++probe->commands_unmatched;
    return;
  }
  probe->command_latency_ns[k] = now_ns - probe->publish_ns[k];
}

// "p50 .. max" of latencies [ns] in us; sorts them.
std::string LatencyText(std::vector<int64_t>* latencies) {
  std::sort(latencies->begin(), latencies->end());
  char text[200];
  std::snprintf(text, sizeof text, "p50 %.1f  p90 %.1f  p99 %.1f  p99.9 %.1f  max %.1f",
                birotor::Percentile(*latencies, 0.50) * 1e-3, birotor::Percentile(*latencies, 0.90) * 1e-3,
                birotor::Percentile(*latencies, 0.99) * 1e-3, birotor::Percentile(*latencies, 0.999) * 1e-3,
                static_cast<double>(latencies->back()) * 1e-3);
  return text;
}

void OnForce(const void* data, size_t size, Probe* probe) {
  const int64_t now_ns = birotor::SteadyClockNs();
  birotor::force_estimate_t message;
  if (birotor::DecodeMessage(data, size, &message) != birotor::DecodeError::kNone || message.seq < 0 ||
      static_cast<size_t>(message.seq) >= probe->publish_ns.size() || probe->publish_ns[message.seq] == 0) {
    ++probe->unmatched;
    return;
  }
  if (probe->latency_ns[message.seq] >= 0) {
    ++probe->duplicates;
    return;
  }
  probe->latency_ns[message.seq] = now_ns - probe->publish_ns[message.seq];
  ++probe->received;
}

// FORCE and MOTOR_COMMAND from the message source to the probe.
class ProbeInput : public birotor::PacketHandler {
 public:
  ProbeInput(Probe* probe, const birotor::ChannelNames& channels) : probe_(probe), channels_(channels) {}
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t /*receive_wall_utime*/) override {
    if (channel == channels_.force) OnForce(data, size, probe_);
    if (channel == channels_.motor_command) OnCommand(data, size, probe_);
  }

 private:
  Probe* probe_;
  birotor::ChannelNames channels_;
};

struct ProbeOptions {
  birotor::CommonOptions common;
  double rate_hz = 1000;                     // STRAIN rate [Hz]; MOTOR at half of it
  double duration_s = 10;                    // publishing time [s]
  double drain_s = 1.0;                      // wait for the last FORCE messages [s]
  bool through_controller = false;           // also IMU and POSE, and STRAIN -> MOTOR_COMMAND
  int realtime_priority = 0;                 // SCHED_FIFO priority; 0: normal scheduler
  birotor::ChannelSecurityOptions security;  // the key that seals POSE (--through-controller)
};

void AddProbeOptions(CLI::App& app, ProbeOptions* options) {
  options->common.prefix = "LATENCY_PROBE_";  // keep away from a real vehicle's channels
  birotor::AddCommonOptions(app, &options->common);
  app.add_option("--rate-hz", options->rate_hz, "STRAIN rate [Hz]; MOTOR at half of it")
      ->check(CLI::Range(1.0, 100000.0));
  app.add_option("--duration-s", options->duration_s, "Publishing time [s]")->check(CLI::Range(0.1, 3600.0));
  app.add_option("--drain-s", options->drain_s, "Time to wait for the last FORCE messages [s]")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--through-controller", options->through_controller,
               "Also publish IMU (every sample) and POSE (every 10th) of a hover and measure STRAIN published -> "
               "MOTOR_COMMAND of a running birotor-controller");
  birotor::AddRealtimeOption(app, &options->realtime_priority);
  birotor::AddChannelSecurityOptions(app, &options->security);
}

// The synthetic hover the probe publishes, sample k at a time.
class HoverPublisher {
 public:
  // sink: LCM behind the signing sink (POSE goes out sealed).
  HoverPublisher(birotor::MessageSink* sink, const birotor::ChannelNames& channels)
      : sink_(sink), channels_(channels) {}

  // MOTOR at half the STRAIN rate.
  void PublishMotor(int64_t k, int64_t utime) {
    if (k % 2 != 0) return;
    motor_.utime = utime;
    motor_.seq = static_cast<int32_t>(k / 2);
    for (int i = 0; i < birotor::kBirotorRotors; ++i) {
      motor_.omega_cmd_rad_s[i] = kHoverOmegaRadS;
      motor_.omega_meas_rad_s[i] = kHoverOmegaRadS;
    }
    Publish(channels_.motor, motor_, &motor_buffer_);
  }

  // Level hover at the origin: the controller's inputs besides FORCE (IMU
  // every sample, POSE every 10th).
  void PublishControllerInputs(int64_t k, int64_t utime) {
    imu_.utime = utime;
    imu_.seq = static_cast<int32_t>(k);
    imu_.accel_z_m_s2 = 9.81;
    Publish(channels_.imu, imu_, &imu_buffer_);
    if (k % 10 == 0) {
      pose_.utime = utime;
      pose_.seq = static_cast<int32_t>(k / 10);
      Publish(channels_.pose, pose_, &pose_buffer_);
    }
  }

  // STRAIN sample k, its publication time recorded in the probe.
  void PublishStrain(int64_t k, int64_t utime, Probe* probe) {
    strain_.utime = utime;
    strain_.seq = static_cast<int32_t>(k);
    // A small deterministic ripple (1e-6 rad) so the filter sees changing data.
    const double ripple_rad = 1e-6 * std::sin(0.01 * static_cast<double>(k));
    strain_.deflection_rad[0] = -kHoverDeflectionRad + ripple_rad;
    strain_.deflection_rad[1] = kHoverDeflectionRad + ripple_rad;
    birotor::EncodeMessage(strain_, &strain_buffer_);
    probe->publish_ns[k] = birotor::SteadyClockNs();
    sink_->Publish(channels_.strain, utime, strain_buffer_.data(), strain_buffer_.size());
  }

 private:
  template <typename Message>
  void Publish(const std::string& channel, const Message& message, std::vector<uint8_t>* buffer) {
    birotor::EncodeMessage(message, buffer);
    sink_->Publish(channel, message.utime, buffer->data(), buffer->size());
  }

  birotor::MessageSink* sink_;
  const birotor::ChannelNames& channels_;
  birotor::strain_t strain_;
  birotor::motor_t motor_;
  birotor::imu_t imu_{};
  birotor::pose_t pose_{};
  std::vector<uint8_t> strain_buffer_, motor_buffer_, imu_buffer_, pose_buffer_;
};

// Publishes the hover at --rate-hz for --duration-s (or until a signal);
// returns the number of STRAIN samples published and their time [s].
int64_t PublishHover(const ProbeOptions& options, birotor::MessageSink* sink, const birotor::ChannelNames& channels,
                     int64_t count, Probe* probe, double* publish_s) {
  using namespace birotor;
  const int64_t period_ns = static_cast<int64_t>(std::llround(1e9 / options.rate_hz));
  const int64_t period_us = std::max<int64_t>(1, period_ns / 1000);
  // Vehicle clock of the synthetic samples: the wall clock at start, so a
  // second run moves forward in time for the daemon.
  const int64_t utime0 = WallClockUs();
  probe->utime0 = utime0;
  probe->period_us = period_us;
  HoverPublisher publisher(sink, channels);
  const int64_t start_ns = SteadyClockNs();
  int64_t published = 0;
  for (int64_t k = 0; k < count && !ShutdownRequested(); ++k) {
    const int64_t due_ns = start_ns + k * period_ns;
    std::this_thread::sleep_until(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(due_ns)));
    const int64_t utime = utime0 + k * period_us;
    publisher.PublishMotor(k, utime);
    if (options.through_controller) publisher.PublishControllerInputs(k, utime);
    publisher.PublishStrain(k, utime, probe);
    ++published;
  }
  *publish_s = static_cast<double>(SteadyClockNs() - start_ns) * 1e-9;
  return published;
}

// The latencies [ns] of the first `published` samples that got an answer.
std::vector<int64_t> AnsweredLatencies(const std::vector<int64_t>& latency_ns, int64_t published) {
  std::vector<int64_t> latencies;
  latencies.reserve(static_cast<size_t>(published));
  for (int64_t k = 0; k < published; ++k) {
    if (latency_ns[k] >= 0) latencies.push_back(latency_ns[k]);
  }
  return latencies;
}

// --through-controller: the STRAIN -> MOTOR_COMMAND figures; false (reported)
// if no command could be paired.
bool ReportControllerLatency(const ProbeOptions& options, const birotor::ChannelNames& channels, const Probe& probe,
                             int64_t published) {
  std::vector<int64_t> command_latencies = AnsweredLatencies(probe.command_latency_ns, published);
  std::printf("MOTOR_COMMAND received %" PRId64 ", paired with a STRAIN %zu, unpaired %" PRId64 "\n",
              probe.commands.load(), command_latencies.size(), probe.commands_unmatched.load());
  if (command_latencies.empty()) {
    birotor::ReportError("no MOTOR_COMMAND paired on " + channels.motor_command +
                         ": is birotor-controller running with --lcm-url " + options.common.lcm_url + " --prefix " +
                         options.common.prefix + "?");
    return false;
  }
  std::printf("latency STRAIN publish->MOTOR_COMMAND [us]: %s\n", LatencyText(&command_latencies).c_str());
  return true;
}

// The figures; returns the exit status: 0, 1 when nothing came back, 3 when
// the figures are real but some samples got no FORCE (see "dropped").
int ReportLatency(const ProbeOptions& options, const birotor::ChannelNames& channels, const Probe& probe,
                  const birotor::MessageSource& source, int64_t published, double publish_s) {
  using namespace birotor;
  std::vector<int64_t> latencies = AnsweredLatencies(probe.latency_ns, published);
  std::sort(latencies.begin(), latencies.end());
  const int64_t dropped = published - static_cast<int64_t>(latencies.size());
  std::printf("url %s prefix %s: %" PRId64 " STRAIN published at %.0f Hz in %.2f s (achieved %.1f Hz)\n",
              options.common.lcm_url.c_str(), options.common.prefix.c_str(), published, options.rate_hz, publish_s,
              static_cast<double>(published) / publish_s);
  std::printf("FORCE received %zu, dropped (no FORCE) %" PRId64 ", unmatched %" PRId64 ", duplicates %" PRId64 "\n",
              latencies.size(), dropped, probe.unmatched.load(), probe.duplicates.load());
  if (source.udp_counters() != nullptr) std::printf("input: %s\n", UdpCountersText(source.udp_counters()).c_str());
  if (latencies.empty()) {
    return ReportError("no FORCE received on " + channels.force + " for " + std::to_string(published) +
                       " STRAIN published on " + channels.strain + ": is birotor-estimator running with --lcm-url " +
                       options.common.lcm_url + " --prefix " + options.common.prefix + "?");
  }
  std::printf("latency publish->FORCE [us]: %s\n", LatencyText(&latencies).c_str());
  if (options.through_controller && !ReportControllerLatency(options, channels, probe, published)) return kExitFailure;
  return dropped == 0 ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-latency-probe: publish-to-FORCE latency of a running birotor-estimator"};
  ProbeOptions options;
  AddProbeOptions(app, &options);
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-latency-probe", options.common.log_level);
  const birotor::RealtimeOutcome realtime = birotor::ApplyRealtimePriority(options.realtime_priority);
  if (!realtime.warning.empty()) std::fprintf(stderr, "birotor-latency-probe: warning: %s\n", realtime.warning.c_str());

  // --through-controller publishes POSE, which the controller and the
  // estimator take only sealed unless the site lets it through unsigned.
  std::string error;
  ChannelSecurity security;
  if (!LoadChannelSecurity(options.security, ChannelSet{false, false, options.through_controller, false}, &security,
                           &error)) {
    return ReportError(error);
  }
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(options.common.lcm_url, &error);
  if (!lcm) return ReportError(error);
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(options.common.prefix);
  const int64_t count = static_cast<int64_t>(std::llround(options.rate_hz * options.duration_s));
  Probe probe;
  probe.publish_ns.assign(static_cast<size_t>(count), 0);
  probe.latency_ns.assign(static_cast<size_t>(count), -1);
  probe.command_latency_ns.assign(static_cast<size_t>(count), -1);
  // FORCE (and MOTOR_COMMAND) through the shared message source on a
  // receiver thread: on udpm our own LC02 reader, which drops and counts
  // fragments instead of reassembling them.
  // The plain FORCE and MOTOR_COMMAND (a signing publisher sends the plain
  // copy right after the sealed one, so the latency includes the sealing).
  ProbeInput input(&probe, channels);
  std::vector<std::string> inputs = {channels.force};
  if (options.through_controller) inputs.push_back(channels.motor_command);
  std::unique_ptr<MessageSource> source = OpenLiveSource(options.common.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(inputs, &input, &error)) return ReportError(error);
  std::atomic<bool> stop_receiving{false};
  std::thread receiver([&] {
    DroppedDatagramLog dropped;
    while (!stop_receiving.load()) {
      ReceiveUntil(source.get(), 0.05, SteadyClockUs() + 50000);
      dropped.Check(source->udp_counters());
    }
  });

  double publish_s = 0;
  LcmSink lcm_sink(lcm.get());
  SigningSink sink(&lcm_sink, security.authenticator.get(), channels, security.signed_channels(), RandomPublisherId());
  const int64_t published = PublishHover(options, &sink, channels, count, &probe, &publish_s);
  std::this_thread::sleep_for(std::chrono::duration<double>(options.drain_s));
  stop_receiving = true;
  receiver.join();
  return ReportLatency(options, channels, probe, *source, published, publish_s);
}

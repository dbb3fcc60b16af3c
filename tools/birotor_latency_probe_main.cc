// birotor-latency-probe: publishes synthetic STRAIN (and MOTOR at half rate)
// samples on LCM at a fixed rate, listens for the daemon's FORCE messages,
// pairs them by seq and prints the publish-to-FORCE latency distribution and
// the samples that never got a FORCE. Run birotor-estimator with the same
// --lcm-url and --prefix. --through-controller also publishes IMU and POSE
// and measures STRAIN published -> MOTOR_COMMAND of a running
// birotor-controller (paired by utime: a command carries the utime of the
// FORCE, hence of the strain sample, that triggered it).
#include <sched.h>

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
#include "program/logging.h"
#include "program/program_options.h"
#include "program/shutdown.h"
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

}  // namespace

int main(int argc, char** argv) {
  using namespace birotor;
  CLI::App app{"birotor-latency-probe: publish-to-FORCE latency of a running birotor-estimator"};
  CommonOptions common;
  common.prefix = "LATENCY_PROBE_";  // keep away from a real vehicle's channels
  AddCommonOptions(app, &common);
  double rate_hz = 1000;
  double duration_s = 10;
  double drain_s = 1.0;
  app.add_option("--rate-hz", rate_hz, "STRAIN rate [Hz]; MOTOR at half of it")->check(CLI::Range(1.0, 100000.0));
  app.add_option("--duration-s", duration_s, "Publishing time [s]")->check(CLI::Range(0.1, 3600.0));
  app.add_option("--drain-s", drain_s, "Time to wait for the last FORCE messages [s]")->check(CLI::Range(0.0, 60.0));
  bool through_controller = false;
  app.add_flag("--through-controller", through_controller,
               "Also publish IMU (every sample) and POSE (every 10th) of a hover and measure STRAIN published -> "
               "MOTOR_COMMAND of a running birotor-controller");
  int realtime_priority = 0;
  app.add_option("--realtime-priority", realtime_priority,
                 "SCHED_FIFO priority (1-99) for the probe's threads; 0: normal scheduler")
      ->check(CLI::Range(0, 99));
  if (const auto exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  SetupLogging("birotor-latency-probe", common.log_level);
  if (realtime_priority > 0) {
    sched_param param{};
    param.sched_priority = realtime_priority;  // inherited by the receiver thread
    if (sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
      std::fprintf(stderr, "birotor-latency-probe: warning: cannot set SCHED_FIFO (needs CAP_SYS_NICE)\n");
    }
  }

  std::string error;
  std::unique_ptr<lcm::LCM> lcm = OpenLcm(common.lcm_url, &error);
  if (!lcm) {
    return ReportError(error);
  }
  InstallShutdownHandlers();
  const ChannelNames channels = MakeChannelNames(common.prefix);
  const int64_t count = static_cast<int64_t>(std::llround(rate_hz * duration_s));
  Probe probe;
  probe.publish_ns.assign(static_cast<size_t>(count), 0);
  probe.latency_ns.assign(static_cast<size_t>(count), -1);
  probe.command_latency_ns.assign(static_cast<size_t>(count), -1);
  // FORCE (and MOTOR_COMMAND) through the shared message source on a
  // receiver thread: on udpm our own LC02 reader, which drops and counts
  // fragments instead of reassembling them.
  ProbeInput input(&probe, channels);
  std::vector<std::string> inputs = {channels.force};
  if (through_controller) inputs.push_back(channels.motor_command);
  std::unique_ptr<MessageSource> source = OpenLiveSource(common.lcm_url, lcm.get(), &error);
  if (!source || !source->Subscribe(inputs, &input, &error)) return ReportError(error);

  std::atomic<bool> stop_receiving{false};
  std::thread receiver([&] {
    DroppedDatagramLog dropped;
    while (!stop_receiving.load()) {
      ReceiveUntil(source.get(), 0.05, SteadyClockUs() + 50000);
      dropped.Check(source->udp_counters());
    }
  });

  const int64_t period_ns = static_cast<int64_t>(std::llround(1e9 / rate_hz));
  const int64_t period_us = std::max<int64_t>(1, period_ns / 1000);
  // Vehicle clock of the synthetic samples: the wall clock at start, so a
  // second run moves forward in time for the daemon.
  const int64_t utime0 = WallClockUs();
  probe.utime0 = utime0;
  probe.period_us = period_us;
  strain_t strain;
  motor_t motor;
  imu_t imu{};
  pose_t pose{};
  std::vector<uint8_t> strain_buffer, motor_buffer, imu_buffer, pose_buffer;
  const int64_t start_ns = SteadyClockNs();
  int64_t published = 0;
  for (int64_t k = 0; k < count && !ShutdownRequested(); ++k) {
    const int64_t due_ns = start_ns + k * period_ns;
    std::this_thread::sleep_until(std::chrono::steady_clock::time_point(std::chrono::nanoseconds(due_ns)));
    const int64_t utime = utime0 + k * period_us;
    if (k % 2 == 0) {
      motor.utime = utime;
      motor.seq = static_cast<int32_t>(k / 2);
      for (int i = 0; i < 2; ++i) {
        motor.omega_cmd_rad_s[i] = kHoverOmegaRadS;
        motor.omega_meas_rad_s[i] = kHoverOmegaRadS;
      }
      EncodeMessage(motor, &motor_buffer);
      lcm->publish(channels.motor, motor_buffer.data(), static_cast<unsigned>(motor_buffer.size()));
    }
    if (through_controller) {
      // Level hover at the origin: the controller's inputs besides FORCE.
      imu.utime = utime;
      imu.seq = static_cast<int32_t>(k);
      imu.accel_z_m_s2 = 9.81;
      EncodeMessage(imu, &imu_buffer);
      lcm->publish(channels.imu, imu_buffer.data(), static_cast<unsigned>(imu_buffer.size()));
      if (k % 10 == 0) {
        pose.utime = utime;
        pose.seq = static_cast<int32_t>(k / 10);
        EncodeMessage(pose, &pose_buffer);
        lcm->publish(channels.pose, pose_buffer.data(), static_cast<unsigned>(pose_buffer.size()));
      }
    }
    strain.utime = utime;
    strain.seq = static_cast<int32_t>(k);
    // A small deterministic ripple (1e-6 rad) so the filter sees changing data.
    const double ripple_rad = 1e-6 * std::sin(0.01 * static_cast<double>(k));
    strain.deflection_rad[0] = -kHoverDeflectionRad + ripple_rad;
    strain.deflection_rad[1] = kHoverDeflectionRad + ripple_rad;
    EncodeMessage(strain, &strain_buffer);
    probe.publish_ns[k] = SteadyClockNs();
    lcm->publish(channels.strain, strain_buffer.data(), static_cast<unsigned>(strain_buffer.size()));
    ++published;
  }
  const double publish_s = static_cast<double>(SteadyClockNs() - start_ns) * 1e-9;
  std::this_thread::sleep_for(std::chrono::duration<double>(drain_s));
  stop_receiving = true;
  receiver.join();

  std::vector<int64_t> latencies;
  latencies.reserve(static_cast<size_t>(published));
  for (int64_t k = 0; k < published; ++k) {
    if (probe.latency_ns[k] >= 0) latencies.push_back(probe.latency_ns[k]);
  }
  std::sort(latencies.begin(), latencies.end());
  const int64_t dropped = published - static_cast<int64_t>(latencies.size());
  std::printf("url %s prefix %s: %" PRId64 " STRAIN published at %.0f Hz in %.2f s (achieved %.1f Hz)\n",
              common.lcm_url.c_str(), common.prefix.c_str(), published, rate_hz, publish_s,
              static_cast<double>(published) / publish_s);
  std::printf("FORCE received %zu, dropped (no FORCE) %" PRId64 ", unmatched %" PRId64 ", duplicates %" PRId64 "\n",
              latencies.size(), dropped, probe.unmatched.load(), probe.duplicates.load());
  if (source->udp_counters() != nullptr) std::printf("input: %s\n", UdpCountersText(source->udp_counters()).c_str());
  if (latencies.empty()) {
    return ReportError("no FORCE received on " + channels.force + " for " + std::to_string(published) +
                       " STRAIN published on " + channels.strain + ": is birotor-estimator running with --lcm-url " +
                       common.lcm_url + " --prefix " + common.prefix + "?");
  }
  std::printf("latency publish->FORCE [us]: %s\n", LatencyText(&latencies).c_str());
  if (through_controller) {
    std::vector<int64_t> command_latencies;
    for (int64_t k = 0; k < published; ++k) {
      if (probe.command_latency_ns[k] >= 0) command_latencies.push_back(probe.command_latency_ns[k]);
    }
    std::printf("MOTOR_COMMAND received %" PRId64 ", paired with a STRAIN %zu, unpaired %" PRId64 "\n",
                probe.commands.load(), command_latencies.size(), probe.commands_unmatched.load());
    if (command_latencies.empty()) {
      return ReportError("no MOTOR_COMMAND paired on " + channels.motor_command +
                         ": is birotor-controller running with --lcm-url " + common.lcm_url + " --prefix " +
                         common.prefix + "?");
    }
    std::printf("latency STRAIN publish->MOTOR_COMMAND [us]: %s\n", LatencyText(&command_latencies).c_str());
  }
  // 3: the figures are real but some samples got no FORCE (see "dropped").
  return dropped == 0 ? 0 : 3;
}

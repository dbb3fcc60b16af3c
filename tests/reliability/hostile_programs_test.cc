// Issue 23 item 1: every program that subscribes receives through the shared
// message source (sources/: on udpm our own LC02 reader), so the two LC03
// datagrams that crash LCM's reassembly and a 256 MB partial message on each
// of its channels leave it alive, with RSS growth under 20 MB, and the
// dropped fragments counted where the program says them (its log; the
// controller also in CONTROLLER_STATUS). One live program per test, on a
// private udpm port (ttl=0) and a prefix with the test's PID.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "birotor/controller_status_t.hpp"
#include "tests/reliability/live_harness.h"
#include "transport/udpm_receiver.h"

namespace birotor::reliability {
namespace {

// Fragments of the 256 MB message per channel: enough to hold LCM's
// reassembly buffer (it allocates the declared size) well above 20 MB.
constexpr int kFragmentsPerChannel = 500;

struct ProgramCase {
  std::string name;
  std::vector<std::string> argv;
  std::vector<std::string> channels;  // base names it subscribes to
};

std::string ReadFile(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Starts the program, attacks each of its channels, and checks that it
// lives, stays small and says what it dropped; returns its exit status
// after SIGTERM (-1: killed by a signal).
int AttackProgram(const ProgramCase& program, int port, const std::string& prefix) {
  const std::string log_path = TempPath(program.name + ".log");
  std::remove(log_path.c_str());
  ChildProcess child;
  EXPECT_TRUE(child.Start(program.argv, log_path));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // start-up
  EXPECT_TRUE(child.Alive()) << program.name << " did not start: " << ReadFile(log_path);
  const int64_t rss_before_kb = ResidentKb(child.pid());
  RawMulticastSender attacker(port);
  uint32_t seqno = 100;
  for (const std::string& channel : program.channels) {
    EXPECT_EQ(SendFragmentAttack(&attacker, prefix + channel, kFragmentsPerChannel, seqno), kFragmentsPerChannel + 2);
    seqno += 2;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // read, and a warning (1 per s)
  const int64_t rss_after_kb = ResidentKb(child.pid());
  std::printf("%s: RSS %lld kB -> %lld kB after the attack on %zu channels\n", program.name.c_str(),
              static_cast<long long>(rss_before_kb), static_cast<long long>(rss_after_kb), program.channels.size());
  EXPECT_TRUE(child.Alive()) << program.name << " died; log: " << ReadFile(log_path);
  EXPECT_GT(rss_before_kb, 0);
  EXPECT_LT(rss_after_kb - rss_before_kb, 20 * 1024) << program.name;  // issue 23 target
  const int status = child.Stop();
  const std::string log = ReadFile(log_path);
  EXPECT_NE(log.find("udp fragments dropped"), std::string::npos) << program.name << " log: " << log;
  EXPECT_EQ(log.find("udp fragments dropped 0,"), std::string::npos) << program.name << " log: " << log;
  return status;
}

TEST(HostileProgramsTest, ControllerSurvivesFragmentsAndCountsThemInItsStatus) {
  const int port = PrivatePort(7742);
  const std::string url = PrivateUrl(7742);
  const std::string prefix = UniquePrefix("REL_HOSTILE_CTRL_");
  UdpmUrl parsed;
  std::string error;
  ASSERT_TRUE(ParseUdpmUrl(url, &parsed, &error)) << error;
  UdpmReceiver status_reader;  // our own reader: the attack cannot hurt the test either
  ASSERT_TRUE(status_reader.Open(parsed, &error)) << error;
  const ProgramCase program{"controller",
                            {BIROTOR_CONTROLLER_BIN, "--lcm-url", url, "--prefix", prefix, "--status-rate-hz", "20"},
                            {"POSE", "IMU", "FORCE"}};
  std::atomic<bool> stop{false};
  std::atomic<int64_t> fragments_reported{0};
  const std::string status_channel = prefix + "CONTROLLER_STATUS";
  std::thread reader([&] {
    ReceivedDatagram datagram;
    controller_status_t status;
    while (!stop.load()) {
      if (!status_reader.Wait(0.02)) continue;
      while (status_reader.Receive(&datagram)) {
        if (datagram.packet.kind == LcmPacketKind::kSmallMessage && datagram.packet.channel == status_channel &&
            DecodeMessage(datagram.packet.payload, datagram.packet.payload_size, &status) == DecodeError::kNone) {
          fragments_reported = status.udp_fragments_dropped;
        }
      }
    }
  });
  EXPECT_EQ(AttackProgram(program, port, prefix), 0);
  stop = true;
  reader.join();
  EXPECT_GE(fragments_reported.load(), 2) << "CONTROLLER_STATUS udp_fragments_dropped";
}

TEST(HostileProgramsTest, SimulatorAsEscsSurvivesFragments) {
  const std::string url = PrivateUrl(7743);
  const std::string prefix = UniquePrefix("REL_HOSTILE_SIM_");
  std::vector<std::string> argv = SimCommand(url, prefix, 30.0);
  *(std::find(argv.begin(), argv.end(), "--log-level") + 1) = "info";  // the summary line with the counters
  argv.push_back("--external-controller");
  EXPECT_EQ(AttackProgram({"sim", argv, {"MOTOR_COMMAND"}}, PrivatePort(7743), prefix), 0);
}

TEST(HostileProgramsTest, MonitorSurvivesFragments) {
  const std::string url = PrivateUrl(7744);
  const std::string prefix = UniquePrefix("REL_HOSTILE_MON_");
  // Exit 1 after SIGTERM: no FORCE was received (there is no estimator).
  EXPECT_EQ(AttackProgram({"monitor",
                           {BIROTOR_MONITOR_BIN, "--lcm-url", url, "--prefix", prefix, "--quiet"},
                           {"TRUTH", "FORCE", "ESTIMATOR_STATUS"}},
                          PrivatePort(7744), prefix),
            1);
}

TEST(HostileProgramsTest, LatencyProbeSurvivesFragments) {
  const std::string url = PrivateUrl(7745);
  const std::string prefix = UniquePrefix("REL_HOSTILE_PROBE_");
  // Exit 1 after SIGTERM: no FORCE was received (there is no estimator).
  EXPECT_EQ(AttackProgram({"latency_probe",
                           {BIROTOR_LATENCY_PROBE_BIN, "--lcm-url", url, "--prefix", prefix, "--rate-hz", "100",
                            "--duration-s", "30", "--drain-s", "0", "--through-controller"},
                           {"FORCE", "MOTOR_COMMAND"}},
                          PrivatePort(7745), prefix),
            1);
}

TEST(HostileProgramsTest, SoakMonitorSurvivesFragments) {
  const std::string url = PrivateUrl(7746);
  const std::string prefix = UniquePrefix("REL_HOSTILE_SOAK_");
  // Exit 1 after SIGTERM: the soak targets fail (there is no estimator).
  EXPECT_EQ(AttackProgram({"soak_monitor",
                           {BIROTOR_SOAK_MONITOR_BIN, "--lcm-url", url, "--prefix", prefix, "--duration-s", "30",
                            "--interval-s", "1"},
                           {"STRAIN", "FORCE", "ESTIMATOR_STATUS"}},
                          PrivatePort(7746), prefix),
            1);
}

}  // namespace
}  // namespace birotor::reliability

// Issue 16, items 1, 3 and 11: hostile datagrams against a live
// birotor-estimator on a private udpm port (ttl=0, prefix with the test's
// PID). The daemon reads its inputs with its own LC02 reader; these tests
// send what crashed or bloated LCM's reassembly and check that the daemon
// survives, keeps publishing, stays small and counts what it dropped; and
// that ESTIMATOR_STATUS stays on schedule under a burst of strain packets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "birotor/strain_t.hpp"
#include "tests/reliability/live_harness.h"
#include "transport/udpm_receiver.h"

namespace birotor::reliability {
namespace {

std::vector<uint8_t> EncodedStrain(int64_t utime, int32_t seq) {
  strain_t strain{};
  strain.utime = utime;
  strain.seq = seq;
  strain.deflection_rad[0] = -0.0018664;  // hover deflection (tests/estimator equilibrium)
  strain.deflection_rad[1] = 0.0018664;
  std::vector<uint8_t> bytes;
  EncodeMessage(strain, &bytes);
  return bytes;
}

// Newest ESTIMATOR_STATUS, or one with seq -1.
estimator_status_t NewestStatus(DaemonListener* listener) {
  const std::vector<StatusRecord> statuses = listener->Statuses();
  if (statuses.empty()) {
    estimator_status_t none{};
    none.seq = -1;
    return none;
  }
  return statuses.back().message;
}

TEST(HostilePacketsTest, FragmentAttacksNeitherCrashNorBloatTheDaemonAndAreCounted) {
  const int port = PrivatePort(7683);
  const std::string url = PrivateUrl(7683);
  const std::string prefix = UniquePrefix("REL_HOSTILE_");
  DaemonListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  ChildProcess daemon;
  ASSERT_TRUE(daemon.Start(DaemonCommand(url, prefix), TempPath("hostile_daemon.log")));
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return NewestStatus(&listener).seq >= 1; }, 30.0))
      << "no ESTIMATOR_STATUS from the daemon";
  const int64_t rss_before_kb = ResidentKb(daemon.pid());

  RawMulticastSender attacker(port);
  // The two crash datagrams and 1500 fragments of a 256 MB message
  // (live_harness.h, SendFragmentAttack).
  const std::string channel = prefix + "STRAIN";
  const int sent = SendFragmentAttack(&attacker, channel, 1500, 77);
  ASSERT_EQ(sent, 1502);
  // 3. Malformed datagrams: unknown magic, LC02 without a NUL, empty channel.
  ASSERT_TRUE(attacker.Send({0xDE, 0xAD, 0xBE, 0xEF, 0, 0, 0, 1, 'A', 0, 1}));
  std::vector<uint8_t> unterminated = SmallMessageDatagram(channel, {}, 1);
  unterminated.pop_back();
  ASSERT_TRUE(attacker.Send(unterminated));
  ASSERT_TRUE(attacker.Send(SmallMessageDatagram("", {1, 2, 3}, 2)));

  // Still alive and publishing: honest strain samples after the attack get a
  // FORCE (sent once the daemon has had time to empty its socket buffer).
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  lcm::LCM publisher(url);
  ASSERT_TRUE(publisher.good());
  const double honest_s = SteadyClockS();
  for (int i = 0; i < 50; ++i) {
    const std::vector<uint8_t> strain = EncodedStrain(1000000 + 1000 * i, i);
    publisher.publish(channel, strain.data(), static_cast<unsigned>(strain.size()));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return listener.FirstForceWith(0, honest_s).arrival_s >= 0; }, 10.0))
      << "no FORCE after the attack";
  // The counters of a status published after everything was read.
  const double counted_s = SteadyClockS() + 0.2;
  ASSERT_TRUE(DaemonListener::WaitUntil(
      [&] {
        const std::vector<StatusRecord> statuses = listener.Statuses();
        return !statuses.empty() && statuses.back().arrival_s > counted_s;
      },
      10.0));
  const estimator_status_t status = NewestStatus(&listener);
  const int64_t rss_after_kb = ResidentKb(daemon.pid());
  std::printf(
      "after the attack: fragments dropped %lld, kernel dropped %lld, malformed %lld, datagrams %lld; "
      "RSS %lld kB -> %lld kB\n",
      static_cast<long long>(status.udp_fragments_dropped), static_cast<long long>(status.udp_kernel_dropped),
      static_cast<long long>(status.udp_malformed_dropped), static_cast<long long>(status.udp_datagrams),
      static_cast<long long>(rss_before_kb), static_cast<long long>(rss_after_kb));
  EXPECT_TRUE(daemon.Alive()) << "the daemon died (see " << TempPath("hostile_daemon.log") << ")";
  // Every fragment is accounted for: read and dropped, or dropped by the
  // kernel on the full socket buffer (which may also have dropped a few of
  // the daemon's own looped-back status messages: at most one per 50 ms).
  EXPECT_GE(status.udp_fragments_dropped + status.udp_kernel_dropped, 1502);
  EXPECT_LE(status.udp_fragments_dropped + status.udp_kernel_dropped, 1502 + 100);
  EXPECT_GE(status.udp_fragments_dropped, 2);
  EXPECT_EQ(status.udp_malformed_dropped, 3);
  // Issue 16 target: RSS under 20 MB after every attack.
  EXPECT_GT(rss_after_kb, 0);
  EXPECT_LT(rss_after_kb, 20 * 1024);
  EXPECT_EQ(status.inputs[0].received, 50);
  EXPECT_EQ(daemon.Stop(), 0);  // a clean exit on SIGTERM, not a signal death
}

// ESTIMATOR_STATUS keeps its 5 Hz schedule at any input rate. A 2 s burst of
// strain packets at 50 kHz from this process; the status messages' own
// wall_utime (the daemon's publication time) is read by our small-message
// reader, which keeps up with the burst. Asserted, as it holds on any machine:
// the status timer ran through the burst (at least half the statuses its
// period promises carry a publication time inside it), the daemon lives and
// stays small. The largest gap and the count off schedule are printed: how
// close to 200 ms they come depends on the cores the daemon gets (measured
// 205-209 ms at 49-50 kHz on an idle 2-core machine).
TEST(HostilePacketsTest, StatusKeepsComingThroughA50kHzBurst) {
  const int port = PrivatePort(7684);
  const std::string url = PrivateUrl(7684);
  const std::string prefix = UniquePrefix("REL_BURST_");
  const ChannelNames channels = MakeChannelNames(prefix);
  UdpmUrl parsed;
  std::string error;
  ASSERT_TRUE(ParseUdpmUrl(url, &parsed, &error)) << error;
  UdpmReceiver status_reader;
  ASSERT_TRUE(status_reader.Open(parsed, &error)) << error;
  std::vector<int64_t> status_wall_us;
  std::vector<int32_t> status_seq;
  std::atomic<bool> stop{false};
  std::thread reader([&] {
    ReceivedDatagram datagram;
    estimator_status_t status;
    while (!stop.load()) {
      if (!status_reader.Wait(0.02)) continue;
      while (status_reader.Receive(&datagram)) {
        if (datagram.packet.kind != LcmPacketKind::kSmallMessage ||
            datagram.packet.channel != channels.estimator_status) {
          continue;
        }
        if (DecodeMessage(datagram.packet.payload, datagram.packet.payload_size, &status) == DecodeError::kNone) {
          status_wall_us.push_back(status.wall_utime);
          status_seq.push_back(status.seq);
        }
      }
    }
  });
  ChildProcess daemon;
  ASSERT_TRUE(daemon.Start({BIROTOR_ESTIMATOR_BIN, "--lcm-url", url, "--prefix", prefix, "--status-rate-hz", "5",
                            "--realtime-priority", kEstimatorPriority},
                           TempPath("burst_daemon.log")));
  std::this_thread::sleep_for(std::chrono::milliseconds(800));

  // Every datagram encoded before the burst, sent in batches (sendmmsg) every
  // 0.5 ms: the sender's cost is the kernel's, so the daemon gets the cores.
  const double rate_hz = 50000;
  const double burst_s = 2.0;
  std::vector<std::vector<uint8_t>> packets(static_cast<size_t>(rate_hz * burst_s));
  for (size_t k = 0; k < packets.size(); ++k) {
    packets[k] = SmallMessageDatagram(channels.strain,
                                      EncodedStrain(1000000 + static_cast<int64_t>(k) * 20, static_cast<int32_t>(k)),
                                      static_cast<uint32_t>(k));
  }
  RawMulticastSender sender(port);
  const int64_t burst_start_wall_us = WallClockUs();
  const double start_s = SteadyClockS();
  size_t sent = 0;
  while (sent < packets.size() && SteadyClockS() - start_s < 2 * burst_s) {
    const size_t due = std::min(packets.size(), static_cast<size_t>((SteadyClockS() - start_s) * rate_hz));
    if (due > sent) sent += sender.SendBatch(packets, sent, due);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  const double burst_s_measured = SteadyClockS() - start_s;
  const int64_t burst_end_wall_us = WallClockUs();
  const double achieved_hz = static_cast<double>(sent) / burst_s_measured;
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  stop = true;
  reader.join();
  EXPECT_TRUE(daemon.Alive());
  const int64_t rss_kb = ResidentKb(daemon.pid());
  EXPECT_EQ(daemon.Stop(), 0);

  // At least half of the 16 the period promises over the burst and the 1.2 s
  // after it: this reader shares its socket buffer with the burst and, with
  // both cores busy beside the suite, received 14 (test-under-load).
  ASSERT_GE(status_wall_us.size(), 8u) << "expected about 5 status messages per second over 3.2 s";
  // Gaps between consecutive seq only: a status this reader missed (its own
  // socket buffer is shared with the burst) is not a late status.
  double max_gap_ms = 0;
  int off_schedule = 0, measured = 0;
  for (size_t i = 1; i < status_wall_us.size(); ++i) {
    if (status_seq[i] != status_seq[i - 1] + 1) continue;
    const double gap_ms = 1e-3 * static_cast<double>(status_wall_us[i] - status_wall_us[i - 1]);
    max_gap_ms = std::max(max_gap_ms, gap_ms);
    off_schedule += std::abs(gap_ms - 200.0) > 50.0 ? 1 : 0;
    ++measured;
  }
  std::printf(
      "burst: %zu strain packets at %.0f Hz; %zu status messages, %d gaps measured, largest %.1f ms, %d more than "
      "50 ms off the 200 ms period; daemon RSS %lld kB\n",
      sent, achieved_hz, status_wall_us.size(), measured, max_gap_ms, off_schedule, static_cast<long long>(rss_kb));
  int64_t during_burst = 0;
  for (int64_t wall_us : status_wall_us) during_burst += wall_us >= burst_start_wall_us && wall_us <= burst_end_wall_us;
  const double promised = burst_s_measured * 5.0;  // --status-rate-hz 5 over the burst as it lasted
  std::printf("burst lasted %.2f s: %lld status messages published inside it (the period promises %.1f)\n",
              burst_s_measured, static_cast<long long>(during_burst), promised);
  EXPECT_GE(static_cast<double>(during_burst), std::floor(0.5 * promised));
  EXPECT_GT(rss_kb, 0);
  EXPECT_LT(rss_kb, 20 * 1024);
}

}  // namespace
}  // namespace birotor::reliability

// Tests of sources/udpm_source.h on loopback multicast (ttl=0, a private port
// shifted by BIROTOR_TEST_PORT_OFFSET): only small messages of subscribed
// channels reach the handler, with the kernel's arrival stamp; fragments,
// malformed datagrams and other channels are taken and counted.
#include "sources/udpm_source.h"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "tests/sources/packet_recorder.h"
#include "tests/transport/raw_datagram.h"
#include "transport/host_clock.h"

namespace birotor {
namespace {

using testing::SendRaw;
using testing::TestPort;

std::vector<uint8_t> Small(const std::string& channel, std::vector<uint8_t> payload) {
  std::vector<uint8_t> packet = {0x4c, 0x43, 0x30, 0x32, 0, 0, 0, 1};  // LC02, seqno 1
  packet.insert(packet.end(), channel.begin(), channel.end());
  packet.push_back(0);
  packet.insert(packet.end(), payload.begin(), payload.end());
  return packet;
}

TEST(UdpmSourceTest, DeliversSubscribedSmallMessagesAndCountsTheRest) {
  const int port = TestPort(7740);
  UdpmUrl url;
  url.port = port;
  UdpmSource source;
  std::string error;
  ASSERT_TRUE(source.Open(url, &error)) << error;
  PacketRecorder recorder;
  ASSERT_TRUE(source.Subscribe({"SRC_STRAIN", "SRC_POSE"}, &recorder, &error));
  EXPECT_NE(source.udp_counters(), nullptr);

  const int64_t before_us = WallClockUs();
  SendRaw(port, Small("SRC_STRAIN", {1, 2, 3}));
  SendRaw(port, Small("SRC_OTHER", {4}));
  // An LC03 fragment header (fragment 0 of 2 of a 100-byte message) and garbage.
  SendRaw(port, {0x4c, 0x43, 0x30, 0x33, 0, 0, 0, 2, 0, 0, 0, 100, 0, 0, 0, 0, 0, 0, 0, 2, 'S', 0});
  SendRaw(port, {0xde, 0xad});
  SendRaw(port, Small("SRC_POSE", {}));
  int taken = 0;
  for (int turn = 0; turn < 100 && taken < 5; ++turn) {
    if (!source.Wait(0.02)) continue;
    while (source.DeliverOne()) ++taken;
  }
  EXPECT_EQ(taken, 5);
  ASSERT_EQ(recorder.packets.size(), 2u);
  EXPECT_EQ(recorder.packets[0].channel, "SRC_STRAIN");
  EXPECT_EQ(recorder.packets[0].bytes, (std::vector<uint8_t>{1, 2, 3}));
  EXPECT_GE(recorder.packets[0].receive_wall_utime, before_us);
  EXPECT_LE(recorder.packets[0].receive_wall_utime, WallClockUs());
  EXPECT_EQ(recorder.packets[1].channel, "SRC_POSE");
  EXPECT_TRUE(recorder.packets[1].bytes.empty());
  EXPECT_EQ(source.udp_counters()->datagrams, 5);
  EXPECT_EQ(source.udp_counters()->fragments_dropped, 1);
  EXPECT_EQ(source.udp_counters()->malformed_dropped, 1);
  EXPECT_EQ(source.other_channel(), 1);
  EXPECT_FALSE(source.DeliverOne());  // nothing left
}

}  // namespace
}  // namespace birotor

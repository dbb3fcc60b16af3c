// Tests of sources/lcm_source.h over memq:// (in-process LCM): subscribed
// channels reach the handler by their exact name, a prefix with regular
// expression characters matches only itself.
#include "sources/lcm_source.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "tests/sources/packet_recorder.h"

namespace birotor {
namespace {

TEST(LcmSourceTest, EscapesEverythingButLettersDigitsAndUnderscore) {
  EXPECT_EQ(ExactChannelRegex("BIROTOR_STRAIN"), "BIROTOR_STRAIN");
  EXPECT_EQ(ExactChannelRegex("A.B+C"), "A\\.B\\+C");
}

TEST(LcmSourceTest, DeliversExactlyTheSubscribedChannels) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  LcmSource source(&lcm);
  PacketRecorder recorder;
  std::string error;
  ASSERT_TRUE(source.Subscribe({"V.1_STRAIN"}, &recorder, &error)) << error;
  const uint8_t payload[] = {7, 8};
  lcm.publish("V.1_STRAIN", payload, 2);
  lcm.publish("VX1_STRAIN", payload, 2);  // '.' is not a wildcard
  lcm.publish("OTHER", payload, 1);
  EXPECT_TRUE(source.Wait(0.0));
  int taken = 0;
  while (source.DeliverOne()) ++taken;
  EXPECT_EQ(taken, 1);
  ASSERT_EQ(recorder.packets.size(), 1u);
  EXPECT_EQ(recorder.packets[0].channel, "V.1_STRAIN");
  EXPECT_EQ(recorder.packets[0].bytes, (std::vector<uint8_t>{7, 8}));
  EXPECT_GT(recorder.packets[0].receive_wall_utime, 0);
  EXPECT_FALSE(source.Wait(0.0));
  EXPECT_FALSE(source.finished());
  EXPECT_EQ(source.udp_counters(), nullptr);
}

}  // namespace
}  // namespace birotor

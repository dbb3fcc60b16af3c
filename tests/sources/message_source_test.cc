// Tests of sources/message_source.h's OpenLiveSource: udpm URLs get the own
// LC02 reader (with UDP counters), other providers LCM's subscription, a
// malformed udpm URL an error.
#include "sources/message_source.h"

#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>

namespace birotor {
namespace {

TEST(MessageSourceTest, UdpmUrlsGetTheOwnReaderAndOthersLcm) {
  std::string error;
  std::unique_ptr<MessageSource> udpm = OpenLiveSource("udpm://239.255.76.67:7741?ttl=0", nullptr, &error);
  ASSERT_NE(udpm, nullptr) << error;
  EXPECT_NE(udpm->udp_counters(), nullptr);
  EXPECT_EQ(udpm->Describe(), "own LC02 reader, fragments dropped");
  lcm::LCM lcm("memq://");
  std::unique_ptr<MessageSource> memq = OpenLiveSource("memq://", &lcm, &error);
  ASSERT_NE(memq, nullptr);
  EXPECT_EQ(memq->udp_counters(), nullptr);
  EXPECT_EQ(memq->Describe(), "LCM subscription");
}

TEST(MessageSourceTest, AMalformedUdpmUrlIsAnError) {
  std::string error;
  EXPECT_EQ(OpenLiveSource("udpm://239.255.76.67:99999", nullptr, &error), nullptr);
  EXPECT_NE(error.find("bad port"), std::string::npos) << error;
  EXPECT_EQ(OpenLiveSource("udpm://10.0.0.1:7667", nullptr, &error), nullptr);
  EXPECT_NE(error.find("not an IPv4 multicast"), std::string::npos) << error;
}

}  // namespace
}  // namespace birotor

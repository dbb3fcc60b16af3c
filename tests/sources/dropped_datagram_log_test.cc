// Tests of sources/dropped_datagram_log.h: the text of the counters, and a
// warning only when the fragment or malformed counts rose.
#include "sources/dropped_datagram_log.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

TEST(DroppedDatagramLogTest, SaysTheCounters) {
  UdpReceiveCounters counters;
  counters.fragments_dropped = 1502;
  counters.malformed_dropped = 3;
  counters.kernel_dropped = 7;
  EXPECT_EQ(UdpCountersText(&counters), "udp fragments dropped 1502, malformed 3, kernel drops 7");
  EXPECT_EQ(UdpCountersText(nullptr), "");
}

TEST(DroppedDatagramLogTest, WarnsOnlyWhenTheDropCountsRose) {
  DroppedDatagramLog log(0.0);
  UdpReceiveCounters counters;
  EXPECT_FALSE(log.Check(nullptr));
  EXPECT_FALSE(log.Check(&counters));
  counters.datagrams = 10;  // honest traffic says nothing
  EXPECT_FALSE(log.Check(&counters));
  counters.fragments_dropped = 2;
  EXPECT_TRUE(log.Check(&counters));
  EXPECT_FALSE(log.Check(&counters));
  counters.malformed_dropped = 1;
  EXPECT_TRUE(log.Check(&counters));
}

}  // namespace
}  // namespace birotor

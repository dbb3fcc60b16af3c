// The controller node's own clock (nodes/controller_service.h) against wild
// input stamps: the regression of the libFuzzer finding of
// controller_receive_fuzzer (a stamp of -1.2e184 us cast to int64_t, then a
// signed overflow in the clock's acquisition step).
#include "nodes/controller_service.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "birotor/pose_t.hpp"
#include "numerics/time_units.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

class DiscardSink : public MessageSink {
 public:
  void Publish(const std::string&, int64_t, const void*, size_t) override {}
};

std::vector<uint8_t> PoseStamped(int64_t utime) {
  pose_t pose{};
  pose.utime = utime;
  pose.seq = 1;
  std::vector<uint8_t> bytes;
  EncodeMessage(pose, &bytes);
  return bytes;
}

class ControllerClockTest : public ::testing::Test {
 protected:
  // Through the node's one way in, at host time host_us on its own clock.
  void Deliver(int64_t utime, int64_t host_us) {
    const std::vector<uint8_t> bytes = PoseStamped(utime);
    host_us_ = host_us;
    service_.HandlePacket(channels_.pose, bytes.data(), bytes.size(), -1);
  }
  DiscardSink sink_;
  int64_t host_us_ = 0;
  const ChannelNames channels_ = MakeChannelNames("TEST_");
  ControllerService service_{ControllerConfig{}, channels_, &sink_, [this] { return host_us_; }};
};

TEST_F(ControllerClockTest, AStampBeyondThePlausibleRangeNeverSetsTheClock) {
  Deliver(std::numeric_limits<int64_t>::max(), 5000000);
  Deliver(kLatestPlausibleUtime + 1, 5001000);
  EXPECT_EQ(service_.VehicleTimeUs(5002000), -1);
  Deliver(1000000, 5003000);  // an honest stamp sets it
  EXPECT_EQ(service_.VehicleTimeUs(5003000), 1000000);
}

TEST_F(ControllerClockTest, WildStampsDuringAcquisitionDoNotMoveTheClock) {
  Deliver(1000000, 5000000);
  ASSERT_EQ(service_.VehicleTimeUs(5000000), 1000000);
  for (const int64_t wild :
       {std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(), int64_t{-1}, kLatestPlausibleUtime}) {
    Deliver(wild, 5001000);
  }
  EXPECT_EQ(service_.VehicleTimeUs(5002000), 1002000);
}

// One route table: the subscription list is every channel the node reads.
TEST_F(ControllerClockTest, TheRouteTableIsTheSubscriptionList) {
  EXPECT_EQ(service_.InputChannels(),
            (std::vector<std::string>{"TEST_POSE", "TEST_IMU", "TEST_FORCE", "TEST_SETPOINT"}));
  const uint8_t garbage[3] = {1, 2, 3};
  service_.HandlePacket("TEST_IMU", garbage, sizeof(garbage), -1);
  service_.HandlePacket("TEST_TRUTH", garbage, sizeof(garbage), -1);  // not routed: not counted
  EXPECT_EQ(service_.decode_errors(ControllerInput::kImu), 1);
  EXPECT_EQ(service_.decode_errors(ControllerInput::kPose), 0);
}

}  // namespace
}  // namespace birotor

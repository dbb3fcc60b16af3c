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
  void Deliver(int64_t utime, int64_t host_us) {
    const std::vector<uint8_t> bytes = PoseStamped(utime);
    service_.HandlePacket(ControllerInput::kPose, bytes.data(), bytes.size(), host_us);
  }
  DiscardSink sink_;
  ControllerService service_{ControllerConfig{}, MakeChannelNames("TEST_"), &sink_};
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

}  // namespace
}  // namespace birotor

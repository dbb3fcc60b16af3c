// The controller node's own clock (nodes/controller_service.h) against wild
// input stamps: the regression of the libFuzzer finding of
// controller_receive_fuzzer (a stamp of -1.2e184 us cast to int64_t, then a
// signed overflow in the clock's acquisition step), and issue 37 item 3: a
// lone stream stamped +1000 s does not set the clock; two inputs that agree
// do.
#include "nodes/controller_service.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "birotor/force_estimate_t.hpp"
#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "numerics/time_units.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

// Counts what the node publishes on one channel.
class CountingSink : public MessageSink {
 public:
  explicit CountingSink(std::string channel) : channel_(std::move(channel)) {}
  void Publish(const std::string& channel, int64_t, const void*, size_t) override { count_ += channel == channel_; }
  int64_t count() const { return count_; }

 private:
  std::string channel_;
  int64_t count_ = 0;
};

std::vector<uint8_t> ImuStamped(int64_t utime, int32_t seq) {
  imu_t imu{};
  imu.utime = utime;
  imu.seq = seq;
  imu.accel_z_m_s2 = 9.81;  // hover: the specific force holds up the weight
  std::vector<uint8_t> bytes;
  EncodeMessage(imu, &bytes);
  return bytes;
}

std::vector<uint8_t> ForceStamped(int64_t utime, int32_t seq) {
  force_estimate_t force{};
  force.utime = utime;
  force.seq = seq;
  for (int i = 0; i < 2; ++i) {
    force.force_n[i] = 11.0;
    force.force_std_n[i] = 0.1;
    force.thrust_scale[i] = 1.0;
  }
  force.status = force_estimate_t::STATUS_VALID;
  std::vector<uint8_t> bytes;
  EncodeMessage(force, &bytes);
  return bytes;
}

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
  void Deliver(int64_t utime, int64_t host_us) { Send(channels_.pose, PoseStamped(utime), host_us); }
  void Send(const std::string& channel, const std::vector<uint8_t>& bytes, int64_t host_us) {
    host_us_ = host_us;
    service_.HandlePacket(channel, bytes.data(), bytes.size(), -1);
  }
  CountingSink sink_{"TEST_MOTOR_COMMAND"};
  int64_t host_us_ = 0;
  const ChannelNames channels_ = MakeChannelNames("TEST_");
  ControllerService service_{ControllerConfig{}, channels_, &sink_, [this] { return host_us_; }};
};

TEST_F(ControllerClockTest, AStampBeyondThePlausibleRangeNeverSetsTheClock) {
  Deliver(std::numeric_limits<int64_t>::max(), 5000000);
  Deliver(kLatestPlausibleUtime + 1, 5001000);
  EXPECT_EQ(service_.VehicleTimeUs(5002000), -1);
  Deliver(1000000, 5003000);  // an honest stamp alone does not set it
  EXPECT_EQ(service_.VehicleTimeUs(5003000), -1);
  Send(channels_.imu, ImuStamped(1000500, 1), 5003500);  // an IMU that agrees does
  EXPECT_EQ(service_.VehicleTimeUs(5003000), 1000000);
}

TEST_F(ControllerClockTest, WildStampsDuringAcquisitionDoNotMoveTheClock) {
  Deliver(1000000, 5000000);
  Send(channels_.imu, ImuStamped(1000000, 1), 5000000);
  ASSERT_EQ(service_.VehicleTimeUs(5000000), 1000000);
  for (const int64_t wild :
       {std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(), int64_t{-1}, kLatestPlausibleUtime}) {
    Deliver(wild, 5001000);
  }
  EXPECT_EQ(service_.VehicleTimeUs(5002000), 1002000);
}

TEST_F(ControllerClockTest, AFutureStampedImuStreamBeforeStartUpDoesNotSetTheClock) {
  // Vehicle time = host time - 4 s; a peer's IMU stream stamped +1000 s at
  // 1 kHz, alone for 0.1 s, then on with the real POSE (100 Hz), IMU and
  // FORCE (1 kHz) for 0.5 s.
  constexpr int64_t kVehicleMinusHostUs = -4000000;
  constexpr int64_t kBogusLeadUs = 1000000000;
  int64_t bogus_sent_after_real = 0;
  for (int32_t ms = 0; ms < 600; ++ms) {
    const int64_t host_us = 5000000 + 1000 * static_cast<int64_t>(ms);
    const int64_t vehicle_us = host_us + kVehicleMinusHostUs;
    Send(channels_.imu, ImuStamped(vehicle_us + kBogusLeadUs, 900000 + ms), host_us);
    if (ms < 100) {
      EXPECT_EQ(service_.VehicleTimeUs(host_us), -1);
      continue;
    }
    ++bogus_sent_after_real;
    if (ms % 10 == 0) Send(channels_.pose, PoseStamped(vehicle_us), host_us);
    Send(channels_.imu, ImuStamped(vehicle_us, ms), host_us + 100);
    Send(channels_.force, ForceStamped(vehicle_us, ms), host_us + 200);
    service_.RunIfDue(host_us + 300);
  }
  // The real time base (the POSE and IMU that agreed at 0.1 s), not +1000 s.
  EXPECT_EQ(service_.VehicleTimeUs(6000000), 6000000 + kVehicleMinusHostUs);
  // 500 Hz from the first POSE on the set clock to 0.6 s: 245 periods (the
  // POSE of 0.1 s came before the IMU that agreed with it and set the
  // clock, and was not delivered: the first is the one of 0.11 s).
  EXPECT_EQ(sink_.count(), 245);
  // Every bogus IMU once the clock was set (the one of the setting
  // millisecond, before it, not delivered).
  EXPECT_EQ(service_.health().imu.rejected_future, bogus_sent_after_real - 1);
  EXPECT_EQ(service_.clock_relatches(), 0);
}

TEST_F(ControllerClockTest, TheRelatchAfterSilenceNeedsTwoInputsThatAgree) {
  Deliver(1000000, 5000000);
  Send(channels_.imu, ImuStamped(1000000, 1), 5000000);
  ASSERT_EQ(service_.VehicleTimeUs(5000000), 1000000);
  // No input for 3 s (> kClockRelatchUs, 2 s), then a lone IMU stream
  // stamped +1000 s: the clock stays; it is refused as from the future.
  for (int32_t ms = 0; ms < 100; ++ms) {
    const int64_t host_us = 8000000 + 1000 * static_cast<int64_t>(ms);
    Send(channels_.imu, ImuStamped(host_us - 4000000 + 1000000000, 100 + ms), host_us);
  }
  EXPECT_EQ(service_.VehicleTimeUs(8100000), 4100000);
  EXPECT_EQ(service_.clock_relatches(), 0);
  EXPECT_EQ(service_.health().imu.rejected_future, 100);
  // A restarted vehicle clock (time base 0.5 s) heard on POSE and IMU: relatched.
  Deliver(500000, 8200000);
  Send(channels_.imu, ImuStamped(500000, 300), 8200000);
  EXPECT_EQ(service_.VehicleTimeUs(8200000), 500000);
  EXPECT_EQ(service_.clock_relatches(), 1);
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

// The simulator's trajectory as SETPOINT (Simulator::EmitSetpoints): one
// setpoint per 1 / rate_hz, stamped with the time it is meant for, carrying
// the scenario's reference with its feed-forward, and the same numbers after
// the wire message (setpoint_t) round trip.
#include <gtest/gtest.h>

#include <vector>

#include "simulator/scenario_yaml.h"
#include "simulator/simulator.h"
#include "sinks/wire_sample_sink.h"
#include "tests/simulator/test_support.h"
#include "transport/lcm_codec.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

struct SetpointSink : SampleSink {
  std::vector<Setpoint> setpoints;
  void OnSetpoint(const Setpoint& s) override { setpoints.push_back(s); }
};

struct BytesSink : MessageSink {
  std::vector<std::string> channels;
  std::vector<std::vector<uint8_t>> messages;
  void Publish(const std::string& channel, int64_t /*utime*/, const void* data, size_t size) override {
    channels.push_back(channel);
    const uint8_t* p = static_cast<const uint8_t*>(data);
    messages.emplace_back(p, p + size);
  }
};

TEST(SetpointPublishTest, TrajectoryAsSetpointsAtTheRate) {
  Scenario scenario = LoadScenario(ScenarioPath("gentle"));
  scenario.duration_s = 3.0;
  Simulator sim(scenario);
  sim.EmitSetpoints(100.0);
  SetpointSink sink;
  sim.Run(&sink);
  ASSERT_EQ(sink.setpoints.size(), 300u);  // 100 Hz for 3 s
  for (size_t k = 0; k < sink.setpoints.size(); ++k) {
    const Setpoint& s = sink.setpoints[k];
    ASSERT_EQ(s.utime, static_cast<int64_t>(k) * 10000);
    ASSERT_EQ(s.seq, static_cast<int32_t>(k));
    const ReferencePoint r = sim.ReferenceAt(1e-6 * static_cast<double>(s.utime));
    // The stamp in seconds and back rounds in the last bits.
    ASSERT_NEAR(s.x_m, r.position_m.x(), 1e-12);
    ASSERT_NEAR(s.z_dot_m_s, r.velocity_m_s.y(), 1e-12);
    ASSERT_NEAR(s.x_ddot_m_s2, r.acceleration_m_s2.x(), 1e-12);
  }
}

TEST(SetpointPublishTest, WireRoundTripKeepsEveryField) {
  BytesSink bytes;
  WireSampleSink wire(MakeChannelNames("P_"), &bytes);
  Setpoint s;
  s.utime = 123456;
  s.seq = -7;
  s.x_m = 1.5;
  s.z_m = -2.25;
  s.x_dot_m_s = 0.125;  // z_dot and the accelerations stay NaN (not given)
  wire.OnSetpoint(s);
  ASSERT_EQ(bytes.channels.size(), 1u);
  EXPECT_EQ(bytes.channels[0], "P_SETPOINT");
  setpoint_t message;
  ASSERT_EQ(DecodeMessage(bytes.messages[0].data(), bytes.messages[0].size(), &message), DecodeError::kNone);
  const Setpoint back = FromMessage(message);
  EXPECT_EQ(back.utime, 123456);
  EXPECT_EQ(back.seq, -7);
  EXPECT_EQ(back.x_m, 1.5);
  EXPECT_EQ(back.z_m, -2.25);
  EXPECT_EQ(back.x_dot_m_s, 0.125);
  EXPECT_TRUE(std::isnan(back.z_dot_m_s));
  EXPECT_TRUE(std::isnan(back.z_ddot_m_s2));
}

}  // namespace
}  // namespace birotor

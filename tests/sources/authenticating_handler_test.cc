// The authenticated channels end to end in memory: SigningSink (sinks/)
// seals what a publisher sends and sends the plain copy after it,
// AuthenticatingHandler (sources/) opens the sealed one for the node, drops
// the copy, and refuses and counts any other plain message on a required
// channel, a forged or replayed one; a channel the site lets through
// unsigned passes plain; other channels pass untouched.
#include "sources/authenticating_handler.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "birotor/imu_t.hpp"
#include "birotor/pose_t.hpp"
#include "sinks/signing_sink.h"
#include "tests/security/counting_key.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

// What reaches the node (or the bus).
struct Recorded {
  std::string channel;
  std::vector<uint8_t> data;
};
class Recorder : public PacketHandler, public MessageSink {
 public:
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t) override {
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    packets.push_back({std::string(channel), std::vector<uint8_t>(bytes, bytes + size)});
  }
  void Publish(const std::string& channel, int64_t, const void* data, size_t size) override {
    HandlePacket(channel, data, size, 0);
  }
  std::vector<Recorded> packets;
};

std::vector<uint8_t> PoseBytes(int32_t seq) {
  pose_t pose{};
  pose.utime = 1000 * seq;
  pose.seq = seq;
  pose.x_m = 0.25;
  std::vector<uint8_t> bytes;
  EncodeMessage(pose, &bytes);
  return bytes;
}

class AuthenticatingHandlerTest : public ::testing::Test {
 protected:
  void SendPose(int32_t seq) {
    const std::vector<uint8_t> bytes = PoseBytes(seq);
    signing_.Publish(channels_.pose, 0, bytes.data(), bytes.size());
  }
  // The bus's newest packet into the handler.
  void Deliver(const Recorded& packet) {
    handler_.HandlePacket(packet.channel, packet.data.data(), packet.data.size(), 0);
  }
  const AuthenticationCounters& pose() const { return handler_.counters(AuthenticatedChannel::kPose); }

  const ChannelNames channels_ = MakeChannelNames();
  const MessageAuthenticator authenticator_{CountingKeyFrom(1)};
  Recorder bus_;
  SigningSink signing_{&bus_, &authenticator_, channels_, ChannelSet{true, true, true, true}, 77};
  Recorder node_;
  AuthenticatingHandler handler_{&node_,
                                 SealedMessages::kVerify,
                                 &authenticator_,
                                 channels_,
                                 {AuthenticatedChannel::kPose, AuthenticatedChannel::kForce},
                                 ChannelSet{}};
};

TEST_F(AuthenticatingHandlerTest, ASealedMessageReachesTheNodeAsThePlainOneAndItsCopyIsDropped) {
  SendPose(1);
  ASSERT_EQ(bus_.packets.size(), 2u);
  EXPECT_EQ(bus_.packets[0].channel, "BIROTOR_POSE_AUTH");
  EXPECT_EQ(bus_.packets[1].channel, "BIROTOR_POSE");  // the plain copy, after it
  EXPECT_EQ(bus_.packets[1].data, PoseBytes(1));
  EXPECT_EQ(signing_.sealed(), 1);
  Deliver(bus_.packets[0]);
  Deliver(bus_.packets[1]);
  ASSERT_EQ(node_.packets.size(), 1u);
  EXPECT_EQ(node_.packets[0].channel, "BIROTOR_POSE");
  EXPECT_EQ(node_.packets[0].data, PoseBytes(1));
  EXPECT_EQ(pose().authenticated, 1);
  EXPECT_EQ(pose().plain_copies, 1);
  EXPECT_EQ(pose().unauthenticated, 0);
  EXPECT_EQ(handler_.WithSealedChannels({"BIROTOR_IMU"}),
            (std::vector<std::string>{"BIROTOR_IMU", "BIROTOR_POSE_AUTH", "BIROTOR_FORCE_AUTH"}));
}

TEST_F(AuthenticatingHandlerTest, PlainForgedAndReplayedMessagesAreRefusedAndCounted) {
  SendPose(1);
  SendPose(2);
  const Recorded first = bus_.packets[0];
  const Recorded second = bus_.packets[2];
  Deliver(first);
  Deliver(second);
  Deliver(first);   // a replay of an earlier message
  Deliver(second);  // and of the newest
  const std::vector<uint8_t> plain = PoseBytes(3);
  handler_.HandlePacket(channels_.pose, plain.data(), plain.size(), 0);  // a plain one on the required channel
  Recorded forged = second;
  forged.data[30] ^= 0x40;  // a changed byte in the message
  Deliver(forged);
  const MessageAuthenticator other(CountingKeyFrom(2));
  Recorder other_bus;
  SigningSink other_key(&other_bus, &other, channels_, ChannelSet{true, true, true, true}, 78);
  other_key.Publish(channels_.pose, 0, plain.data(), plain.size());
  Deliver(other_bus.packets[0]);  // sealed under another key
  Recorded cut = second;
  cut.data.resize(20);
  Deliver(cut);

  EXPECT_EQ(node_.packets.size(), 2u);
  EXPECT_EQ(pose().authenticated, 2);
  EXPECT_EQ(pose().replayed, 2);
  EXPECT_EQ(pose().unauthenticated, 3);
  EXPECT_EQ(pose().malformed, 1);
  EXPECT_EQ(pose().unsigned_accepted, 0);
  EXPECT_EQ(handler_.Summary(),
            "POSE: 2 accepted, 4 refused, 2 replayed, 0 unsigned accepted, 0 plain copies dropped; FORCE: 0 "
            "accepted, 0 refused, 0 replayed, 0 unsigned accepted, 0 plain copies dropped");
}

TEST_F(AuthenticatingHandlerTest, OtherChannelsPassAndAnUnsignedChannelTakesPlainMessages) {
  imu_t imu{};
  std::vector<uint8_t> bytes;
  EncodeMessage(imu, &bytes);
  handler_.HandlePacket(channels_.imu, bytes.data(), bytes.size(), 0);
  ASSERT_EQ(node_.packets.size(), 1u);
  EXPECT_EQ(node_.packets[0].channel, "BIROTOR_IMU");

  Recorder node;
  AuthenticatingHandler lenient(&node, SealedMessages::kVerify, &authenticator_, channels_,
                                {AuthenticatedChannel::kPose}, ChannelSet{false, false, true, false});
  const std::vector<uint8_t> plain = PoseBytes(5);
  lenient.HandlePacket(channels_.pose, plain.data(), plain.size(), 0);
  EXPECT_EQ(node.packets.size(), 1u);
  EXPECT_EQ(lenient.counters(AuthenticatedChannel::kPose).unsigned_accepted, 1);
}

TEST_F(AuthenticatingHandlerTest, WithoutAKeyNothingSealedIsTaken) {
  SendPose(1);
  Recorder node;
  AuthenticatingHandler keyless(&node, SealedMessages::kVerify, nullptr, channels_, {AuthenticatedChannel::kPose},
                                ChannelSet{false, false, true, false});
  Deliver(bus_.packets[0]);
  keyless.HandlePacket(bus_.packets[0].channel, bus_.packets[0].data.data(), bus_.packets[0].data.size(), 0);
  EXPECT_TRUE(node.packets.empty());
  EXPECT_EQ(keyless.counters(AuthenticatedChannel::kPose).unauthenticated, 1);
}

TEST_F(AuthenticatingHandlerTest, ADisplayToolOpensSealedMessagesWithoutTheKey) {
  SendPose(1);
  Recorder node;
  AuthenticatingHandler display(&node, SealedMessages::kOpenWithoutCheck, nullptr, channels_,
                                {AuthenticatedChannel::kPose}, ChannelSet{});
  display.HandlePacket(bus_.packets[0].channel, bus_.packets[0].data.data(), bus_.packets[0].data.size(), 0);
  const std::vector<uint8_t> plain = PoseBytes(2);
  display.HandlePacket(channels_.pose, plain.data(), plain.size(), 0);
  ASSERT_EQ(node.packets.size(), 2u);
  EXPECT_EQ(node.packets[0].data, PoseBytes(1));
}

TEST_F(AuthenticatingHandlerTest, TheSinkPassesOtherAndUnsignedChannelsPlain) {
  Recorder bus;
  SigningSink sink(&bus, &authenticator_, channels_, ChannelSet{true, false, false, true}, 5);
  const std::vector<uint8_t> pose = PoseBytes(1);
  sink.Publish(channels_.pose, 0, pose.data(), pose.size());   // POSE unsigned here
  sink.Publish(channels_.force, 0, pose.data(), pose.size());  // not a FORCE message: not published at all
  ASSERT_EQ(bus.packets.size(), 1u);
  EXPECT_EQ(bus.packets[0].channel, "BIROTOR_POSE");
  EXPECT_EQ(sink.seal_failures(), 1);
  EXPECT_EQ(sink.sealed(), 0);
}

}  // namespace
}  // namespace birotor

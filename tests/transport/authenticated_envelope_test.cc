// The sealed twins of the authenticated channels (transport/
// authenticated_envelope.h): sealing and opening are each other's inverse,
// the sealed bytes are what lcm-gen's own <type>_auth_t encodes and
// decodes, and a changed byte, another key or another type is refused.
#include "transport/authenticated_envelope.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "birotor/force_estimate_auth_t.hpp"
#include "birotor/force_estimate_n_auth_t.hpp"
#include "birotor/motor_command_auth_t.hpp"
#include "birotor/motor_command_n_auth_t.hpp"
#include "birotor/pose_auth_t.hpp"
#include "birotor/setpoint_auth_t.hpp"
#include "tests/security/counting_key.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

motor_command_t Command() {
  motor_command_t m{};
  m.utime = 1234567;
  m.seq = 42;
  m.omega_cmd_rad_s[0] = 611.5;
  m.omega_cmd_rad_s[1] = 612.25;
  m.mode = motor_command_t::MODE_FORCE_FEEDBACK;
  m.status = 0;
  return m;
}

class AuthenticatedEnvelopeTest : public ::testing::Test {
 protected:
  const ChannelNames channels_ = MakeChannelNames();
  const AuthenticatedChannelNames names_ = NamesOf(channels_, AuthenticatedChannel::kMotorCommand);
  const MessageAuthenticator authenticator_{CountingKeyFrom(1)};
  std::vector<uint8_t> Plain() const {
    std::vector<uint8_t> plain;
    EncodeMessage(Command(), &plain);
    return plain;
  }
  std::vector<uint8_t> Sealed(uint64_t counter = 9) const {
    const std::vector<uint8_t> plain = Plain();
    std::vector<uint8_t> sealed;
    EXPECT_TRUE(
        SealMessage(authenticator_, names_, 0x1122334455667788ull, counter, plain.data(), plain.size(), &sealed));
    return sealed;
  }
};

TEST_F(AuthenticatedEnvelopeTest, NamesAndTypesOfTheFourChannels) {
  EXPECT_EQ(names_.plain, "BIROTOR_MOTOR_COMMAND");
  EXPECT_EQ(names_.sealed, "BIROTOR_MOTOR_COMMAND_AUTH");
  EXPECT_EQ(names_.sealed_hash, static_cast<uint64_t>(motor_command_auth_t::getHash()));
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kSetpoint).sealed, "BIROTOR_SETPOINT_AUTH");
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kPose).sealed_hash, static_cast<uint64_t>(pose_auth_t::getHash()));
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kForce).sealed_hash,
            static_cast<uint64_t>(force_estimate_auth_t::getHash()));
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kForce).plain, "BIROTOR_FORCE");
}

// The N-arm twins: a variable-length message (n_rotors = 3) seals to
// lcm-gen's motor_command_n_auth_t and opens to the same bytes.
TEST_F(AuthenticatedEnvelopeTest, NArmTwinsSealToTheirAuthTypes) {
  const AuthenticatedChannelNames n = NamesOf(channels_, AuthenticatedChannel::kMotorCommandN);
  EXPECT_EQ(n.plain, "BIROTOR_MOTOR_COMMAND_N");
  EXPECT_EQ(n.sealed, "BIROTOR_MOTOR_COMMAND_N_AUTH");
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kForceN).sealed, "BIROTOR_FORCE_N_AUTH");
  EXPECT_EQ(NamesOf(channels_, AuthenticatedChannel::kForceN).sealed_hash,
            static_cast<uint64_t>(force_estimate_n_auth_t::getHash()));
  motor_command_n_t command{};
  command.utime = 777;
  command.seq = 5;
  command.n_rotors = 3;
  command.omega_cmd_rad_s = {500.0, 510.5, 520.25};
  std::vector<uint8_t> plain, sealed, opened;
  EncodeMessage(command, &plain);
  ASSERT_TRUE(SealMessage(authenticator_, n, 31, 4, plain.data(), plain.size(), &sealed));
  motor_command_n_auth_t decoded;
  ASSERT_EQ(DecodeMessage(sealed.data(), sealed.size(), &decoded), DecodeError::kNone);
  EXPECT_EQ(decoded.counter, 4);
  EXPECT_EQ(decoded.message.omega_cmd_rad_s[2], 520.25);
  uint64_t publisher = 0, counter = 0;
  ASSERT_EQ(OpenMessage(&authenticator_, n, sealed.data(), sealed.size(), &opened, &publisher, &counter),
            OpenVerdict::kAuthentic);
  EXPECT_EQ(opened, plain);
  sealed[30] ^= 1;  // inside the message: the tag no longer fits
  EXPECT_EQ(OpenMessage(&authenticator_, n, sealed.data(), sealed.size(), &opened, &publisher, &counter),
            OpenVerdict::kBadTag);
}

TEST_F(AuthenticatedEnvelopeTest, SealedBytesAreTheGeneratedAuthTypeAndOpenToThePlainMessage) {
  const std::vector<uint8_t> sealed = Sealed();
  EXPECT_EQ(sealed.size(), Plain().size() + kSealOverheadBytes);
  motor_command_auth_t decoded;
  ASSERT_EQ(DecodeMessage(sealed.data(), sealed.size(), &decoded), DecodeError::kNone);
  EXPECT_EQ(static_cast<uint64_t>(decoded.publisher), 0x1122334455667788ull);
  EXPECT_EQ(decoded.counter, 9);
  EXPECT_EQ(decoded.message.seq, 42);
  EXPECT_EQ(decoded.message.omega_cmd_rad_s[1], 612.25);
  // lcm-gen's encoder gives the same bytes (what lcm-spy and other languages read).
  std::vector<uint8_t> reencoded;
  EncodeMessage(decoded, &reencoded);
  EXPECT_EQ(reencoded, sealed);

  std::vector<uint8_t> plain;
  uint64_t publisher = 0, counter = 0;
  ASSERT_EQ(OpenMessage(&authenticator_, names_, sealed.data(), sealed.size(), &plain, &publisher, &counter),
            OpenVerdict::kAuthentic);
  EXPECT_EQ(plain, Plain());
  EXPECT_EQ(publisher, 0x1122334455667788ull);
  EXPECT_EQ(counter, 9u);
}

TEST_F(AuthenticatedEnvelopeTest, EveryChangedByteIsRefused) {
  const std::vector<uint8_t> sealed = Sealed();
  std::vector<uint8_t> plain;
  uint64_t publisher = 0, counter = 0;
  for (size_t i = 0; i < sealed.size(); ++i) {
    std::vector<uint8_t> altered = sealed;
    altered[i] ^= 0x01;
    const OpenVerdict verdict =
        OpenMessage(&authenticator_, names_, altered.data(), altered.size(), &plain, &publisher, &counter);
    EXPECT_NE(verdict, OpenVerdict::kAuthentic) << "byte " << i;
    EXPECT_TRUE(plain.empty());
  }
}

TEST_F(AuthenticatedEnvelopeTest, AnotherKeyAnotherTypeOrACutMessageIsRefused) {
  const std::vector<uint8_t> sealed = Sealed();
  std::vector<uint8_t> plain;
  uint64_t publisher = 0, counter = 0;
  const MessageAuthenticator other(CountingKeyFrom(2));
  EXPECT_EQ(OpenMessage(&other, names_, sealed.data(), sealed.size(), &plain, &publisher, &counter),
            OpenVerdict::kBadTag);
  const AuthenticatedChannelNames pose = NamesOf(channels_, AuthenticatedChannel::kPose);
  EXPECT_EQ(OpenMessage(&authenticator_, pose, sealed.data(), sealed.size(), &plain, &publisher, &counter),
            OpenVerdict::kMalformed);
  EXPECT_EQ(OpenMessage(&authenticator_, names_, sealed.data(), 40, &plain, &publisher, &counter),
            OpenVerdict::kMalformed);
  EXPECT_EQ(OpenMessage(&authenticator_, names_, sealed.data(), sealed.size() - 1, &plain, &publisher, &counter),
            OpenVerdict::kBadTag);
  const std::vector<uint8_t> zero_counter = Sealed(0);
  EXPECT_EQ(
      OpenMessage(&authenticator_, names_, zero_counter.data(), zero_counter.size(), &plain, &publisher, &counter),
      OpenVerdict::kMalformed);
  // Without a key (a tool reading a log) the tag is not checked.
  EXPECT_EQ(OpenMessage(nullptr, names_, sealed.data(), sealed.size(), &plain, &publisher, &counter),
            OpenVerdict::kAuthentic);
}

TEST_F(AuthenticatedEnvelopeTest, OnlyThePlainTypeIsSealed) {
  pose_t pose{};
  std::vector<uint8_t> bytes;
  EncodeMessage(pose, &bytes);
  std::vector<uint8_t> sealed;
  EXPECT_FALSE(SealMessage(authenticator_, names_, 1, 1, bytes.data(), bytes.size(), &sealed));
  EXPECT_TRUE(sealed.empty());
  EXPECT_FALSE(SealMessage(authenticator_, names_, 1, 1, bytes.data(), 4, &sealed));
}

TEST(ChannelSetTest, NamesAllNoneAndUnknown) {
  ChannelSet set{};
  std::string error;
  ASSERT_TRUE(ParseChannelSet("POSE,SETPOINT", &set, &error));
  EXPECT_EQ(set, (ChannelSet{false, true, true, false, false, false}));
  ASSERT_TRUE(ParseChannelSet("all", &set, &error));
  EXPECT_EQ(set, (ChannelSet{true, true, true, true, true, true}));
  ASSERT_TRUE(ParseChannelSet("FORCE_N,MOTOR_COMMAND_N", &set, &error));
  EXPECT_EQ(set, (ChannelSet{false, false, false, false, true, true}));
  ASSERT_TRUE(ParseChannelSet("none", &set, &error));
  EXPECT_EQ(set, (ChannelSet{}));
  EXPECT_FALSE(ParseChannelSet("POSE,IMU", &set, &error));
  EXPECT_EQ(
      error,
      "unknown channel 'IMU' (allowed: MOTOR_COMMAND, SETPOINT, POSE, FORCE, MOTOR_COMMAND_N, FORCE_N, all, none)");
}

}  // namespace
}  // namespace birotor

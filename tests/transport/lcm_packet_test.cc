// Tests of transport/lcm_packet.h: LC02 accepted only when well-formed, LC03
// always classified as a fragment, and the two packets of issue 16 item 1.
#include "transport/lcm_packet.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace birotor {
namespace {

void Put32(uint32_t value, std::vector<uint8_t>* out) {
  for (int i = 3; i >= 0; --i) out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

std::vector<uint8_t> SmallMessage(const std::string& channel, const std::vector<uint8_t>& payload, uint32_t seq = 7) {
  std::vector<uint8_t> packet;
  Put32(kLcmSmallMessageMagic, &packet);
  Put32(seq, &packet);
  packet.insert(packet.end(), channel.begin(), channel.end());
  packet.push_back(0);
  packet.insert(packet.end(), payload.begin(), payload.end());
  return packet;
}

LcmPacket Parse(const std::vector<uint8_t>& bytes) { return ParseLcmPacket(bytes.data(), bytes.size()); }

TEST(LcmPacketTest, SmallMessageGivesChannelAndPayload) {
  const std::vector<uint8_t> packet = SmallMessage("BIROTOR_STRAIN", {1, 2, 3});
  const LcmPacket parsed = Parse(packet);
  ASSERT_EQ(parsed.kind, LcmPacketKind::kSmallMessage);
  EXPECT_EQ(parsed.seqno, 7u);
  EXPECT_EQ(parsed.channel, "BIROTOR_STRAIN");
  ASSERT_EQ(parsed.payload_size, 3u);
  EXPECT_EQ(parsed.payload, packet.data() + 8 + 15);
  EXPECT_EQ(parsed.payload[2], 3);
  EXPECT_EQ(Parse(SmallMessage("X", {})).payload_size, 0u);
}

TEST(LcmPacketTest, BadChannelNamesAreMalformed) {
  EXPECT_EQ(Parse(SmallMessage("", {1})).kind, LcmPacketKind::kMalformed);
  EXPECT_EQ(Parse(SmallMessage(std::string(63, 'C'), {1})).kind, LcmPacketKind::kSmallMessage);
  EXPECT_EQ(Parse(SmallMessage(std::string(64, 'C'), {1})).kind, LcmPacketKind::kMalformed);
  EXPECT_EQ(Parse(SmallMessage("TAB\tNAME", {1})).kind, LcmPacketKind::kMalformed);
  // No NUL inside the datagram: nothing past it is read.
  std::vector<uint8_t> unterminated = SmallMessage("STRAIN", {});
  unterminated.pop_back();
  EXPECT_EQ(Parse(unterminated).kind, LcmPacketKind::kMalformed);
}

TEST(LcmPacketTest, ShortAndUnknownPacketsAreMalformed) {
  EXPECT_EQ(ParseLcmPacket(nullptr, 0).kind, LcmPacketKind::kMalformed);
  const std::vector<uint8_t> three = {0x4c, 0x43, 0x30};
  EXPECT_EQ(Parse(three).kind, LcmPacketKind::kMalformed);
  std::vector<uint8_t> header_only;
  Put32(kLcmSmallMessageMagic, &header_only);
  Put32(1, &header_only);
  EXPECT_EQ(Parse(header_only).kind, LcmPacketKind::kMalformed);
  std::vector<uint8_t> other;
  Put32(0x4c433031, &other);  // "LC01"
  Put32(1, &other);
  other.push_back('A');
  other.push_back(0);
  EXPECT_EQ(Parse(other).kind, LcmPacketKind::kMalformed);
}

// The reproducer of issue 16 item 1: fragment 1 carrying a channel name,
// then a 20-byte fragment 0 with offset 11. Both are fragments, nothing more.
TEST(LcmPacketTest, TheCrashingFragmentPairIsClassifiedAsFragments) {
  std::vector<uint8_t> first;
  Put32(kLcmFragmentMagic, &first);
  Put32(42, &first);   // seqno
  Put32(100, &first);  // msg_size
  Put32(0, &first);    // fragment_offset
  first.push_back(0);  // fragment_no = 1
  first.push_back(1);
  first.push_back(0);  // fragments_in_msg = 2
  first.push_back(2);
  const std::string name = "STRAIN";  // <= 10 bytes, so that LCM's offset check wraps
  first.insert(first.end(), name.begin(), name.end());
  first.push_back(0);
  std::vector<uint8_t> second;
  Put32(kLcmFragmentMagic, &second);
  Put32(42, &second);
  Put32(100, &second);
  Put32(11, &second);  // fragment_offset
  Put32(2, &second);   // fragment_no = 0, fragments_in_msg = 2
  ASSERT_EQ(second.size(), kLcmFragmentHeaderBytes);
  EXPECT_EQ(Parse(first).kind, LcmPacketKind::kFragment);
  EXPECT_EQ(Parse(first).seqno, 42u);
  EXPECT_EQ(Parse(second).kind, LcmPacketKind::kFragment);
  const std::vector<uint8_t> bare = {0x4c, 0x43, 0x30, 0x33};
  EXPECT_EQ(Parse(bare).kind, LcmPacketKind::kFragment);
}

}  // namespace
}  // namespace birotor

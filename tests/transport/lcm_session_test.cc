// Tests of transport/lcm_session.h: opening LCM, a real publish/handle round
// trip over memq://, and the receive-buffer report.
#include "transport/lcm_session.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "tests/transport/test_messages.h"
#include "transport/lcm_codec.h"

namespace birotor {
namespace {

TEST(OpenLcmTest, UnknownProviderGivesAnError) {
  std::string error;
  EXPECT_EQ(OpenLcm("bogus://x", &error), nullptr);
  EXPECT_NE(error.find("bogus://x"), std::string::npos) << error;
}

TEST(OpenLcmTest, MemqOpens) {
  std::string error;
  auto lcm = OpenLcm("memq://", &error);
  ASSERT_NE(lcm, nullptr) << error;
  EXPECT_TRUE(lcm->good());
}

struct RawReceiver {
  void Handle(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    const auto* data = static_cast<const uint8_t*>(buffer->data);
    channels.push_back(channel);
    packets.emplace_back(data, data + buffer->data_size);
  }
  std::vector<std::string> channels;
  std::vector<std::vector<uint8_t>> packets;
};

TEST(OpenLcmTest, PublishAndHandleOverMemq) {
  std::string error;
  auto lcm = OpenLcm("memq://", &error);
  ASSERT_NE(lcm, nullptr) << error;
  RawReceiver receiver;
  lcm->subscribe("BIROTOR_STRAIN", &RawReceiver::Handle, &receiver);

  EXPECT_EQ(HandleFor(*lcm, 0.01), 0);  // nothing published yet: timeout

  const strain_t sent = transport_test::MakeTestMessage<strain_t>();
  std::vector<uint8_t> bytes;
  EncodeMessage(sent, &bytes);
  ASSERT_EQ(lcm->publish("BIROTOR_STRAIN", bytes.data(), static_cast<unsigned>(bytes.size())), 0);
  ASSERT_EQ(lcm->publish("BIROTOR_MOTOR", bytes.data(), static_cast<unsigned>(bytes.size())), 0);
  EXPECT_GT(HandleFor(*lcm, 1.0), 0);
  HandleFor(*lcm, 0.0);  // the MOTOR packet, not subscribed

  ASSERT_EQ(receiver.packets.size(), 1u);
  EXPECT_EQ(receiver.channels[0], "BIROTOR_STRAIN");
  strain_t received{};
  ASSERT_EQ(DecodeMessage(receiver.packets[0].data(), receiver.packets[0].size(), &received), DecodeError::kNone);
  EXPECT_EQ(received.seq, sent.seq);
  EXPECT_EQ(received.deflection_rad[0], sent.deflection_rad[0]);
}

TEST(ReceiveBufferTest, ParsesTheUrlOption) {
  EXPECT_EQ(RequestedReceiveBuffer("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152"), 2097152);
  EXPECT_EQ(RequestedReceiveBuffer("udpm://239.255.76.67:7667?recv_buf_size=4096&ttl=0"), 4096);
  EXPECT_EQ(RequestedReceiveBuffer("udpm://239.255.76.67:7667?ttl=0"), std::nullopt);
  EXPECT_EQ(RequestedReceiveBuffer("udpm://239.255.76.67:7667"), std::nullopt);
  EXPECT_EQ(RequestedReceiveBuffer("udpm://h:1?recv_buf_size=big"), std::nullopt);
  EXPECT_EQ(RequestedReceiveBuffer("udpm://h:1?recv_buf_size=-5"), std::nullopt);
}

TEST(ReceiveBufferTest, RequestAboveTheKernelLimitSuggestsSysctl) {
  bool sufficient = true;
  const std::string report =
      ReceiveBufferReport("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152", 212992, &sufficient);
  EXPECT_FALSE(sufficient);
  EXPECT_EQ(report,
            "requested 2097152 B receive buffer; kernel rmem_max is 212992 B: raise it with "
            "sysctl -w net.core.rmem_max=2097152");
}

TEST(ReceiveBufferTest, RequestWithinTheLimitIsFine) {
  bool sufficient = false;
  const std::string report =
      ReceiveBufferReport("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152", 4194304, &sufficient);
  EXPECT_TRUE(sufficient);
  EXPECT_EQ(report, "requested 2097152 B receive buffer; kernel rmem_max is 4194304 B");
}

TEST(ReceiveBufferTest, OtherCases) {
  bool sufficient = false;
  EXPECT_NE(ReceiveBufferReport(kDefaultLcmUrl, 212992, &sufficient).find("no recv_buf_size"), std::string::npos);
  EXPECT_TRUE(sufficient);
  EXPECT_NE(ReceiveBufferReport("udpm://h:1?recv_buf_size=100", -1).find("unknown"), std::string::npos);
  EXPECT_EQ(ReceiveBufferReport("memq://", 212992), "LCM provider 'memq' uses no UDP receive buffer");
}

TEST(ReceiveBufferTest, ReadsRmemMaxFromAFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "lcm_session_test_rmem_max").string();
  std::ofstream(path) << "212992\n";
  EXPECT_EQ(ReadRmemMax(path), 212992);
  std::remove(path.c_str());
  EXPECT_EQ(ReadRmemMax(path), -1);
}

}  // namespace
}  // namespace birotor

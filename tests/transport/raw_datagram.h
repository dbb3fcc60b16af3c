// Test helpers for the UDP multicast receivers: the private test port (base
// shifted by BIROTOR_TEST_PORT_OFFSET) and a raw datagram sent to LCM's
// default group with ttl=0, as an attacker on the host would send it.
#pragma once

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

namespace birotor {
namespace testing {

inline int TestPort(int base) {
  const char* offset = std::getenv("BIROTOR_TEST_PORT_OFFSET");
  return base + (offset != nullptr ? std::atoi(offset) : 0);
}

inline void SendRaw(int port, const std::vector<uint8_t>& bytes) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  const unsigned char ttl = 0;
  setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl));
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  inet_pton(AF_INET, "239.255.76.67", &to.sin_addr);
  EXPECT_EQ(sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to)),
            static_cast<ssize_t>(bytes.size()));
  close(fd);
}

}  // namespace testing
}  // namespace birotor

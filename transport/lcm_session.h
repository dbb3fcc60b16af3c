// Opening an LCM instance with a clear error, a check of the UDP receive
// buffer against the kernel limit (1 kHz strain bursts overflow the default),
// and a handle-with-timeout wrapper in seconds.
#pragma once

#include <cstdint>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <string>

namespace birotor {

// LCM's own default: multicast that never leaves the host.
inline constexpr char kDefaultLcmUrl[] = "udpm://239.255.76.67:7667?ttl=0";

// Returns a working LCM instance, or nullptr and *error when the URL is
// malformed or its provider cannot be opened.
std::unique_ptr<lcm::LCM> OpenLcm(const std::string& url, std::string* error);

// Value of the recv_buf_size option of an LCM URL [bytes], if present and a
// positive integer.
std::optional<int64_t> RequestedReceiveBuffer(const std::string& url);

// Kernel limit on a socket receive buffer [bytes], read from
// /proc/sys/net/core/rmem_max (or path); -1 if unreadable.
int64_t ReadRmemMax(const std::string& path = "/proc/sys/net/core/rmem_max");

// One sentence on the receive buffer a udpm URL will get given the kernel
// limit rmem_max_bytes (-1 if unknown), with the sysctl fix when the request
// exceeds it. *sufficient (optional) is false only in that case.
std::string ReceiveBufferReport(const std::string& url, int64_t rmem_max_bytes, bool* sufficient = nullptr);

// Where a udpm URL ("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=N")
// sends and listens, with LCM's defaults for what it omits.
struct UdpmUrl {
  std::string group = "239.255.76.67";  // IPv4 multicast group
  int port = 7667;                      // UDP port
  int ttl = 0;                          // multicast time-to-live (0: this host only)
  int64_t recv_buf_size = 0;            // SO_RCVBUF request [bytes]; 0 keeps the kernel default
};

// Parses a udpm URL; false (with *error) for another provider, a malformed
// address or port, or an option value that is not a number.
bool ParseUdpmUrl(const std::string& url, UdpmUrl* parsed, std::string* error);

// lcm.handleTimeout with the timeout in seconds (clamped to >= 0). Returns >0
// if a message was handled, 0 on timeout, <0 on error.
int HandleFor(lcm::LCM& lcm, double timeout_s);

}  // namespace birotor

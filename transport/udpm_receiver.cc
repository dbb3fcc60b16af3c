// A stateless LC02 reader on a multicast UDP socket (Linux).
#include "transport/udpm_receiver.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

namespace birotor {
namespace {

// One byte more than the largest UDP payload over IPv4 (65507), so a
// datagram that fills it was truncated.
constexpr size_t kDatagramBufferBytes = 65536;

int64_t WallNowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

UdpmReceiver::UdpmReceiver() : buffer_(kDatagramBufferBytes) {}

UdpmReceiver::~UdpmReceiver() { Close(); }

void UdpmReceiver::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool UdpmReceiver::Open(const UdpmUrl& url, std::string* error) {
  Close();
  counters_ = UdpReceiveCounters();
  in_addr group{};
  if (inet_pton(AF_INET, url.group.c_str(), &group) != 1 || !IN_MULTICAST(ntohl(group.s_addr))) {
    *error = "udpm group '" + url.group.substr(0, 80) + "' is not an IPv4 multicast address";
    return false;
  }
  auto fail = [&](const char* what) {
    *error = std::string("udpm receiver: ") + what + ": " + std::strerror(errno);
    Close();
    return false;
  };
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) return fail("socket");
  const int one = 1;
  // Several receivers on one host (lcm-spy, lcm-logger, a second daemon).
  if (setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) != 0) return fail("SO_REUSEADDR");
  if (url.recv_buf_size > 0) {
    const int size = static_cast<int>(url.recv_buf_size);
    // Capped by net.core.rmem_max; the start-up log reports the limit.
    if (setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof(size)) != 0) return fail("SO_RCVBUF");
  }
  socklen_t length = sizeof(granted_buffer_bytes_);
  if (getsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &granted_buffer_bytes_, &length) != 0) granted_buffer_bytes_ = -1;
  // Kernel arrival stamps (what the overload guard measures queueing from)
  // and the count of datagrams the kernel dropped on a full buffer.
  if (setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof(one)) != 0) return fail("SO_TIMESTAMP");
  if (setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof(one)) != 0) return fail("SO_RXQ_OVFL");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr = group;  // as LCM on Linux: only this group's datagrams
  address.sin_port = htons(static_cast<uint16_t>(url.port));
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) return fail("bind");
  ip_mreq membership{};
  membership.imr_multiaddr = group;
  membership.imr_interface.s_addr = htonl(INADDR_ANY);
  if (setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof(membership)) != 0) {
    return fail("IP_ADD_MEMBERSHIP (without a network: ip route add 224.0.0.0/4 dev lo)");
  }
  return true;
}

bool UdpmReceiver::Wait(double timeout_s) {
  if (fd_ < 0) return false;
  pollfd entry{};
  entry.fd = fd_;
  entry.events = POLLIN;
  const double timeout_ms = std::isfinite(timeout_s) ? std::min(std::max(timeout_s * 1e3, 0.0), 1e6) : 0.0;
  return ::poll(&entry, 1, static_cast<int>(std::ceil(timeout_ms))) > 0 && (entry.revents & POLLIN) != 0;
}

bool UdpmReceiver::Receive(ReceivedDatagram* datagram) {
  if (fd_ < 0) return false;
  iovec io{};
  io.iov_base = buffer_.data();
  io.iov_len = buffer_.size();
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval)) + CMSG_SPACE(sizeof(uint32_t))];
  msghdr message{};
  message.msg_iov = &io;
  message.msg_iovlen = 1;
  message.msg_control = control;
  message.msg_controllen = sizeof(control);
  ssize_t size;
  do {
    size = ::recvmsg(fd_, &message, MSG_DONTWAIT);
  } while (size < 0 && errno == EINTR);
  if (size < 0) return false;
  ++counters_.datagrams;
  datagram->receive_wall_utime = -1;
  for (cmsghdr* c = CMSG_FIRSTHDR(&message); c != nullptr; c = CMSG_NXTHDR(&message, c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SCM_TIMESTAMP && c->cmsg_len >= CMSG_LEN(sizeof(timeval))) {
      timeval stamp;
      std::memcpy(&stamp, CMSG_DATA(c), sizeof(stamp));
      datagram->receive_wall_utime = int64_t{stamp.tv_sec} * 1000000 + stamp.tv_usec;
    } else if (c->cmsg_type == SO_RXQ_OVFL && c->cmsg_len >= CMSG_LEN(sizeof(uint32_t))) {
      uint32_t dropped;  // the socket's running total, wraps at 2^32
      std::memcpy(&dropped, CMSG_DATA(c), sizeof(dropped));
      counters_.kernel_dropped = dropped;
    }
  }
  if (datagram->receive_wall_utime < 0) datagram->receive_wall_utime = WallNowUs();
  if ((message.msg_flags & MSG_TRUNC) != 0 || static_cast<size_t>(size) >= buffer_.size()) {
    datagram->packet = LcmPacket();
    datagram->packet.problem = "datagram larger than 65507 bytes";
  } else {
    datagram->packet = ParseLcmPacket(buffer_.data(), static_cast<size_t>(size));
  }
  if (datagram->packet.kind == LcmPacketKind::kFragment) ++counters_.fragments_dropped;
  if (datagram->packet.kind == LcmPacketKind::kMalformed) ++counters_.malformed_dropped;
  return true;
}

}  // namespace birotor

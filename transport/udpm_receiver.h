// The estimator daemon's own receiver for LCM's UDP multicast transport: one
// socket joined to the group of a udpm URL (same group, port, SO_REUSEADDR and
// recv_buf_size as LCM, so lcm-spy and lcm-logger on the host still see every
// packet), reading small (LC02) messages only. Fragments (LC03) and malformed
// datagrams are counted and dropped without keeping any state, so no packet
// sequence can make it allocate, and the fragment-reassembly bug of LCM's own
// receiver (docs/lcm-udpm-fragment-bug.md) is out of reach.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "transport/lcm_packet.h"
#include "transport/lcm_session.h"

namespace birotor {

// What the receiver has read and dropped since Open, for ESTIMATOR_STATUS.
struct UdpReceiveCounters {
  int64_t datagrams = 0;          // datagrams read from the socket
  int64_t fragments_dropped = 0;  // LC03 fragments, never reassembled
  int64_t malformed_dropped = 0;  // too short, unknown magic, bad channel name, truncated
  // Datagrams the kernel discarded because the socket buffer was full
  // (SO_RXQ_OVFL); they never reached the daemon.
  int64_t kernel_dropped = 0;
};

// One datagram as read: the parsed packet (pointing into the receiver's
// buffer, valid until the next Receive) and its arrival time.
struct ReceivedDatagram {
  LcmPacket packet;
  int64_t receive_wall_utime = 0;  // kernel arrival stamp (SO_TIMESTAMP) [us since epoch]
};

class UdpmReceiver {
 public:
  UdpmReceiver();
  ~UdpmReceiver();
  UdpmReceiver(const UdpmReceiver&) = delete;
  UdpmReceiver& operator=(const UdpmReceiver&) = delete;

  // Opens and binds the socket and joins the group. False (with *error) when
  // the group is not an IPv4 multicast address or a socket call fails.
  bool Open(const UdpmUrl& url, std::string* error);
  void Close();

  // Waits up to timeout_s [s] for a datagram; true when one is ready.
  // False on timeout or when a signal interrupted the wait.
  bool Wait(double timeout_s);

  // Reads one queued datagram without blocking; false when none is queued.
  // Every datagram is counted; fragments and malformed ones come back with
  // their kind so the caller can skip them (they are already counted).
  bool Receive(ReceivedDatagram* datagram);

  const UdpReceiveCounters& counters() const { return counters_; }
  // SO_RCVBUF as granted by the kernel after Open [bytes] (twice the request,
  // the kernel's book-keeping), -1 before.
  int granted_buffer_bytes() const { return granted_buffer_bytes_; }

 private:
  int fd_ = -1;
  std::vector<uint8_t> buffer_;  // one datagram (UDP over IPv4: at most 65507 bytes)
  UdpReceiveCounters counters_;
  int granted_buffer_bytes_ = -1;
};

}  // namespace birotor

// The live source on udpm:// URLs: our own stateless LC02 reader
// (transport/udpm_receiver.h) with the subscribed channels filtered before
// the handler. LC03 fragments and malformed datagrams are counted by the
// reader and dropped, never reassembled (docs/lcm-udpm-fragment-bug.md).
#pragma once

#include <string>
#include <vector>

#include "sources/message_source.h"
#include "transport/lcm_session.h"
#include "transport/udpm_receiver.h"

namespace birotor {

// The routing step of UdpmSource on its own, for the fuzzers that feed the
// nodes datagrams from memory: a small message of one of channels goes to
// handler (true); a fragment, a malformed datagram or another channel does
// not (false).
bool RouteDatagram(const ReceivedDatagram& datagram, const std::vector<std::string>& channels, PacketHandler* handler);

class UdpmSource : public MessageSource {
 public:
  UdpmSource() = default;
  // Opens the socket on the URL's group and port; false (with *error) when
  // the group is not multicast or a socket call fails.
  bool Open(const UdpmUrl& url, std::string* error);

  bool Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* error) override;
  bool Wait(double timeout_s) override { return receiver_.Wait(timeout_s); }
  bool DeliverOne() override;
  const UdpReceiveCounters* udp_counters() const override { return &receiver_.counters(); }
  std::string Describe() const override { return "own LC02 reader, fragments dropped"; }

  // Small messages on channels nobody here subscribed to (other prefixes,
  // the program's own outputs looped back).
  int64_t other_channel() const { return other_channel_; }
  int granted_buffer_bytes() const { return receiver_.granted_buffer_bytes(); }

 private:
  UdpmReceiver receiver_;
  ReceivedDatagram datagram_;
  std::vector<std::string> channels_;
  PacketHandler* handler_ = nullptr;
  int64_t other_channel_ = 0;
};

}  // namespace birotor

// The one way in, as MessageSink (sinks/) is the one way out: a node
// implements PacketHandler, and a MessageSource feeds it complete encoded
// messages of the channels it asked for: live from udpm (our own LC02 reader,
// which never reassembles fragments), from LCM's own providers for other URLs
// (memq:// in tests), or from a log file (replay). The daemons, replay and the
// fuzzers all call the same HandlePacket, so every way in runs the same code.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "transport/udpm_receiver.h"

namespace lcm {
class LCM;
}

namespace birotor {

// What a node implements: one complete encoded message of one of the
// channels it subscribed to. channel is the full name (prefix included) and
// only valid during the call; receive_wall_utime is the host's arrival time
// [us since epoch] (kernel stamp on udpm, LCM's recv_utime otherwise, the
// logger's recorded time from a log), or -1 when unknown. Never throws.
class PacketHandler {
 public:
  virtual ~PacketHandler() = default;
  virtual void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) = 0;
};

// Where packets come from. Single-threaded: Wait and DeliverOne from one
// thread (the receive loop's).
class MessageSource {
 public:
  virtual ~MessageSource() = default;

  // Routes the messages of these channels (full names) to handler, which
  // must outlive the source; every other channel is dropped before it.
  // Replaces an earlier subscription. False (with *error) if the provider
  // refuses.
  virtual bool Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* error) = 0;

  // Waits up to timeout_s [s] until a packet is ready; false on timeout,
  // when a signal interrupted the wait, or at the end of a log.
  virtual bool Wait(double timeout_s) = 0;

  // Takes one ready packet without blocking and, when it is a message of a
  // subscribed channel, hands it to the handler. False when nothing was
  // ready. A fragment, a malformed datagram or another channel's message
  // counts as taken (true) without reaching the handler.
  virtual bool DeliverOne() = 0;

  // True once the source can deliver nothing more (end of a log, a failed
  // provider); error() then says why ("" at a normal end).
  virtual bool finished() const { return false; }
  virtual const std::string& error() const;

  // The UDP reader's counters (datagrams, fragments and malformed datagrams
  // dropped, kernel drops) when the source reads udpm itself; nullptr for
  // the other sources. Valid as long as the source.
  virtual const UdpReceiveCounters* udp_counters() const { return nullptr; }

  // One phrase for the start-up log ("own LC02 reader, fragments dropped").
  virtual std::string Describe() const = 0;
};

// The live source for an LCM URL: on udpm:// our own LC02 reader on the
// URL's group and port (lcm then only publishes: it opens no receive socket
// while nothing subscribes on it, so LCM's fragment reassembly,
// docs/lcm-udpm-fragment-bug.md, is never reached); on any other provider
// (memq://, file://) a subscription on lcm, which must outlive the source.
// nullptr with *error when the URL is malformed or the socket cannot be opened.
std::unique_ptr<MessageSource> OpenLiveSource(const std::string& url, lcm::LCM* lcm, std::string* error);

}  // namespace birotor

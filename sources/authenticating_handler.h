// The way in of an authenticated channel: a PacketHandler in front of a
// node's. A sealed message (<NAME>_AUTH, transport/authenticated_envelope.h)
// whose tag is right and whose counter is above the newest of its publisher
// reaches the node as the plain message on the plain channel, so the node
// keeps its one checked decoder. On a channel the site requires
// authenticated, a plain message is the copy a signing publisher sends after
// the sealed one (sinks/signing_sink.h) when it equals one of the last
// kRecentCopies messages opened on the channel: dropped, counted as a copy;
// any other plain message is refused. A forged, altered or replayed sealed
// message is refused. Each refusal is counted per channel. Every other
// channel passes unchanged. No allocation once the buffer has grown.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "security/message_authenticator.h"
#include "security/replay_guard.h"
#include "sources/message_source.h"
#include "transport/authenticated_envelope.h"

namespace birotor {

// Per authenticated channel, since start-up.
struct AuthenticationCounters {
  int64_t authenticated = 0;      // sealed, right tag, fresh counter: handed on
  int64_t unauthenticated = 0;    // plain message on a required channel, or a wrong tag: refused
  int64_t replayed = 0;           // right tag, counter not above its publisher's newest: refused
  int64_t malformed = 0;          // on the sealed channel but not a sealed message of its type: refused
  int64_t unsigned_accepted = 0;  // plain message on a channel the site lets through unsigned: handed on
  int64_t plain_copies = 0;       // plain copy of a message just accepted sealed: dropped (not news)
};

// What the handler does with a sealed message.
enum class SealedMessages {
  kVerify,            // check the tag with the site key and the counter (the daemons)
  kOpenWithoutCheck,  // hand on without checking (tools that display a log or the bus, without the key)
};

class AuthenticatingHandler : public PacketHandler {
 public:
  static constexpr int kRecentCopies = 8;  // opened messages remembered per channel for their plain copies

  // next and authenticator must outlive the handler. authenticator null
  // with kVerify: every sealed message is refused (no key to check it). routes: the channels of channels this node
  // reads; unsigned_allowed: those the site lets through plain.
  AuthenticatingHandler(PacketHandler* next, SealedMessages mode, const MessageAuthenticator* authenticator,
                        const ChannelNames& channels, const std::vector<AuthenticatedChannel>& routes,
                        const ChannelSet& unsigned_allowed);

  // What to subscribe a source to: the node's own channels and the sealed
  // names of the routes.
  std::vector<std::string> WithSealedChannels(std::vector<std::string> node_channels) const;
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override;

  // One line for a log: per channel read, its counters ("POSE: 912 accepted,
  // 0 refused, 0 replayed, 0 unsigned accepted; ...").
  std::string Summary() const;

  const AuthenticationCounters& counters(AuthenticatedChannel channel) const {
    return counters_[static_cast<int>(channel)];
  }

 private:
  struct Route {
    AuthenticatedChannelNames names;
    AuthenticatedChannel channel;
    bool unsigned_allowed = false;
    ReplayGuard guard;
    std::array<uint64_t, kRecentCopies> recent{};  // FNV-1a of the last opened messages (0: none)
    int next_recent = 0;
  };
  void HandlePlain(Route* route, std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime);
  void HandleSealed(Route* route, const void* data, size_t size, int64_t receive_wall_utime);

  PacketHandler* next_;
  SealedMessages mode_;
  const MessageAuthenticator* authenticator_;
  std::vector<Route> routes_;
  std::array<AuthenticationCounters, kNumAuthenticatedChannels> counters_{};
  std::vector<uint8_t> buffer_;
};

}  // namespace birotor

#include "sources/authenticating_handler.h"

#include "numerics/fnv1a.h"

namespace birotor {

AuthenticatingHandler::AuthenticatingHandler(PacketHandler* next, SealedMessages mode,
                                             const MessageAuthenticator* authenticator, const ChannelNames& channels,
                                             const std::vector<AuthenticatedChannel>& routes,
                                             const ChannelSet& unsigned_allowed)
    : next_(next), mode_(mode), authenticator_(authenticator) {
  for (const AuthenticatedChannel channel : routes) {
    Route route;
    route.names = NamesOf(channels, channel);
    route.channel = channel;
    route.unsigned_allowed = mode == SealedMessages::kOpenWithoutCheck || unsigned_allowed[static_cast<int>(channel)];
    routes_.push_back(route);
  }
  buffer_.reserve(512);
}

std::vector<std::string> AuthenticatingHandler::WithSealedChannels(std::vector<std::string> node_channels) const {
  for (const Route& route : routes_) node_channels.push_back(route.names.sealed);
  return node_channels;
}

std::string AuthenticatingHandler::Summary() const {
  std::string text;
  for (const Route& route : routes_) {
    const AuthenticationCounters& c = counters_[static_cast<int>(route.channel)];
    if (!text.empty()) text += "; ";
    text += std::string(route.names.base) + ": " + std::to_string(c.authenticated) + " accepted, " +
            std::to_string(c.unauthenticated + c.malformed) + " refused, " + std::to_string(c.replayed) +
            " replayed, " + std::to_string(c.unsigned_accepted) + " unsigned accepted, " +
            std::to_string(c.plain_copies) + " plain copies dropped";
  }
  return text;
}

void AuthenticatingHandler::HandlePacket(std::string_view channel, const void* data, size_t size,
                                         int64_t receive_wall_utime) {
  for (Route& route : routes_) {
    if (channel == route.names.sealed) {
      HandleSealed(&route, data, size, receive_wall_utime);
      return;
    }
    if (channel == route.names.plain) {
      HandlePlain(&route, channel, data, size, receive_wall_utime);
      return;
    }
  }
  next_->HandlePacket(channel, data, size, receive_wall_utime);
}

void AuthenticatingHandler::HandlePlain(Route* route, std::string_view channel, const void* data, size_t size,
                                        int64_t receive_wall_utime) {
  AuthenticationCounters& counters = counters_[static_cast<int>(route->channel)];
  const uint64_t digest = Fnv1a64(data, size);
  for (const uint64_t recent : route->recent) {
    if (recent == digest) {
      ++counters.plain_copies;  // the copy of a message the node already has
      return;
    }
  }
  if (!route->unsigned_allowed) {
    ++counters.unauthenticated;
    return;
  }
  ++counters.unsigned_accepted;
  next_->HandlePacket(channel, data, size, receive_wall_utime);
}

void AuthenticatingHandler::HandleSealed(Route* route, const void* data, size_t size, int64_t receive_wall_utime) {
  AuthenticationCounters& counters = counters_[static_cast<int>(route->channel)];
  if (mode_ == SealedMessages::kVerify && authenticator_ == nullptr) {
    ++counters.unauthenticated;  // no key: nothing sealed can be verified
    return;
  }
  const MessageAuthenticator* check = mode_ == SealedMessages::kVerify ? authenticator_ : nullptr;
  uint64_t publisher = 0;
  uint64_t counter = 0;
  const OpenVerdict verdict =
      OpenMessage(check, route->names, static_cast<const uint8_t*>(data), size, &buffer_, &publisher, &counter);
  if (verdict == OpenVerdict::kMalformed) {
    ++counters.malformed;
    return;
  }
  if (verdict == OpenVerdict::kBadTag) {
    ++counters.unauthenticated;
    return;
  }
  if (mode_ == SealedMessages::kVerify && !route->guard.Admit(publisher, counter)) {
    ++counters.replayed;
    return;
  }
  ++counters.authenticated;
  route->recent[route->next_recent] = Fnv1a64(buffer_.data(), buffer_.size());
  route->next_recent = (route->next_recent + 1) % kRecentCopies;
  next_->HandlePacket(route->names.plain, buffer_.data(), buffer_.size(), receive_wall_utime);
}

}  // namespace birotor

#include "sinks/signing_sink.h"

namespace birotor {

SigningSink::SigningSink(MessageSink* next, const MessageAuthenticator* authenticator, const ChannelNames& channels,
                         const ChannelSet& signed_channels, uint64_t publisher)
    : next_(next), authenticator_(authenticator), publisher_(publisher) {
  for (int i = 0; i < kNumAuthenticatedChannels; ++i) {
    if (signed_channels[i]) routes_.push_back(NamesOf(channels, static_cast<AuthenticatedChannel>(i)));
  }
  buffer_.reserve(512);
}

void SigningSink::Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) {
  for (const AuthenticatedChannelNames& route : routes_) {
    if (channel != route.plain) continue;
    if (!SealMessage(*authenticator_, route, publisher_, counter_ + 1, static_cast<const uint8_t*>(data), size,
                     &buffer_)) {
      ++seal_failures_;  // not the channel's type: not published at all
      return;
    }
    ++counter_;
    next_->Publish(route.sealed, timestamp_us, buffer_.data(), buffer_.size());
    next_->Publish(channel, timestamp_us, data, size);  // the plain copy, after the sealed one
    return;
  }
  next_->Publish(channel, timestamp_us, data, size);
}

}  // namespace birotor

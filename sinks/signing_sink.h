// The way out of an authenticated channel: a MessageSink in front of another
// that publishes each message of a signed channel as its sealed twin
// (transport/authenticated_envelope.h) on <NAME>_AUTH, under this
// publisher's random identity and its counter (1, 2, ... over every sealed
// message it publishes), and then the message itself on <NAME>, the plain
// copy the wire contract promises its readers (lcm-spy, loggers, programs
// that do not fly the vehicle). Receivers that fly take the sealed one and
// drop the copy (sources/authenticating_handler.h). Messages of other
// channels, and of a channel the site lets through unsigned, pass
// unchanged. No allocation once its buffer has grown to the largest message.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "security/message_authenticator.h"
#include "sinks/message_sink.h"
#include "transport/authenticated_envelope.h"

namespace birotor {

class SigningSink : public MessageSink {
 public:
  // next and authenticator must outlive the sink. signed_channels: the
  // channels sealed (the others pass unchanged); publisher: this
  // publisher's identity (RandomPublisherId() in a program).
  SigningSink(MessageSink* next, const MessageAuthenticator* authenticator, const ChannelNames& channels,
              const ChannelSet& signed_channels, uint64_t publisher);

  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override;

  uint64_t publisher() const { return publisher_; }
  int64_t sealed() const { return static_cast<int64_t>(counter_); }  // messages sealed so far
  int64_t seal_failures() const { return seal_failures_; }  // a message of a signed channel that was not its type

 private:
  MessageSink* next_;
  const MessageAuthenticator* authenticator_;
  std::vector<AuthenticatedChannelNames> routes_;
  uint64_t publisher_;
  uint64_t counter_ = 0;
  int64_t seal_failures_ = 0;
  std::vector<uint8_t> buffer_;
};

}  // namespace birotor

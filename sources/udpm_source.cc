// Small messages of the own udpm reader to the handler.
#include "sources/udpm_source.h"

#include <algorithm>

namespace birotor {

bool UdpmSource::Open(const UdpmUrl& url, std::string* error) { return receiver_.Open(url, error); }

bool UdpmSource::Subscribe(const std::vector<std::string>& channels, PacketHandler* handler, std::string* /*error*/) {
  channels_ = channels;
  handler_ = handler;
  return true;
}

bool UdpmSource::DeliverOne() {
  if (!receiver_.Receive(&datagram_)) return false;
  const LcmPacket& packet = datagram_.packet;
  if (packet.kind != LcmPacketKind::kSmallMessage) return true;  // counted by the reader
  const bool subscribed = std::find(channels_.begin(), channels_.end(), packet.channel) != channels_.end();
  if (!subscribed || handler_ == nullptr) {
    ++other_channel_;
    return true;
  }
  handler_->HandlePacket(packet.channel, packet.payload, packet.payload_size, datagram_.receive_wall_utime);
  return true;
}

}  // namespace birotor

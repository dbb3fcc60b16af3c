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

bool RouteDatagram(const ReceivedDatagram& datagram, const std::vector<std::string>& channels, PacketHandler* handler) {
  const LcmPacket& packet = datagram.packet;
  if (packet.kind != LcmPacketKind::kSmallMessage || handler == nullptr) return false;
  if (std::find(channels.begin(), channels.end(), packet.channel) == channels.end()) return false;
  handler->HandlePacket(packet.channel, packet.payload, packet.payload_size, datagram.receive_wall_utime);
  return true;
}

bool UdpmSource::DeliverOne() {
  if (!receiver_.Receive(&datagram_)) return false;
  // Fragments and malformed datagrams are counted by the reader.
  if (!RouteDatagram(datagram_, channels_, handler_) && datagram_.packet.kind == LcmPacketKind::kSmallMessage) {
    ++other_channel_;
  }
  return true;
}

}  // namespace birotor

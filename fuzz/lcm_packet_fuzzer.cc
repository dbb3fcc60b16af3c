// libFuzzer harness for the daemon's UDP datagram parser (transport/
// lcm_packet.h, used by its own LC02 reader): any datagram is classified
// without reading outside it, and an accepted small message's channel and
// payload lie inside the datagram and add up to its size.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "transport/lcm_packet.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // An exact-size heap copy, so AddressSanitizer sees any read past the end.
  std::vector<uint8_t> datagram(data, data + size);
  const birotor::LcmPacket packet = birotor::ParseLcmPacket(datagram.data(), datagram.size());
  if (packet.kind != birotor::LcmPacketKind::kSmallMessage) return 0;
  const uint8_t* begin = datagram.data();
  const uint8_t* end = begin + datagram.size();
  const auto* channel = reinterpret_cast<const uint8_t*>(packet.channel.data());
  if (packet.channel.empty() || packet.channel.size() > birotor::kLcmMaxChannelBytes) std::abort();
  if (channel != begin + birotor::kLcmSmallHeaderBytes) std::abort();
  if (channel[packet.channel.size()] != 0) std::abort();
  if (packet.payload != channel + packet.channel.size() + 1 || packet.payload + packet.payload_size != end) {
    std::abort();
  }
  if (std::memchr(packet.channel.data(), 0, packet.channel.size()) != nullptr) std::abort();
  return 0;
}

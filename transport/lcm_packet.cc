// Bounds-checked parsing of LCM udpm datagrams.
#include "transport/lcm_packet.h"

#include <cstring>

namespace birotor {
namespace {

uint32_t ReadBigEndian32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}

LcmPacket Malformed(const char* problem) {
  LcmPacket packet;
  packet.kind = LcmPacketKind::kMalformed;
  packet.problem = problem;
  return packet;
}

}  // namespace

LcmPacket ParseLcmPacket(const uint8_t* data, size_t size) {
  if (data == nullptr || size < 4) return Malformed("shorter than the 4-byte magic");
  const uint32_t magic = ReadBigEndian32(data);
  if (magic == kLcmFragmentMagic) {
    // Dropped whatever it holds: the daemon's inputs never need fragments,
    // and reassembly is where LCM 1.3-1.5 overflows (lcm_udpm.c).
    LcmPacket packet;
    packet.kind = LcmPacketKind::kFragment;
    if (size >= 8) packet.seqno = ReadBigEndian32(data + 4);
    return packet;
  }
  if (magic != kLcmSmallMessageMagic) return Malformed("unknown magic");
  if (size < kLcmSmallHeaderBytes + 2) return Malformed("LC02 packet shorter than its header and a channel");
  const auto* name = reinterpret_cast<const char*>(data + kLcmSmallHeaderBytes);
  const size_t room = size - kLcmSmallHeaderBytes;
  // Search for the NUL only inside the datagram and within the name limit + 1.
  const size_t search = room < kLcmMaxChannelBytes + 1 ? room : kLcmMaxChannelBytes + 1;
  const void* nul = std::memchr(name, '\0', search);
  if (nul == nullptr) return Malformed("LC02 channel name unterminated or longer than 63 bytes");
  const size_t length = static_cast<size_t>(static_cast<const char*>(nul) - name);
  if (length == 0) return Malformed("LC02 channel name empty");
  for (size_t i = 0; i < length; ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    if (c < 0x21 || c > 0x7e) return Malformed("LC02 channel name not printable ASCII");
  }
  LcmPacket packet;
  packet.kind = LcmPacketKind::kSmallMessage;
  packet.seqno = ReadBigEndian32(data + 4);
  packet.channel = std::string_view(name, length);
  packet.payload = data + kLcmSmallHeaderBytes + length + 1;
  packet.payload_size = room - length - 1;
  return packet;
}

}  // namespace birotor

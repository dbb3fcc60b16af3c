// The two datagram formats of LCM's UDP multicast transport (udpm), parsed
// without trusting a single byte: LC02, one whole message in one datagram, and
// LC03, one fragment of a larger message. The estimator daemon's inputs are
// small messages (< 1 kB), so its reader accepts LC02 only and counts LC03
// fragments as dropped instead of reassembling them (see docs/reliability.md,
// "Fragment defence").
//
//   LC02: u32 magic 0x4c433032 | u32 seqno | channel, NUL-terminated | payload
//   LC03: u32 magic 0x4c433033 | u32 seqno | u32 msg_size | u32 fragment_offset
//         | u16 fragment_no | u16 fragments_in_msg | [fragment 0: channel NUL] | data
// All integers big-endian.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace birotor {

inline constexpr uint32_t kLcmSmallMessageMagic = 0x4c433032;  // "LC02"
inline constexpr uint32_t kLcmFragmentMagic = 0x4c433033;      // "LC03"
inline constexpr size_t kLcmSmallHeaderBytes = 8;              // magic + seqno
inline constexpr size_t kLcmFragmentHeaderBytes = 20;
// LCM_MAX_CHANNEL_NAME_LENGTH: longest channel name, without the NUL.
inline constexpr size_t kLcmMaxChannelBytes = 63;

enum class LcmPacketKind {
  kSmallMessage,  // a complete LC02 message: channel and payload are set
  kFragment,      // an LC03 fragment (well-formed header or not): never reassembled
  kMalformed,     // anything else: too short, unknown magic, bad channel name
};

// A parsed datagram. channel and payload point into the caller's buffer.
struct LcmPacket {
  LcmPacketKind kind = LcmPacketKind::kMalformed;
  uint32_t seqno = 0;
  std::string_view channel;
  const uint8_t* payload = nullptr;
  size_t payload_size = 0;
  const char* problem = "";  // why a packet is kMalformed (static string)
};

// Classifies one datagram of `size` bytes. An LC02 message is accepted only if
// its channel name is 1..63 bytes of printable ASCII terminated by a NUL inside
// the datagram; the payload is every byte after the NUL (may be empty).
// Reads only data[0, size). Never allocates, never throws.
LcmPacket ParseLcmPacket(const uint8_t* data, size_t size);

}  // namespace birotor

// Shared by the receive-path fuzzers (controller_receive_fuzzer,
// esc_receive_fuzzer): the fuzz input as a sequence of UDP datagrams, each
// parsed by the daemons' own LC02 parser (transport/lcm_packet.h) and routed
// by the udpm source's own RouteDatagram (sources/udpm_source.h), so the
// whole receive path below the socket runs: raw bytes, LC02 or LC03 headers
// around fuzzed channels, and well-formed messages with fuzzed fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "sources/udpm_source.h"
#include "transport/lcm_packet.h"

namespace birotor::fuzz {

// Consumes the input front to back; zeros past its end.
struct ByteReader {
  const uint8_t* data;
  size_t size;
  size_t offset = 0;
  uint8_t Byte() { return offset < size ? data[offset++] : 0; }
  bool done() const { return offset >= size; }
  // Up to n bytes as they are.
  std::vector<uint8_t> Bytes(size_t n) {
    const size_t available = n < size - offset ? n : size - offset;
    std::vector<uint8_t> out(data + offset, data + offset + available);
    offset += available;
    return out;
  }
  uint64_t AnyBits() {
    uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits = (bits << 8) | Byte();
    return bits;
  }
  // Any 64-bit stamp, wild ones included (a double cast would be undefined
  // outside int64_t's range: the harness must not be the one misbehaving).
  int64_t AnyInt64() {
    const uint64_t bits = AnyBits();
    int64_t value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  double AnyDouble() {
    const uint64_t bits = AnyBits();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
};

inline void PutBigEndian32(uint32_t value, std::vector<uint8_t>* out) {
  for (int i = 3; i >= 0; --i) out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// One datagram from the input: kind 0 raw bytes; 1 an LC02 header around a
// channel (one of channels, or garbage) and a raw payload; 2 an LC03
// fragment header around the same; 3 an LC02 message on channels[i] with
// `payload` (a well-formed encoded message the harness built).
inline std::vector<uint8_t> NextDatagram(ByteReader* in, const std::vector<std::string>& channels,
                                         const std::vector<uint8_t>& payload) {
  const uint8_t kind = in->Byte() % 4;
  const size_t length = in->Byte();
  if (kind == 0) return in->Bytes(length);
  std::vector<uint8_t> datagram;
  PutBigEndian32(kind == 2 ? kLcmFragmentMagic : kLcmSmallMessageMagic, &datagram);
  PutBigEndian32(in->Byte(), &datagram);  // seqno
  if (kind == 2) {
    for (int i = 0; i < 12; ++i) datagram.push_back(in->Byte());  // size, offset, numbers
  }
  const uint8_t pick = in->Byte();
  if (pick < 200 && !channels.empty()) {
    const std::string& channel = channels[pick % channels.size()];
    datagram.insert(datagram.end(), channel.begin(), channel.end());
    datagram.push_back(0);
  } else {
    const std::vector<uint8_t> name = in->Bytes(pick % 80);
    datagram.insert(datagram.end(), name.begin(), name.end());
    if (pick % 2 == 0) datagram.push_back(0);
  }
  const std::vector<uint8_t> body = kind == 3 ? payload : in->Bytes(length);
  datagram.insert(datagram.end(), body.begin(), body.end());
  return datagram;
}

// Parses and routes one datagram as UdpmSource does; true if it reached the handler.
inline bool Deliver(const std::vector<uint8_t>& datagram, int64_t receive_wall_utime,
                    const std::vector<std::string>& channels, PacketHandler* handler) {
  ReceivedDatagram received;
  received.packet = ParseLcmPacket(datagram.data(), datagram.size());
  received.receive_wall_utime = receive_wall_utime;
  return RouteDatagram(received, channels, handler);
}

}  // namespace birotor::fuzz

// A PacketHandler that records what it is given, for the tests of sources/.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sources/message_source.h"

namespace birotor {

struct RecordedPacket {
  std::string channel;
  std::vector<uint8_t> bytes;
  int64_t receive_wall_utime = 0;
};

class PacketRecorder : public PacketHandler {
 public:
  void HandlePacket(std::string_view channel, const void* data, size_t size, int64_t receive_wall_utime) override {
    const uint8_t* bytes = static_cast<const uint8_t*>(data);
    packets.push_back({std::string(channel), std::vector<uint8_t>(bytes, bytes + size), receive_wall_utime});
  }
  std::vector<RecordedPacket> packets;
};

}  // namespace birotor

// Rate-limited warnings about dropped datagrams.
#include "sources/dropped_datagram_log.h"

#include <spdlog/spdlog.h>

#include "transport/host_clock.h"

namespace birotor {

std::string UdpCountersText(const UdpReceiveCounters* counters) {
  if (counters == nullptr) return "";
  return "udp fragments dropped " + std::to_string(counters->fragments_dropped) + ", malformed " +
         std::to_string(counters->malformed_dropped) + ", kernel drops " + std::to_string(counters->kernel_dropped);
}

bool DroppedDatagramLog::Check(const UdpReceiveCounters* counters) {
  if (counters == nullptr) return false;
  if (counters->fragments_dropped == fragments_said_ && counters->malformed_dropped == malformed_said_) return false;
  if (!limit_.ShouldLog(SteadyClockUs())) return false;
  spdlog::warn("{} (LCM fragments are never reassembled: our messages fit one datagram)", UdpCountersText(counters));
  fragments_said_ = counters->fragments_dropped;
  malformed_said_ = counters->malformed_dropped;
  return true;
}

}  // namespace birotor

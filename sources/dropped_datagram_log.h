// What the programs without a status message of their own (birotor-sim,
// birotor-monitor, birotor-latency-probe, birotor-soak-monitor) say about
// dropped datagrams: a warning, at most one per interval, when the UDP
// reader's fragment or malformed counts rose, and the totals as text for
// their summary line.
#pragma once

#include <cstdint>
#include <string>

#include "program/logging.h"
#include "transport/udpm_receiver.h"

namespace birotor {

// "udp fragments dropped F, malformed M, kernel drops K" ("" for nullptr: a
// source that reads no UDP itself).
std::string UdpCountersText(const UdpReceiveCounters* counters);

class DroppedDatagramLog {
 public:
  explicit DroppedDatagramLog(double interval_s = 1.0) : limit_(interval_s) {}
  // Warns when counters (nullptr: nothing to say) show more fragments or
  // malformed datagrams than at the last warning. Returns true if it warned.
  bool Check(const UdpReceiveCounters* counters);

 private:
  RateLimitedLog limit_;
  int64_t fragments_said_ = 0;
  int64_t malformed_said_ = 0;
};

}  // namespace birotor

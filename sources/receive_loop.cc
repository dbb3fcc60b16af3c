// The shared receive loop.
#include "sources/receive_loop.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>

#include "numerics/time_units.h"
#include "program/shutdown.h"
#include "sources/dropped_datagram_log.h"
#include "transport/host_clock.h"

namespace birotor {

int64_t ReceiveUntil(MessageSource* source, double wait_s, int64_t until_us) {
  int64_t taken = 0;
  if (!source->Wait(wait_s)) return 0;
  // At least one packet per turn, so a node whose deadline is always due
  // still gets its input.
  while (source->DeliverOne()) {
    ++taken;
    if (ShutdownRequested() || SteadyClockUs() >= until_us) break;
  }
  return taken;
}

bool RunReceiveLoop(MessageSource* source, const PeriodicWork& work, const ReceiveLoopOptions& options) {
  DroppedDatagramLog dropped;
  int64_t deadline_us = work(SteadyClockUs());
  while (!ShutdownRequested() && !source->finished()) {
    const double wait_s = std::clamp(ElapsedSeconds(deadline_us, SteadyClockUs()), 0.0, options.max_wait_s);
    ReceiveUntil(source, wait_s, deadline_us);
    // Also after packets: one may have moved the node's deadline (the first
    // POSE makes the controller's first period due at once).
    deadline_us = work(SteadyClockUs());
    dropped.Check(source->udp_counters());
    const std::string signals = TakeIgnoredSignalReport();
    if (!signals.empty()) spdlog::info("{} (no meaning for this program)", signals);
  }
  return source->error().empty();
}

}  // namespace birotor

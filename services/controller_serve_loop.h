// The controller daemon's serving loop, for the birotor's node and the
// N-rotor one alike (services/birotor_controller_main.cc,
// birotor_controller_vehicle.cc): control periods on the node's own timer,
// CONTROLLER_STATUS on a fixed grid of the host clock.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "deploy/systemd_notify.h"
#include "sources/message_source.h"
#include "sources/receive_loop.h"
#include "transport/host_clock.h"

namespace birotor {

// Serves until a signal or a failed source; false if the source failed.
template <class Service>
bool ServeController(MessageSource* source, double status_rate_hz, Service* service) {
  const int64_t status_period_us = std::llround(1e6 / status_rate_hz);
  int64_t next_status_us = SteadyClockUs() + status_period_us;
  NotifyReady();  // systemd Type=notify: serving now
  const bool source_ok = RunReceiveLoop(source, [&](int64_t now_us) {
    NotifyWatchdog();  // WatchdogSec: this loop is alive
    service->RunIfDue(now_us);
    if (now_us >= next_status_us) {
      service->PublishStatus(WallClockUs(), now_us);
      next_status_us += status_period_us;
      if (next_status_us <= now_us) next_status_us = now_us + status_period_us;  // a stall longer than a period
    }
    return std::min(service->NextPeriodHostUs(), next_status_us);
  });
  NotifyStopping();
  return source_ok;
}

}  // namespace birotor

// The estimator daemon's serving loop, for the birotor's node and the N-arm
// one alike (services/birotor_estimator_main.cc, birotor_estimator_vehicle.cc).
#pragma once

#include <cmath>
#include <cstdint>

#include "deploy/systemd_notify.h"
#include "sources/message_source.h"
#include "sources/receive_loop.h"
#include "transport/host_clock.h"

namespace birotor {

// Serves until a signal or a failed source; false if the source failed.
// ESTIMATOR_STATUS on a fixed grid of the host clock. The loop hands packets
// over until the next status is due and never past it, so the status stays
// on time at any input rate (a backlog waits in the socket, and the overload
// guard sheds what waited too long).
template <class Service>
bool ServeEstimator(MessageSource* source, double status_rate_hz, Service* service) {
  const int64_t status_period_us = std::llround(1e6 / status_rate_hz);
  int64_t last_status_us = SteadyClockUs();
  int64_t next_status_us = last_status_us + status_period_us;
  NotifyReady();  // systemd Type=notify: serving now
  const bool source_ok = RunReceiveLoop(source, [&](int64_t now_us) {
    NotifyWatchdog();  // WatchdogSec: this loop is alive
    if (now_us >= next_status_us) {
      service->PublishStatus(WallClockUs(), 1e-6 * static_cast<double>(now_us - last_status_us));
      last_status_us = now_us;
      next_status_us += status_period_us;
      if (next_status_us <= now_us) next_status_us = now_us + status_period_us;  // a stall longer than a period
    }
    return next_status_us;
  });
  NotifyStopping();
  return source_ok;
}

}  // namespace birotor

#include "deploy/systemd_notify.h"

#include <systemd/sd-daemon.h>

#include <chrono>

namespace birotor {
namespace {

// Written once by NotifyReady, read by the main loop's thread only.
int64_t watchdog_period_us = 0;
int64_t last_watchdog_us = 0;

int64_t SteadyNowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

bool NotifyReady() {
  uint64_t period_us = 0;
  // sd_watchdog_enabled: > 0 with the period when this process is meant to pet it.
  watchdog_period_us = sd_watchdog_enabled(0, &period_us) > 0 ? static_cast<int64_t>(period_us) : 0;
  last_watchdog_us = SteadyNowUs();
  return sd_notify(0, "READY=1") > 0;
}

bool NotifyWatchdogAt(int64_t now_us) {
  if (watchdog_period_us <= 0 || now_us - last_watchdog_us < watchdog_period_us / 2) return false;
  last_watchdog_us = now_us;
  return sd_notify(0, "WATCHDOG=1") > 0;
}

bool NotifyWatchdog() { return watchdog_period_us > 0 && NotifyWatchdogAt(SteadyNowUs()); }

void NotifyStopping() { sd_notify(0, "STOPPING=1"); }

int64_t WatchdogPeriodUs() { return watchdog_period_us; }

}  // namespace birotor

// The daemons' side of a systemd Type=notify unit with WatchdogSec=
// (deploy/*.service.in): READY=1 once the daemon serves, WATCHDOG=1 from its
// main loop, STOPPING=1 on the way out, through libsystemd's sd_notify.
// Started by hand or in a test (no NOTIFY_SOCKET) every call does nothing.
#pragma once

#include <cstdint>

namespace birotor {

// Sends READY=1 and reads the watchdog period systemd asked for
// (WATCHDOG_USEC). Returns true when a message went to systemd.
bool NotifyReady();

// Sends WATCHDOG=1 when half the watchdog period has passed since the last
// one (so a loop may call it every iteration: a clock read, no allocation,
// no system call in between). Call it only from the loop that does the work,
// so a stuck loop gets the daemon restarted. Returns true when one was sent.
bool NotifyWatchdog();

// Same with the host steady clock now_us given (tests).
bool NotifyWatchdogAt(int64_t now_us);

// Sends STOPPING=1 (the daemon is shutting down on SIGTERM).
void NotifyStopping();

// The watchdog period read by NotifyReady [us]; 0 when there is none.
int64_t WatchdogPeriodUs();

}  // namespace birotor

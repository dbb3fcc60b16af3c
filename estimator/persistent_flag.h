// A flag with persistence, as the rotor-fault monitors raise their flags: it
// goes on once `raise` held for persistence_us without a break, and off at
// the first `lower`. Shared by the birotor's RotorFaultMonitor and the
// N-rotor MultiArmFaultMonitor.
#pragma once

#include <cstdint>

namespace birotor {

struct PersistentFlag {
  bool on = false;
  int64_t since_utime = -1;  // start of the current `raise` run [us]; -1 if none

  void Update(bool raise, bool lower, int64_t utime, int64_t persistence_us) {
    if (!on) {
      if (!raise) {
        since_utime = -1;
        return;
      }
      if (since_utime < 0) since_utime = utime;
      if (utime - since_utime >= persistence_us) on = true;
    } else if (lower) {
      on = false;
      since_utime = -1;
    }
  }
};

}  // namespace birotor

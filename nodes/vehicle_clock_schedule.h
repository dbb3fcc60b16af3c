// When replay publishes ESTIMATOR_STATUS: each time the vehicle clock (the
// newest sample's utime) crosses a multiple of the status period, so a
// replay's output depends on the log only, never on the host clock. Shared
// by the birotor's and the N-arm estimator node.
#pragma once

#include <cmath>
#include <cstdint>

namespace birotor {

class VehicleClockSchedule {
 public:
  // True when a status is due at now_utime [us] with rate_hz [Hz]; *period_s
  // then gets the period it covers [s]. The first sample, or a clock that
  // went back more than a period (a log played in a loop), restarts the
  // schedule one period later; a gap longer than a period gives one status.
  bool Due(int64_t now_utime, double rate_hz, double* period_s) {
    if (now_utime < 0 || !(rate_hz > 0)) return false;
    const int64_t period_us = static_cast<int64_t>(std::llround(1e6 / rate_hz));
    if (next_utime_ < 0 || now_utime < next_utime_ - period_us) {
      next_utime_ = now_utime + period_us;
      return false;
    }
    if (now_utime < next_utime_) return false;
    next_utime_ += period_us;
    if (next_utime_ <= now_utime) next_utime_ = now_utime + period_us;  // a long gap
    *period_s = static_cast<double>(period_us) * 1e-6;
    return true;
  }

 private:
  int64_t next_utime_ = -1;  // [us]
};

}  // namespace birotor

// What the estimator nodes (the birotor's and the N-arm one) judge from the
// host time a live strain packet arrived: the overload guard (a packet that
// waited longer than overload_max_delay_s between arrival and processing is
// shed, with a rate-limited warning, so a backlog does not grow) and whether
// strain stopped arriving (no packet for stale_input_wall_s: INPUT_STALE on
// ESTIMATOR_STATUS). Replay and the lock-step loop give no arrival time
// (-1): nothing is shed and nothing goes stale.
#pragma once

#include <spdlog/spdlog.h>

#include <cstdint>

#include "program/logging.h"
#include "transport/host_clock.h"

namespace birotor {

class StrainArrivalGuard {
 public:
  StrainArrivalGuard(double overload_max_delay_s, double stale_input_wall_s, double warning_interval_s)
      : overload_max_delay_s_(overload_max_delay_s),
        stale_input_wall_s_(stale_input_wall_s),
        overload_warning_(warning_interval_s) {}

  // A strain packet (seq, for the warning) that arrived at
  // receive_wall_utime [us since epoch; -1: unknown]: true when it waited
  // too long and is to be shed (the caller counts it).
  bool Shed(int64_t receive_wall_utime, int32_t seq) {
    if (receive_wall_utime < 0) return false;
    last_arrival_wall_us_ = receive_wall_utime;
    const int64_t queued_us = WallClockUs() - receive_wall_utime;
    if (!(static_cast<double>(queued_us) > overload_max_delay_s_ * 1e6)) return false;
    if (overload_warning_.ShouldLog(SteadyClockUs())) {
      spdlog::warn("overload: strain sample {} waited {} us, dropped; {} similar suppressed", seq, queued_us,
                   overload_warning_.suppressed());
    }
    return true;
  }
  // No live strain packet for stale_input_wall_s before wall_utime [us].
  bool Stale(int64_t wall_utime) const {
    return last_arrival_wall_us_ >= 0 &&
           static_cast<double>(wall_utime - last_arrival_wall_us_) > stale_input_wall_s_ * 1e6;
  }

 private:
  double overload_max_delay_s_;  // [s]
  double stale_input_wall_s_;    // [s]
  RateLimitedLog overload_warning_;
  int64_t last_arrival_wall_us_ = -1;  // live packets only [us, host clock]
};

}  // namespace birotor

// The controller daemons' clock and control-period grid.
#include "nodes/controller_clock.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/percentile.h"
#include "numerics/time_units.h"

namespace birotor {

int64_t ControllerClock::ForInput(int input, int64_t utime, int64_t host_us) {
  const SupervisionParams& s = supervision_;
  const bool restart = set_ && host_us - last_accepted_host_us_ > kClockRelatchUs;
  if ((!set_ || restart) && utime >= 0 && utime <= kLatestPlausibleUtime) {
    // The offset this input says; set when another input's fresh candidate
    // agrees within clock_agreement_s (a lone stream 1000 s ahead never
    // does). The later offset of the two: the one that arrived soonest.
    candidate_offset_us_[input] = utime - host_us;
    candidate_host_us_[input] = host_us;
    for (int j = 0; j < kClockInputs; ++j) {
      const bool fresh = j != input && candidate_host_us_[j] >= 0 && host_us - candidate_host_us_[j] < kClockAcquireUs;
      if (!fresh ||
          std::fabs(ElapsedSeconds(candidate_offset_us_[input], candidate_offset_us_[j])) > s.clock_agreement_s)
        continue;
      if (restart) ++relatches_;
      set_ = true;
      offset_us_ = std::max(candidate_offset_us_[input], candidate_offset_us_[j]);
      set_host_us_ = last_accepted_host_us_ = host_us;
      for (int64_t& candidate : candidate_host_us_) candidate = -1;
      break;
    }
  } else if (set_ && host_us - set_host_us_ < kClockAcquireUs) {
    // Acquisition: the offset of the input that arrived soonest, forward
    // only and never by more than the future window at a time.
    // In seconds: a wild stamp must not overflow the subtraction.
    const double lead_s = ElapsedSeconds(utime, VehicleTimeUs(host_us));
    if (lead_s > 0 && lead_s <= s.clock_future_window_s) offset_us_ += SecondsToUtime(lead_s);
  }
  return VehicleTimeUs(host_us);
}

void ControlPeriodGrid::Ran(int64_t host_us) {
  next_host_us_ = next_host_us_ < 0 ? host_us + period_us_ : next_host_us_ + period_us_;
  if (next_host_us_ <= host_us) next_host_us_ = host_us + period_us_;
}

void ControlPeriodGrid::NoteLoopTime(int64_t host_us, int64_t done_us) {
  loop_times_us_[count_ % kCapacity] = static_cast<double>(done_us - host_us);
  ++count_;
}

void ControlPeriodGrid::TakeLoopTimes(double* p99_us, double* max_us) {
  const size_t n = std::min(count_, kCapacity);
  *p99_us = Percentile(loop_times_us_.begin(), loop_times_us_.begin() + n, 0.99);
  *max_us = n == 0 ? std::numeric_limits<double>::quiet_NaN()
                   : *std::max_element(loop_times_us_.begin(), loop_times_us_.begin() + n);
  count_ = 0;
}

}  // namespace birotor

#include "controller/force_floor_evidence.h"

#include <algorithm>
#include <cmath>

#include "numerics/time_units.h"
#include "samples/rotor_count.h"

namespace birotor {

int ForceFloorEvidence::FlyAtTheFloor(ForceEstimate* estimate) {
  const int32_t fault_bits[kBirotorRotors] = {kStatusRotor1Fault, kStatusRotor2Fault};
  int set = 0;
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double scale = estimate->thrust_scale[i];
    const bool below = (estimate->status & kStatusValid) != 0 && (estimate->status & fault_bits[i]) != 0 &&
                       scale >= 0.0 && scale < params_.min_plausible_thrust_scale;
    below_floor_run_[i] = below ? below_floor_run_[i] + 1 : 0;
    if (below && below_floor_run_[i] >= params_.at_floor_samples) {
      estimate->thrust_scale[i] = params_.min_plausible_thrust_scale;
      ++set;
    }
  }
  return set;
}

void ForceFloorEvidence::Note(const ForceEstimate& estimate, int64_t now_us, const double (&baseline)[kBirotorRotors]) {
  const double age_s = ElapsedSeconds(now_us, estimate.utime);
  if ((estimate.status & kStatusValid) == 0 || age_s > params_.clock_past_window_s ||
      -age_s > params_.clock_future_window_s || estimate.utime <= reported_utime_)
    return;
  // Low-passed: one ringing sample is not a loss.
  const double dt_s = reported_utime_ < 0 ? 0.0 : ElapsedSeconds(estimate.utime, reported_utime_);
  const double gain = std::min(1.0, dt_s / low_pass_s_);
  reported_utime_ = estimate.utime;
  for (int i = 0; i < kBirotorRotors; ++i) {
    const double scale = estimate.thrust_scale[i];
    if (!std::isfinite(scale) || scale < 0.0 || scale > params_.max_plausible_thrust_scale) continue;
    reported_scale_[i] += gain * (scale / baseline[i] - reported_scale_[i]);
  }
}

}  // namespace birotor

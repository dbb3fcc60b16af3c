#include "controller/force_floor_evidence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/time_units.h"

namespace birotor {

ForceFloorEvidence::ForceFloorEvidence(const SupervisionParams& params, double low_pass_s, int rotor_count)
    : params_(params), low_pass_s_(low_pass_s), rotor_count_(rotor_count) {
  reported_scale_.fill(1.0);
  below_floor_report_.fill(std::numeric_limits<double>::quiet_NaN());
}

int ForceFloorEvidence::FlyAtTheFloor(RotorEfficiencyEstimate* estimate) {
  const bool counted = estimate->valid && estimate->n_rotors == rotor_count_;
  int set = 0;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double scale = estimate->thrust_scale[rotor];
    const bool flagged = counted && (estimate->rotor_fault_bits & (1 << i)) != 0;
    // What the newest report says a flagged rotor below the floor makes (a
    // dead rotor's scale scatters about 0, so negatives read as 0).
    below_floor_report_[rotor] = flagged && scale < params_.min_plausible_thrust_scale
                                     ? std::max(scale, 0.0)
                                     : std::numeric_limits<double>::quiet_NaN();
    const bool flagged_low = flagged && scale < params_.min_plausible_thrust_scale;  // NaN: false
    flagged_low_run_[rotor] = flagged_low ? flagged_low_run_[rotor] + 1 : 0;
    flagged_low_sum_[rotor] = flagged_low ? flagged_low_sum_[rotor] + scale : 0.0;
    const bool below = flagged && scale >= 0.0 && scale < params_.min_plausible_thrust_scale;
    below_floor_run_[rotor] = below ? below_floor_run_[rotor] + 1 : 0;
    if (below && below_floor_run_[rotor] >= params_.at_floor_samples) {
      estimate->thrust_scale[rotor] = params_.min_plausible_thrust_scale;
      ++set;
    }
  }
  return set;
}

int ForceFloorEvidence::FlyAtTheFloor(ForceEstimate* estimate) {
  RotorEfficiencyEstimate report = RotorEfficiencyReportOf(*estimate);
  const int set = FlyAtTheFloor(&report);
  for (int i = 0; i < kBirotorRotors; ++i) estimate->thrust_scale[i] = report.thrust_scale[static_cast<size_t>(i)];
  return set;
}

double ForceFloorEvidence::below_floor_mean(int rotor) const {
  const size_t i = static_cast<size_t>(rotor);
  const int run = flagged_low_run_[i];
  return run >= params_.at_floor_samples && run > 0 ? flagged_low_sum_[i] / run
                                                    : std::numeric_limits<double>::quiet_NaN();
}

void ForceFloorEvidence::Note(const RotorEfficiencyEstimate& estimate, int64_t now_us,
                              const std::array<double, kMaxArms>& baseline) {
  const double age_s = ElapsedSeconds(now_us, estimate.utime);
  if (!estimate.valid || estimate.n_rotors != rotor_count_ || age_s > params_.clock_past_window_s ||
      -age_s > params_.clock_future_window_s || estimate.utime <= reported_utime_)
    return;
  // Low-passed: one ringing sample is not a loss.
  const double dt_s = reported_utime_ < 0 ? 0.0 : ElapsedSeconds(estimate.utime, reported_utime_);
  const double gain = std::min(1.0, dt_s / low_pass_s_);
  reported_utime_ = estimate.utime;
  for (int i = 0; i < rotor_count_; ++i) {
    const size_t rotor = static_cast<size_t>(i);
    const double scale = estimate.thrust_scale[rotor];
    if (!std::isfinite(scale) || scale < 0.0 || scale > params_.max_plausible_thrust_scale) continue;
    reported_scale_[rotor] += gain * (scale / baseline[rotor] - reported_scale_[rotor]);
  }
}

void ForceFloorEvidence::Note(const ForceEstimate& estimate, int64_t now_us, const double (&baseline)[kBirotorRotors]) {
  std::array<double, kMaxArms> baselines;
  baselines.fill(1.0);
  for (int i = 0; i < kBirotorRotors; ++i) baselines[static_cast<size_t>(i)] = baseline[i];
  Note(RotorEfficiencyReportOf(estimate), now_us, baselines);
}

}  // namespace birotor

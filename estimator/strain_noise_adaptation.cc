#include "estimator/strain_noise_adaptation.h"

#include <algorithm>

namespace birotor {

StrainNoiseAdaptation::StrainNoiseAdaptation(const EkfOptions& options, int gauges)
    : enabled_(options.adapt_strain_noise),
      gauges_(std::clamp(gauges, 1, kMaxSampleArms)),
      window_s_(options.strain_noise_window_s),
      scale_min_(options.strain_noise_scale_min),
      scale_max_(options.strain_noise_scale_max),
      min_samples_(options.strain_noise_min_samples),
      hold_us_(static_cast<int64_t>(options.strain_noise_hold_s * 1e6)),
      file_variance_rad2_(options.strain_noise_rad * options.strain_noise_rad) {
  scale_.fill(enabled_ ? std::max(1.0, scale_min_) : 1.0);
}

bool StrainNoiseAdaptation::Add(const FusionReport& report, const double* r_used_rad2, bool converged,
                                bool rotor_fault) {
  if (!enabled_) return false;
  if (report.size != gauges_) {  // (re-)initialised on it: no innovation
    BreakSequence();
    return false;
  }
  // A thrust step (fused after the gate's inflation) or a rotor fault: its
  // transient is not noise. A single gated sample (a spike, or the tail of
  // a noise wider than the file's) is only left out.
  const bool step = report.fused_after_inflation || rotor_fault;
  if (step) hold_until_utime_ = report.utime + hold_us_;
  if (step || report.outcome != FusionOutcome::kFused || !converged || report.utime < hold_until_utime_) {
    BreakSequence();
    return false;
  }
  const bool later = report.utime > previous_utime_;
  bool paired = false;
  for (int i = 0; i < gauges_; ++i) paired = paired || (has_previous_[static_cast<size_t>(i)] && later);
  // One sample more in the mean's count when any gauge pairs (the birotor: both or neither).
  double weight = 0;
  if (paired) {
    ++samples_;
    const double dt_s = 1e-6 * static_cast<double>(report.utime - previous_utime_);
    weight = std::max(1.0 / static_cast<double>(samples_), std::min(1.0, dt_s / window_s_));
  }
  bool changed = false;
  for (int i = 0; i < gauges_; ++i) {
    const size_t k = static_cast<size_t>(i);
    if (!(report.innovation_variance(i) > 0)) {  // not measured in this sample
      has_previous_[k] = false;
      continue;
    }
    const double hph_rad2 = report.innovation_variance(i) - r_used_rad2[i];
    if (has_previous_[k] && later) changed = LearnFromPair(i, report, hph_rad2, weight) || changed;
    has_previous_[k] = true;
    previous_innovation_rad_[k] = report.innovation(i);
    previous_hph_rad2_[k] = hph_rad2;
  }
  previous_utime_ = report.utime;
  return changed;
}

bool StrainNoiseAdaptation::LearnFromPair(int i, const FusionReport& report, double hph_rad2, double weight) {
  const size_t k = static_cast<size_t>(i);
  const double d = report.innovation(i) - previous_innovation_rad_[k];
  const double r_sample = 0.5 * d * d - 0.5 * (hph_rad2 + previous_hph_rad2_[k]);
  variance_estimate_rad2_[k] += weight * (r_sample - variance_estimate_rad2_[k]);
  if (samples_ < min_samples_) return false;
  const double scale = std::clamp(variance_estimate_rad2_[k] / file_variance_rad2_, scale_min_, scale_max_);
  const bool changed = scale != scale_[k];
  scale_[k] = scale;
  return changed;
}

}  // namespace birotor

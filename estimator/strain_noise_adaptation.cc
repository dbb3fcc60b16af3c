#include "estimator/strain_noise_adaptation.h"

#include <algorithm>

namespace birotor {

StrainNoiseAdaptation::StrainNoiseAdaptation(const EkfOptions& options)
    : enabled_(options.adapt_strain_noise),
      window_s_(options.strain_noise_window_s),
      scale_min_(options.strain_noise_scale_min),
      scale_max_(options.strain_noise_scale_max),
      min_samples_(options.strain_noise_min_samples),
      hold_us_(static_cast<int64_t>(options.strain_noise_hold_s * 1e6)),
      file_variance_rad2_(options.strain_noise_rad * options.strain_noise_rad) {
  for (int i = 0; i < kBirotorRotors; ++i) scale_[i] = enabled_ ? std::max(1.0, scale_min_) : 1.0;
}

bool StrainNoiseAdaptation::Add(const FusionReport& report, const double r_used_rad2[kBirotorRotors], bool converged,
                                bool rotor_fault) {
  if (!enabled_) return false;
  if (report.size != kBirotorRotors) {  // (re-)initialised on it: no innovation
    has_previous_ = false;
    return false;
  }
  // A thrust step (fused after the gate's inflation) or a rotor fault: its
  // transient is not noise. A single gated sample (a spike, or the tail of
  // a noise wider than the file's) is only left out.
  const bool step = report.fused_after_inflation || rotor_fault;
  if (step) hold_until_utime_ = report.utime + hold_us_;
  if (step || report.outcome != FusionOutcome::kFused || !converged || report.utime < hold_until_utime_) {
    has_previous_ = false;
    return false;
  }
  double hph_rad2[kBirotorRotors];
  for (int i = 0; i < kBirotorRotors; ++i) hph_rad2[i] = report.innovation_covariance(i, i) - r_used_rad2[i];
  const bool pair = has_previous_ && report.utime > previous_utime_;
  bool changed = false;
  if (pair) {
    ++samples_;
    const double dt_s = 1e-6 * static_cast<double>(report.utime - previous_utime_);
    const double weight = std::max(1.0 / static_cast<double>(samples_), std::min(1.0, dt_s / window_s_));
    for (int i = 0; i < kBirotorRotors; ++i) {
      const double d = report.innovation(i) - previous_innovation_rad_[i];
      const double r_sample = 0.5 * d * d - 0.5 * (hph_rad2[i] + previous_hph_rad2_[i]);
      variance_estimate_rad2_[i] += weight * (r_sample - variance_estimate_rad2_[i]);
      if (samples_ < min_samples_) continue;
      const double scale = std::clamp(variance_estimate_rad2_[i] / file_variance_rad2_, scale_min_, scale_max_);
      changed = changed || scale != scale_[i];
      scale_[i] = scale;
    }
  }
  has_previous_ = true;
  previous_utime_ = report.utime;
  for (int i = 0; i < kBirotorRotors; ++i) {
    previous_innovation_rad_[i] = report.innovation(i);
    previous_hph_rad2_[i] = hph_rad2[i];
  }
  return changed;
}

}  // namespace birotor

#include "estimator/noise_adaptation.h"

#include <algorithm>
#include <cmath>

namespace birotor {

NoiseAdaptationSettings StrainNoiseSettings(const EkfOptions& options) {
  NoiseAdaptationSettings s;
  s.enabled = options.adapt_strain_noise;
  s.file_variance = options.strain_noise_rad * options.strain_noise_rad;
  s.window_s = options.strain_noise_window_s;
  s.scale_min = options.strain_noise_scale_min;
  s.scale_max = options.strain_noise_scale_max;
  s.min_samples = options.strain_noise_min_samples;
  s.hold_s = options.strain_noise_hold_s;
  return s;
}

NoiseAdaptationSettings AccelerometerNoiseSettings(const EkfOptions& options) {
  NoiseAdaptationSettings s;
  s.enabled = options.adapt_accel_noise;
  s.file_variance = options.accel_noise_m_s2 * options.accel_noise_m_s2;
  s.window_s = options.accel_noise_window_s;
  s.scale_min = 1.0;  // never below the file's
  s.scale_max = options.accel_noise_scale_max;
  s.min_samples = options.accel_noise_min_samples;
  s.hold_s = options.accel_noise_hold_s;
  s.learn_gated = true;
  s.clip = options.accel_noise_clip;
  s.trust_samples = options.accel_noise_trust_samples;
  s.trust_sigmas = options.accel_noise_trust_sigmas;
  return s;
}

NoiseAdaptationSettings MultiArmAccelerometerNoiseSettings(const EkfOptions& options) {
  NoiseAdaptationSettings s = AccelerometerNoiseSettings(options);
  s.median_start = true;
  return s;
}

NoiseAdaptation::NoiseAdaptation(const NoiseAdaptationSettings& settings, int gauges)
    : enabled_(settings.enabled),
      gauges_(std::clamp(gauges, 1, kMaxSampleArms)),
      window_s_(settings.window_s),
      scale_min_(settings.scale_min),
      scale_max_(settings.scale_max),
      min_samples_(settings.min_samples),
      trust_samples_(settings.trust_samples),
      trust_sigmas_(settings.trust_sigmas),
      hold_us_(static_cast<int64_t>(settings.hold_s * 1e6)),
      file_variance_(settings.file_variance),
      learn_gated_(settings.learn_gated),
      clip_(settings.clip),
      median_start_(settings.median_start) {
  scale_.fill(enabled_ ? std::max(1.0, scale_min_) : 1.0);
}

bool NoiseAdaptation::Add(const FusionReport& report, const double* r_used, bool converged, bool step) {
  if (!enabled_) return false;
  if (report.size != gauges_) {  // (re-)initialised on it: no innovation
    BreakSequence();
    return false;
  }
  // A thrust step (fused after the gate's inflation, or the caller's) or a
  // rotor fault: its transient is not noise. A single gated sample (a
  // spike, or the tail of a noise wider than the file's) is only left out.
  const bool transient = report.fused_after_inflation || step;
  if (transient) hold_until_utime_ = report.utime + hold_us_;
  const bool usable =
      report.outcome == FusionOutcome::kFused || (learn_gated_ && report.outcome == FusionOutcome::kRejectedGate);
  if (transient || !usable || !converged || report.utime < hold_until_utime_) {
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
    // Not measured in this sample, or not a number (a gated NaN innovation
    // would otherwise reach the mean, or the start's sort): that pair breaks.
    const bool measured = report.innovation_variance(i) > 0 && std::isfinite(report.innovation_variance(i)) &&
                          std::isfinite(report.innovation(i));
    if (!measured) {
      has_previous_[k] = false;
      continue;
    }
    const double hph = report.innovation_variance(i) - r_used[i];
    if (has_previous_[k] && later) changed = LearnFromPair(i, report, hph, weight) || changed;
    has_previous_[k] = true;
    previous_innovation_[k] = report.innovation(i);
    previous_hph_[k] = hph;
  }
  previous_utime_ = report.utime;
  return changed;
}

bool NoiseAdaptation::LearnFromPair(int i, const FusionReport& report, double hph, double weight) {
  const size_t k = static_cast<size_t>(i);
  const double d = report.innovation(i) - previous_innovation_[k];
  const double difference = 0.5 * d * d;
  UpdateEstimate(k, difference, difference - 0.5 * (hph + previous_hph_[k]), weight);
  if (samples_ < min_samples_) return false;
  const double scale = std::clamp(variance_estimate_[k] / file_variance_, scale_min_, scale_max_);
  const bool changed = scale != scale_[k];
  scale_[k] = scale;
  return changed;
}

void NoiseAdaptation::UpdateEstimate(size_t k, double difference, double r_sample, double weight) {
  const int started = start_count_[k];
  if (median_start_ && started < kStartPairs) {
    // The median of the pairs so far (of the middle two for an even count),
    // sorted in a copy of at most kStartPairs values.
    start_samples_[k][static_cast<size_t>(started)] = difference;
    start_count_[k] = started + 1;
    std::array<double, kStartPairs> sorted = start_samples_[k];
    std::sort(sorted.begin(), sorted.begin() + started + 1);
    const double median =
        0.5 * (sorted[static_cast<size_t>(started / 2)] + sorted[static_cast<size_t>((started + 1) / 2)]);
    constexpr double kChiSquare1Median = 0.4549;  // of chi^2 with one degree of freedom
    variance_estimate_[k] = median / kChiSquare1Median;
    return;
  }
  const double capped =
      clip_ > 0 ? std::min(r_sample, clip_ * std::max(variance_estimate_[k], file_variance_)) : r_sample;
  variance_estimate_[k] += weight * (capped - variance_estimate_[k]);
}

double NoiseAdaptation::CautiousScale(int i) const {
  if (!enabled_ || samples_ >= trust_samples_) return scale(i);
  const double n = static_cast<double>(std::max<int64_t>(samples_, 1));
  return std::min(scale_max_, scale(i) * (1.0 + trust_sigmas_ * std::sqrt(2.0 / n)));
}

}  // namespace birotor

// The strain gauges' measurement noise learned online (issue 36 item 2): a
// bounded scale on each gauge's variance R_i from the filter's own strain
// innovations (covariance matching), so that gauges noisier than the
// parameter file says are weighed as they are instead of reading as a
// vehicle that does not match its file. Pure library: no allocation, no
// throw, no log (docs/estimator.md "Measurement noise learned online").
#pragma once

#include <array>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/fusion_report.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"

namespace birotor {

// Covariance matching (Mehra 1972; Sage-Husa with a fading memory) on the
// first difference of each gauge's innovation y_i = z_i - h_i(x):
//   E[y_i y_i] = (H P H^T)_ii + R_i  for white innovations, hence
//   r_i = (y_i,k - y_i,k-1)^2 / 2 - ((H P H^T)_ii,k + (H P H^T)_ii,k-1) / 2
// estimates R_i sample by sample (E[r_i] = R_i); its fading mean
//   R_i_hat += w (r_i - R_i_hat),  w = max(1 / n, dt / window_s)
// (an expanding mean over the first samples, then a memory of window_s), and
//   scale_i = clamp(R_i_hat / R_i_file, scale_min, scale_max).
// The difference is what keeps it to noise: a bias, a slow drift or an
// innovation that follows the manoeuvre (a wrong stiffness, gauge scale or
// mass) changes little from one strain sample to the next and cancels, so it
// stays in the innovations for the model-consistency monitor to see; only
// the sample-to-sample (white) part is learned as noise. A sample counts
// only when fused normally (not gated, not fused after inflation), with the
// filter converged and no rotor fault flagged, and not within hold_s of a
// gated sample or a fault (the innovations of a thrust step are not noise).
// The scale is kept across a re-initialisation (it is the gauges' property).
// For any number of gauges (the birotor's 2, an N-arm vehicle's N): a gauge
// the report does not measure (innovation variance 0: no gauge on the arm,
// or no reading in this sample) breaks that gauge's pair alone.
class StrainNoiseAdaptation {
 public:
  // gauges: the strain measurement's size, 1 .. kMaxSampleArms.
  explicit StrainNoiseAdaptation(const EkfOptions& options, int gauges = kBirotorRotors);
  // The newest strain fusion report with the filter's facts at it; r_used:
  // the variances the report's S was formed with (scale_i R_i_file), one
  // per gauge [rad^2]. Returns true when a scale changed.
  bool Add(const FusionReport& report, const double* r_used_rad2, bool converged, bool rotor_fault);
  // Forgets the previous innovation (filter re-initialised); the scale stays.
  void BreakSequence() { has_previous_.fill(false); }
  // The variance scale of gauge i [1] (1 when not adapting).
  double scale(int i) const { return scale_[static_cast<size_t>(i)]; }
  // The strain samples learned from since start-up.
  int64_t samples() const { return samples_; }
  // Learning at all (EkfOptions::adapt_strain_noise).
  bool enabled() const { return enabled_; }

 private:
  // Gauge i's pair from its previous innovation to this report's.
  bool LearnFromPair(int i, const FusionReport& report, double hph_rad2, double weight);

  bool enabled_;
  int gauges_;
  double window_s_;
  double scale_min_, scale_max_;
  int64_t min_samples_;
  int64_t hold_us_;
  double file_variance_rad2_;  // R_i_file = strain_noise_rad^2
  int64_t previous_utime_ = 0;
  int64_t hold_until_utime_ = -1;                    // no sample counts before this [us]
  std::array<bool, kMaxSampleArms> has_previous_{};  // gauge i's previous innovation is the newest report's
  ArmValues previous_innovation_rad_{};
  ArmValues previous_hph_rad2_{};
  ArmValues variance_estimate_rad2_{};  // R_i_hat
  ArmValues scale_{};
  int64_t samples_ = 0;
};

}  // namespace birotor

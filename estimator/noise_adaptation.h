// A sensor's measurement noise learned online (issue 36 item 2: the strain
// gauges, the accelerometer): a bounded scale on each component's variance
// R_i from the filter's own innovations (covariance matching), so that a
// sensor noisier than the parameter file says is weighed as it is instead
// of reading as a vehicle that does not match its file. Pure library: no
// allocation, no throw, no log (docs/estimator.md "Measurement noise
// learned online").
#pragma once

#include <array>
#include <cstdint>

#include "estimator/estimator_config.h"
#include "estimator/fusion_report.h"
#include "samples/multi_arm_samples.h"
#include "samples/rotor_count.h"

namespace birotor {

// How one sensor's noise is learned (NoiseAdaptation).
struct NoiseAdaptationSettings {
  bool enabled = false;
  double file_variance = 1.0;               // R_file, the parameter file's variance [unit^2]
  double window_s = 2.0;                    // the fading memory [s]
  double scale_min = 1.0, scale_max = 1.0;  // bounds of the scale on the variance [1]
  int64_t min_samples = 1;                  // samples learned from before the scale moves
  double hold_s = 0.0;                      // frozen this long after a step (gate inflation, rotor fault) [s]
  // Samples the gate rejected count too (a sensor whose true noise can lie
  // far beyond the file's gates most of its samples until learned); each
  // sample's r_i is then capped at clip x max(R_i_hat, R_file), so one spike
  // moves the mean by at most w clip R_i_hat [1].
  bool learn_gated = false;
  double clip = 0.0;  // 0: no cap
  // The first pairs start R_i_hat at their median instead of the (capped)
  // mean growing from 0 (NoiseAdaptation, "The start").
  bool median_start = false;
  // Until trust_samples pairs were learned from, CautiousScale fuses the
  // scale's upper confidence bound at trust_sigmas (0 samples: the scale as
  // it is) [1].
  int64_t trust_samples = 0;
  double trust_sigmas = 0.0;
};
// The strain gauges' (estimator.ekf strain_noise_*; rad^2) and the
// accelerometer's a_z (accel_noise_*; m^2/s^4) settings.
NoiseAdaptationSettings StrainNoiseSettings(const EkfOptions& options);
NoiseAdaptationSettings AccelerometerNoiseSettings(const EkfOptions& options);
// The N-arm EKF's accelerometer: at an airborne start it fuses a_z only
// after min_samples pairs, at the scale as it stands (not CautiousScale), so
// the scale must not start low: AccelerometerNoiseSettings with median_start.
NoiseAdaptationSettings MultiArmAccelerometerNoiseSettings(const EkfOptions& options);

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
// only when fused normally (not gated, unless learn_gated; not fused after
// inflation), with the filter converged and no rotor fault flagged, and not
// within hold_s of a fault or a sample fused after inflation (the
// innovations of a thrust step are not noise).
// The start (median_start): R_i_hat begins as the median of the first
// kStartPairs values of (y_i,k - y_i,k-1)^2 / 2 over 0.4549 (the median of
// chi^2 with one degree of freedom), nothing taken off for the state's
// share: right after a start consecutive priors share nearly all their
// error, which the difference cancels, so subtracting H P H^T (30-90 R_file
// there) as for independent innovations took a noise 20x the file's
// (sigma) for none. It errs high while the state still converges (on the
// file's noise 1-160 R_file after 5 pairs, 1-5.3 after 100: the capped mean
// that goes on from there brings it down by 1 / n). The cap alone let a
// noisy sensor's estimate grow from R_file by at most clip x a pair,
// diluted by 1 / n: the N-arm EKF's accelerometer scale stood at 10 of 400
// after 5 pairs and its first fused samples flagged a false rotor fault; a
// mean without the cap took a single lift-off transient (24,850 R_file) as
// the noise for a second. The median keeps neither.
// The scale is kept across a re-initialisation (it is the gauges' property).
// For any number of gauges (the birotor's 2, an N-arm vehicle's N): a gauge
// the report does not measure (innovation variance 0: no gauge on the arm,
// or no reading in this sample) breaks that gauge's pair alone.
class NoiseAdaptation {
 public:
  // gauges: the measurement's size, 1 .. kMaxSampleArms.
  explicit NoiseAdaptation(const NoiseAdaptationSettings& settings, int gauges = kBirotorRotors);
  // The newest fusion report of the sensor with the filter's facts at it;
  // r_used: the variances the report's S was formed with (scale_i R_i_file
  // and whatever else the filter added), one per component [unit^2];
  // step: a rotor fault is flagged or the filter is in a thrust step (for
  // the accelerometer: the strain gated), so the sample is not noise and
  // learning holds for hold_s. Returns true when a scale changed.
  bool Add(const FusionReport& report, const double* r_used, bool converged, bool step);
  // Forgets the previous innovation (filter re-initialised); the scale stays.
  void BreakSequence() { has_previous_.fill(false); }
  // The variance scale of component i [1] (1 when not adapting).
  double scale(int i) const { return scale_[static_cast<size_t>(i)]; }
  // The scale to fuse component i with [1]: scale(i) from trust_samples
  // pairs on; before, its upper confidence bound after n pairs,
  //   min(scale_max, scale(i) (1 + trust_sigmas sqrt(2 / max(n, 1)))),
  // sqrt(2 / n) being the relative sigma of a mean of n squared Gaussian
  // differences. A sensor far noisier than its file, fused as precise on
  // the few samples its noise was learned from, pulled the state with a
  // confidence the filter kept for seconds.
  double CautiousScale(int i) const;
  // The samples learned from since start-up.
  int64_t samples() const { return samples_; }
  // Learning at all (NoiseAdaptationSettings::enabled).
  bool enabled() const { return enabled_; }

 private:
  // The pairs whose median starts R_i_hat (median_start).
  static constexpr int kStartPairs = 5;
  // Gauge i's pair from its previous innovation to this report's.
  bool LearnFromPair(int i, const FusionReport& report, double hph, double weight);
  // R_i_hat from one more pair: the start's median of difference =
  // (y_i,k - y_i,k-1)^2 / 2, or the mean of r_sample (capped when clip > 0)
  // [unit^2].
  void UpdateEstimate(size_t k, double difference, double r_sample, double weight);

  bool enabled_;
  int gauges_;
  double window_s_;
  double scale_min_, scale_max_;
  int64_t min_samples_;
  int64_t trust_samples_;
  double trust_sigmas_;
  int64_t hold_us_;
  double file_variance_;  // R_i_file [unit^2]
  bool learn_gated_;
  double clip_;  // 0: none
  bool median_start_;
  int64_t previous_utime_ = 0;
  int64_t hold_until_utime_ = -1;                    // no sample counts before this [us]
  std::array<bool, kMaxSampleArms> has_previous_{};  // gauge i's previous innovation is the newest report's
  ArmValues previous_innovation_{};
  ArmValues previous_hph_{};
  ArmValues variance_estimate_{};                                                // R_i_hat [unit^2]
  std::array<std::array<double, kStartPairs>, kMaxSampleArms> start_samples_{};  // the start's pairs [unit^2]
  std::array<int, kMaxSampleArms> start_count_{};                                // of them, per component
  ArmValues scale_{};
  int64_t samples_ = 0;
};

}  // namespace birotor

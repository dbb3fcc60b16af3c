// The strain noise learned online (issue 36 item 2,
// estimator/noise_adaptation.h, docs/estimator.md): the scale on a
// gauge's variance converges to the true noise's, stays at 1 on the file's
// noise, holds its bounds, does not absorb a bias or a drift, and freezes
// where it must; and the case, the gentle flight with gauges twice
// as noisy (sigma) as the file says, keeps VALID forces without a
// MODEL_MISMATCH. Figures measured on the development VM with the shipped
// config/estimator.yaml; bounds at most 1.5x from them.
#include "estimator/noise_adaptation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>

#include "evaluation/mismatch_targets.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

constexpr double kFileNoiseRad = 2e-5;  // EkfOptions::strain_noise_rad
constexpr double kFileVariance = kFileNoiseRad * kFileNoiseRad;
constexpr int64_t kStrainPeriodUs = 1000;  // 1 kHz

// Standard normal samples by Box-Muller on mt19937 (the same on every
// standard library, unlike std::normal_distribution).
class Gaussian {
 public:
  explicit Gaussian(uint32_t seed) : engine_(seed) {}
  double Next() {
    const double u1 = (static_cast<double>(engine_()) + 1.0) / 4294967297.0;
    const double u2 = static_cast<double>(engine_()) / 4294967296.0;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  std::mt19937 engine_;
};

// Feeds n strain reports whose innovations are white with variance
// true_variance + hph (H P H^T = hph on each gauge), plus offset(t) [rad],
// each formed with the adaptation's current R; returns the adaptation.
struct SyntheticRun {
  double true_variance_rad2 = kFileVariance;
  double hph_rad2 = 0.2 * kFileVariance;  // the filter's share of S at 1 kHz: small
  double bias_rad = 0;
  double drift_rad_s = 0;
  bool converged = true;
  FusionOutcome outcome = FusionOutcome::kFused;
};

void Feed(const SyntheticRun& run, int samples, NoiseAdaptation* adaptation, int64_t* utime, uint32_t seed = 7) {
  Gaussian gaussian(seed);
  for (int n = 0; n < samples; ++n) {
    *utime += kStrainPeriodUs;
    FusionReport report;
    report.source = FusionSource::kStrain;
    report.utime = *utime;
    report.size = 2;
    report.outcome = run.outcome;
    double r_used[2];
    for (int i = 0; i < 2; ++i) {
      r_used[i] = adaptation->scale(i) * kFileVariance;
      report.innovation(i) = std::sqrt(run.true_variance_rad2 + run.hph_rad2) * gaussian.Next() + run.bias_rad +
                             run.drift_rad_s * (*utime * 1e-6);
      report.innovation_variance(i) = run.hph_rad2 + r_used[i];
    }
    adaptation->Add(report, r_used, run.converged, false);
  }
}

EkfOptions Options() {
  EkfOptions options;
  options.strain_noise_rad = kFileNoiseRad;
  return options;
}

// 2 s of noise at 2x and 4x the file's variance (sigma x1.41 and x2).
// Measured: 1.92 / 2.08 and 3.85 / 4.16 after 2 s (at most 4.1 % off).
TEST(NoiseAdaptation, ConvergesToTheTrueVariance) {
  for (const double ratio : {2.0, 4.0}) {
    NoiseAdaptation adaptation(StrainNoiseSettings(Options()));
    int64_t utime = 0;
    SyntheticRun run;
    run.true_variance_rad2 = ratio * kFileVariance;
    Feed(run, 2000, &adaptation, &utime);
    for (int i = 0; i < 2; ++i) {
      std::printf("variance x%.0f: scale %d %.3f\n", ratio, i + 1, adaptation.scale(i));
      EXPECT_NEAR(adaptation.scale(i), ratio, 0.062 * ratio) << ratio << " gauge " << i + 1;
    }
  }
}

// The file's noise: the scale stays at its floor 1 or just above (measured
// at most 1.073 over 10 s, early, while the mean still expands).
TEST(NoiseAdaptation, StaysNearOneOnTheFilesNoise) {
  NoiseAdaptation adaptation(StrainNoiseSettings(Options()));
  int64_t utime = 0;
  double largest = 0;
  for (int second = 0; second < 10; ++second) {
    Feed(SyntheticRun(), 1000, &adaptation, &utime, 11 + second);
    largest = std::max({largest, adaptation.scale(0), adaptation.scale(1)});
  }
  std::printf("file noise: largest scale %.3f\n", largest);
  EXPECT_GE(largest, 1.0);
  EXPECT_LE(largest, 1.11);
}

// Far noisier or quieter than the file: the bounds hold (defaults [1, 6.25]).
TEST(NoiseAdaptation, TheBoundsHold) {
  for (const double ratio : {20.0, 0.25}) {
    NoiseAdaptation adaptation(StrainNoiseSettings(Options()));
    int64_t utime = 0;
    SyntheticRun run;
    run.true_variance_rad2 = ratio * kFileVariance;
    Feed(run, 3000, &adaptation, &utime);
    for (int i = 0; i < 2; ++i) EXPECT_EQ(adaptation.scale(i), ratio > 1 ? 6.25 : 1.0) << ratio;
  }
}

// The accelerometer's rule (AccelerometerNoiseSettings: gated samples
// count, each capped at clip x the estimate): noise 20x the file's (sigma;
// variance x400), every sample gated, is learned within the bound (measured
// 390-409 after 2 s); with the strain's rule (gated samples not counted)
// nothing is learned. Then a single spike of 1000 file sigmas moves the
// learned variance by at most w clip, w = dt / window_s.
TEST(NoiseAdaptation, TheAccelerometersRuleLearnsFromGatedSamples) {
  NoiseAdaptationSettings settings = AccelerometerNoiseSettings(EkfOptions());
  settings.file_variance = kFileVariance;
  NoiseAdaptation accelerometer(settings);
  NoiseAdaptationSettings fused_only = settings;
  fused_only.learn_gated = false;
  NoiseAdaptation strain_rule(fused_only);
  SyntheticRun run;
  run.true_variance_rad2 = 400.0 * kFileVariance;
  run.outcome = FusionOutcome::kRejectedGate;
  int64_t utime = 0, utime_strain_rule = 0;
  Feed(run, 2000, &accelerometer, &utime);
  Feed(run, 2000, &strain_rule, &utime_strain_rule);
  for (int i = 0; i < 2; ++i) {
    std::printf("gated x400: scale %d %.1f (strain's rule %.2f)\n", i + 1, accelerometer.scale(i),
                strain_rule.scale(i));
    EXPECT_NEAR(accelerometer.scale(i), 400.0, 0.1 * 400.0) << i;
    EXPECT_EQ(strain_rule.scale(i), 1.0) << i;
  }
  const double before = accelerometer.scale(0);
  FusionReport spike;
  spike.source = FusionSource::kAccelerometer;
  spike.utime = utime + kStrainPeriodUs;
  spike.size = 2;
  spike.outcome = FusionOutcome::kRejectedGate;
  const double r_used[2] = {before * kFileVariance, accelerometer.scale(1) * kFileVariance};
  for (int i = 0; i < 2; ++i) {
    spike.innovation(i) = 1000.0 * kFileNoiseRad;
    spike.innovation_variance(i) = r_used[i];
  }
  accelerometer.Add(spike, r_used, true, false);
  const double w = kStrainPeriodUs * 1e-6 / settings.window_s;
  EXPECT_LE(accelerometer.scale(0), before * (1.0 + w * settings.clip) * 1.001);
}

// The N-arm start (median_start): the median of 5 pairs' (y_k - y_k-1)^2 / 2.
// A noise 20x the file's (sigma) behind H P H^T 80 R_file, 100 seeds: below a
// quarter of the truth's 400 after 5 pairs on 13 (the capped mean, H P H^T taken
// off: on 78). The file's noise, a 25,000 R_file lift-off spike: 1.76 (9.03).
TEST(NoiseAdaptation, TheMultiArmStartIsAMedian) {
  NoiseAdaptationSettings median = MultiArmAccelerometerNoiseSettings(EkfOptions());
  median.file_variance = kFileVariance;
  NoiseAdaptationSettings capped_mean = median;
  capped_mean.median_start = false;
  SyntheticRun start;
  start.true_variance_rad2 = 400.0 * kFileVariance;
  start.outcome = FusionOutcome::kRejectedGate;  // fused only once learned
  start.hph_rad2 = 80.0 * kFileVariance;
  int low_median = 0, low_capped = 0;
  for (uint32_t seed = 1; seed <= 100; ++seed) {
    NoiseAdaptation with_median(median), without(capped_mean);
    int64_t utime = 0, utime_without = 0;
    Feed(start, 6, &with_median, &utime, seed);
    Feed(start, 6, &without, &utime_without, seed);
    ASSERT_EQ(with_median.samples(), 5);
    low_median += with_median.scale(0) < 100.0;
    low_capped += without.scale(0) < 100.0;
  }
  std::printf("x400 start, 100 seeds, scale < 100: median %d, capped mean %d\n", low_median, low_capped);
  EXPECT_LE(low_median, 20);
  EXPECT_GE(low_capped, 50);
  // The file's noise, one lift-off spike (two pairs: up and down).
  SyntheticRun settled;
  int64_t utime = 0;
  for (const bool use_median : {true, false}) {
    NoiseAdaptation adaptation(use_median ? median : capped_mean);
    Feed(settled, 2, &adaptation, &utime, 11);
    SyntheticRun spike = settled;
    spike.bias_rad = std::sqrt(2.0 * 25000.0 * kFileVariance);
    Feed(spike, 1, &adaptation, &utime, 12);
    Feed(settled, 4, &adaptation, &utime, 13);
    std::printf("file's noise, spike: %s %.2f\n", use_median ? "median" : "capped mean", adaptation.scale(0));
    EXPECT_TRUE(use_median ? adaptation.scale(0) < 2.5 : adaptation.scale(0) > 5.0) << use_median;
  }
}

// A gated NaN innovation breaks its pair: the scale stays as it was (both rules).
TEST(NoiseAdaptation, ANonFiniteInnovationIsLeftOut) {
  for (const bool use_median : {true, false}) {
    NoiseAdaptationSettings settings = MultiArmAccelerometerNoiseSettings(EkfOptions());
    settings.file_variance = kFileVariance;
    settings.median_start = use_median;
    NoiseAdaptation adaptation(settings);
    SyntheticRun run, bad;
    run.true_variance_rad2 = bad.true_variance_rad2 = 4.0 * kFileVariance;
    bad.outcome = FusionOutcome::kRejectedGate;
    bad.bias_rad = std::numeric_limits<double>::quiet_NaN();
    int64_t utime = 0;
    Feed(run, 20, &adaptation, &utime);
    const double before = adaptation.scale(0);
    Feed(bad, 3, &adaptation, &utime);
    EXPECT_EQ(adaptation.scale(0), before) << use_median;  // a NaN compares unequal
  }
}

// Three gauges (an N-arm vehicle, MultiArmEkf), the third without a
// reading (the report's variance 0): the two measured learn their noise as
// the birotor's do (the same bound as ConvergesToTheTrueVariance), the third
// keeps the floor 1.
TEST(NoiseAdaptation, LearnsEachMeasuredGaugeOfThree) {
  NoiseAdaptation adaptation(StrainNoiseSettings(Options()), 3);
  Gaussian gaussian(7);
  const double true_variance[3] = {4.0 * kFileVariance, 2.0 * kFileVariance, 4.0 * kFileVariance};
  const double hph = 0.2 * kFileVariance;
  int64_t utime = 0;
  for (int n = 0; n < 2000; ++n) {
    FusionReport report;
    report.utime = utime += kStrainPeriodUs;
    report.size = 3;
    report.outcome = FusionOutcome::kFused;
    double r_used[3];
    for (int i = 0; i < 3; ++i) {
      r_used[i] = adaptation.scale(i) * kFileVariance;
      const bool measured = i < 2;
      report.innovation(i) = measured ? std::sqrt(true_variance[i] + hph) * gaussian.Next() : 0.0;
      report.innovation_variance(i) = measured ? hph + r_used[i] : 0.0;
    }
    adaptation.Add(report, r_used, true, false);
  }
  EXPECT_NEAR(adaptation.scale(0), 4.0, 0.062 * 4.0);
  EXPECT_NEAR(adaptation.scale(1), 2.0, 0.062 * 2.0);
  EXPECT_EQ(adaptation.scale(2), 1.0);
}

// A bias of 5 file sigmas and a drift of 10 sigmas per second on the file's
// noise are not noise: the first difference cancels them (the scale stays
// within the bound of the file's noise above).
TEST(NoiseAdaptation, DoesNotAbsorbABiasOrADrift) {
  NoiseAdaptation adaptation(StrainNoiseSettings(Options()));
  int64_t utime = 0;
  SyntheticRun run;
  run.bias_rad = 5.0 * kFileNoiseRad;
  run.drift_rad_s = 10.0 * kFileNoiseRad;
  Feed(run, 5000, &adaptation, &utime);
  for (int i = 0; i < 2; ++i) EXPECT_LE(adaptation.scale(i), 1.11) << i;
}

// Frozen: before strain_noise_min_samples, while the filter converges, on
// gated samples, and for strain_noise_hold_s after a sample fused after the
// gate's inflation (a thrust step).
TEST(NoiseAdaptation, FreezesWhereTheInnovationsAreNotNoise) {
  SyntheticRun noisy;
  noisy.true_variance_rad2 = 4.0 * kFileVariance;
  NoiseAdaptation adaptation(StrainNoiseSettings(Options()));
  int64_t utime = 0;
  Feed(noisy, 150, &adaptation, &utime);  // 149 pairs < 200
  EXPECT_EQ(adaptation.scale(0), 1.0);
  SyntheticRun converging = noisy;
  converging.converged = false;
  Feed(converging, 1000, &adaptation, &utime);
  SyntheticRun gated = noisy;
  gated.outcome = FusionOutcome::kRejectedGate;
  Feed(gated, 1000, &adaptation, &utime);
  EXPECT_EQ(adaptation.samples(), 149);
  EXPECT_EQ(adaptation.scale(0), 1.0);

  // A step: fused after inflation, then 0.2 s of nothing learned.
  Feed(noisy, 500, &adaptation, &utime);
  const double before = adaptation.scale(0);
  FusionReport step;
  step.utime = utime += kStrainPeriodUs;
  step.size = 2;
  step.outcome = FusionOutcome::kFused;
  step.fused_after_inflation = true;
  const double r_used[2] = {before * kFileVariance, before * kFileVariance};
  step.innovation.head<2>() << 100 * kFileNoiseRad, 100 * kFileNoiseRad;
  adaptation.Add(step, r_used, true, false);
  const int64_t learned = adaptation.samples();
  Feed(noisy, 199, &adaptation, &utime);
  EXPECT_EQ(adaptation.samples(), learned);
  Feed(noisy, 10, &adaptation, &utime);
  EXPECT_GT(adaptation.samples(), learned);
  // A rotor fault freezes it as long (from its report on).
  const int64_t at_fault = adaptation.samples();
  step.fused_after_inflation = false;
  step.utime = utime += kStrainPeriodUs;
  adaptation.Add(step, r_used, true, true);
  Feed(noisy, 199, &adaptation, &utime);
  EXPECT_EQ(adaptation.samples(), at_fault);
}

// The case (issue 36 item 2): the gentle flight with the gauges'
// sigma twice the file's (sensors.strain.noise_rad 4e-5). Before the
// adaptation: MODEL_MISMATCH at 0.5 s, VALID 3.3 % of the flight, MAE
// 0.077 / 0.079 N and 2-sigma share 0.926 from 5 s (birotor-eval). Measured
// with it: scale 4.00 / 3.94 at 1 s, 3.89 / 4.09 at the end, VALID 100 %
// from 5 s, MAE 0.0710 / 0.0713 N, 2-sigma share 0.960 / 0.962, no mismatch.
TEST(NoiseAdaptation, GentleFlightWithGaugesTwiceAsNoisy) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("gentle"), {"sensors.strain.noise_rad=4e-5"}), ReferenceConfig());
  const int64_t start = run.pairs.front().utime;
  const int64_t from = start + 5000000;
  int64_t valid = 0, count = 0;
  for (const PairedSample& p : run.pairs) {
    if (p.utime < from) continue;
    ++count;
    if (p.status & kStatusValid) ++valid;
  }
  double scale_at_1s[2] = {0, 0}, scale_end[2] = {0, 0};
  for (const GaugeOffsetSample& s : run.gauge_offsets) {
    for (int i = 0; i < 2; ++i) {
      if (s.utime - start <= 1000000) scale_at_1s[i] = s.strain_noise_scale[i];
      scale_end[i] = s.strain_noise_scale[i];
    }
  }
  const double valid_share = static_cast<double>(valid) / static_cast<double>(count);
  const double mae[2] = {ForceMae(run, 0, from), ForceMae(run, 1, from)};
  const double within[2] = {ShareWithin2Sigma(run, 0, from), ShareWithin2Sigma(run, 1, from)};
  std::printf(
      "gentle noise x2: scale at 1 s %.2f %.2f, end %.2f %.2f; VALID %.3f, MAE %.4f %.4f, 2 sigma %.3f %.3f, "
      "mismatches %lld\n",
      scale_at_1s[0], scale_at_1s[1], scale_end[0], scale_end[1], valid_share, mae[0], mae[1], within[0], within[1],
      static_cast<long long>(run.health.consistency.raised_count));
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(scale_at_1s[i], 4.0, 0.17) << i;  // the true variance ratio 4; measured 0.11 off at most
    EXPECT_NEAR(scale_end[i], 4.0, 0.17) << i;
    EXPECT_LE(mae[i], 0.10) << i;  // the target; measured 0.071
    EXPECT_GE(within[i], 0.93) << i;
    EXPECT_LE(within[i], 0.98) << i;
  }
  EXPECT_GE(valid_share, 0.95);  // target 0.80; measured 1.000
  EXPECT_EQ(run.health.consistency.raised_count, 0);
}

// Issue 36's IMU case: hover with an accelerometer 20x as noisy (sigma 1
// m/s^2) as the file's 0.05. Before the accelerometer's noise was learned:
// MODEL_MISMATCH raised at 0.03-0.50 s, 0.26-0.39 N off, 2-sigma 0.49-0.63
// (seeds 1-3). Measured on the scenario's seed: never raised, VALID 100 %
// from 5 s, MAE 0.0949 / 0.0950 N, 2-sigma 0.956 / 0.957, the scale about
// 400 (the truth's ratio) at the end.
TEST(NoiseAdaptation, HoverWithAnAccelerometerTwentyTimesAsNoisy) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("hover"), {"sensors.imu.accel_noise_m_s2=1.0"}), ReferenceConfig());
  const int64_t from = run.pairs.front().utime + 5000000;
  int64_t valid = 0, count = 0;
  for (const PairedSample& p : run.pairs) {
    if (p.utime < from) continue;
    ++count;
    if (p.status & kStatusValid) ++valid;
  }
  const double valid_share = static_cast<double>(valid) / static_cast<double>(count);
  const double mae[2] = {ForceMae(run, 0, from), ForceMae(run, 1, from)};
  const double within[2] = {ShareWithin2Sigma(run, 0, from), ShareWithin2Sigma(run, 1, from)};
  std::printf("hover accelerometer x20: VALID %.3f, MAE %.4f %.4f, 2 sigma %.3f %.3f, mismatches %lld\n", valid_share,
              mae[0], mae[1], within[0], within[1], static_cast<long long>(run.health.consistency.raised_count));
  EXPECT_EQ(run.health.consistency.raised_count, 0);
  EXPECT_GE(valid_share, 0.95);
  for (int i = 0; i < 2; ++i) {
    EXPECT_LE(mae[i], 0.10) << i;  // the target
    EXPECT_GE(within[i], 0.93) << i;
    EXPECT_LE(within[i], 0.98) << i;
  }
}

// Until accel_noise_trust_samples pairs the accelerometer is fused with its
// scale's upper bound (CautiousScale): fused with the scale as it was, its
// first samples pulled the thrust scales and offsets with a confidence the
// filter kept for seconds, and on seed 3 the worst 2 s window of VALID
// estimates from lift-off held 0.772 of its errors inside 2 sigma (issue
// 36: at least 0.80). Measured with the bound: 0.817 (seeds 1-12:
// 0.817-0.962).
TEST(NoiseAdaptation, ANoisyAccelerometerIsFusedCautiouslyUntilItsNoiseIsLearned) {
  const ScenarioRun run = RunScenario(
      LoadScenario(ScenarioFile("hover"), {"sensors.imu.accel_noise_m_s2=1.0", "scenario.seed=3"}), ReferenceConfig());
  const MismatchTargetFigures f = EvaluateMismatchTargets(run.forces, run.truth, -1, MismatchTargets{});
  std::printf("hover accelerometer x20, seed 3: worst 2 s window %.3f, VALID %.3f, MAE %.4f\n", f.worst_window_share,
              f.valid_share, f.valid_mae_n);
  EXPECT_EQ(run.health.consistency.raised_count, 0);
  EXPECT_GE(f.worst_window_share, 0.80);  // the target
  EXPECT_GE(f.valid_share, 0.95);
  EXPECT_LE(f.valid_mae_n, 0.10);
}

// CautiousScale: before trust_samples pairs the scale's upper confidence
// bound, scale (1 + trust_sigmas sqrt(2 / max(n, 1))) capped at scale_max;
// from trust_samples on the scale itself; always the scale when not
// learning.
TEST(NoiseAdaptation, IsFusedAtItsUpperBoundUntilTrusted) {
  NoiseAdaptationSettings settings = AccelerometerNoiseSettings(EkfOptions());
  settings.file_variance = kFileVariance;
  settings.min_samples = 5;
  settings.trust_samples = 50;
  settings.trust_sigmas = 3.0;
  NoiseAdaptation accelerometer(settings);
  EXPECT_DOUBLE_EQ(accelerometer.CautiousScale(0), 1.0 + 3.0 * std::sqrt(2.0));
  SyntheticRun run;
  run.true_variance_rad2 = 400.0 * kFileVariance;
  run.outcome = FusionOutcome::kRejectedGate;  // gated while the scale is still low
  int64_t utime = 0;
  Feed(run, 50, &accelerometer, &utime);  // 49 pairs
  ASSERT_EQ(accelerometer.samples(), 49);
  const double bound = std::min(settings.scale_max, accelerometer.scale(0) * (1.0 + 3.0 * std::sqrt(2.0 / 49.0)));
  EXPECT_DOUBLE_EQ(accelerometer.CautiousScale(0), bound);
  EXPECT_GT(accelerometer.CautiousScale(0), accelerometer.scale(0));
  Feed(run, 1, &accelerometer, &utime, 8);
  EXPECT_DOUBLE_EQ(accelerometer.CautiousScale(0), accelerometer.scale(0));
  settings.enabled = false;
  EXPECT_DOUBLE_EQ(NoiseAdaptation(settings).CautiousScale(0), 1.0);
}

// The same flight with the file's noise: the scale stays near 1 (measured
// at most 1.070) and the figures are today's (MAE 0.0669 / 0.0676 N from
// 5 s, 2-sigma share 0.962 / 0.961; birotor-eval before: 0.067 / 0.068, 0.961).
TEST(NoiseAdaptation, GentleFlightWithTheFilesNoise) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gentle")), ReferenceConfig());
  double largest = 0;
  for (const GaugeOffsetSample& s : run.gauge_offsets) {
    largest = std::max({largest, s.strain_noise_scale[0], s.strain_noise_scale[1]});
  }
  const int64_t from = run.pairs.front().utime + 5000000;
  std::printf("gentle file noise: largest scale %.3f, MAE %.4f %.4f, 2 sigma %.3f %.3f\n", largest,
              ForceMae(run, 0, from), ForceMae(run, 1, from), ShareWithin2Sigma(run, 0, from),
              ShareWithin2Sigma(run, 1, from));
  EXPECT_GE(largest, 1.0);
  EXPECT_LE(largest, 1.105);
}

// What the adaptation must not absorb: with the gauges twice as noisy, a
// wrong stiffness, gauge scale, mass or tip mass is still raised when it is
// with the file's noise (docs/mismatch.md: 0.011 s after the first
// estimate; the tip mass by the arm mode at 0.852 s) and named the same.
// Measured with noise x2: raised at 0.010 s (tip mass 0.852 s), held for
// the rest of the flight (share of estimates with MODEL_MISMATCH from the
// raise: 1.000; 0.983 for the gauge scale 1.3, cleared 14.50-14.75 s: the
// learned noise weighs the noisier gauges less, so their scale error is
// weaker evidence than with the file's noise).
TEST(NoiseAdaptation, AMismatchedVehicleWithNoisyGaugesIsStillRaised) {
  const struct {
    const char* scenario;
    double raised_s;  // measured
    MismatchParameter parameter;
  } kCases[] = {
      {"mismatch_stiffness_plus20", 0.011, MismatchParameter::kStiffnessOrGaugeScale},
      {"mismatch_gauge_scale_1p3", 0.011, MismatchParameter::kStiffnessOrGaugeScale},
      {"mismatch_payload_plus15", 0.011, MismatchParameter::kMass},
      {"mismatch_tip_mass_plus20", 0.852, MismatchParameter::kTipMass},
  };
  for (const auto& c : kCases) {
    // The tip mass judged against the file's (learning it, the default,
    // learns +20 % instead of raising it: ArmModeScenarios.TipMassIsLearned).
    EstimatorConfig config = ReferenceConfig();
    config.model_consistency.arm_mode_learn_tip_mass = false;
    const ScenarioRun run =
        RunScenario(LoadScenario(ScenarioFile(c.scenario), {"sensors.strain.noise_rad=4e-5"}), config);
    const int64_t start = run.pairs.front().utime;
    int64_t first_raise = -1, raised = 0, since = 0;
    for (const PairedSample& p : run.pairs) {
      const bool mismatch = p.status & kStatusModelMismatch;
      if (mismatch && first_raise < 0) first_raise = p.utime;
      if (first_raise < 0) continue;
      ++since;
      raised += mismatch;
    }
    const double first_s = (first_raise - start) * 1e-6;
    const double share = since > 0 ? static_cast<double>(raised) / since : 0.0;
    std::printf("%s noise x2: first raised at %.3f s, share raised since %.3f\n", c.scenario, first_s, share);
    ASSERT_GE(first_raise, 0) << c.scenario;
    EXPECT_LE(first_s, 1.5 * c.raised_s) << c.scenario;
    EXPECT_GE(share, 0.975) << c.scenario;  // 1.5x the 1.7 % not raised
    // The first raise's parameter (a later re-raise may name another).
    if (run.health.consistency.raised_count == 1) EXPECT_EQ(run.health.consistency.parameter, c.parameter);
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor

// The arm-mode test (estimator/arm_mode_monitor.h, issue 27): the frequency
// estimate on synthetic resonances, the file's mode from the model, the
// ground phase, and the scenarios: tip mass +-20 % raised and named, no raise
// on the matching files and on c_T / tau_m mismatches. Figures measured on
// the development VM (docs/mismatch.md); bounds at most 1.5x.
#include "estimator/arm_mode_monitor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "estimator/model_consistency.h"
#include "estimator/tip_mass_learning.h"
#include "evaluation/mismatch_metrics.h"
#include "tests/estimator/consistency_step.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

constexpr double kDt = 1e-3;  // the gauges' 1 kHz (reference-vehicle.md)

// A resonance of frequency f_hz and damping ratio zeta driven by white noise
// (the AR(2) of its impulse-invariant poles), amplitude sigma_drive per
// sample, plus white measurement noise sigma_noise, through the estimator
// centred at centre_hz for duration_s; returns its last estimate, with
// excess_noise taken out of the fit (FrequencyHz).
double EstimateOnResonance(double f_hz, double zeta, double centre_hz, double sigma_drive, double sigma_noise,
                           double duration_s, unsigned seed, double excess_noise = 0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const double w = 2 * M_PI * f_hz;
  const double r = std::exp(-zeta * w * kDt);
  const double c1 = 2 * r * std::cos(w * kDt * std::sqrt(1 - zeta * zeta)), c2 = -r * r;
  ResonanceFrequencyEstimator estimator;
  estimator.Start(centre_hz, 2.0, 0.5, kDt, 0.0);
  double x1 = 0, x2 = 0;
  for (int n = 0; n < static_cast<int>(duration_s / kDt); ++n) {
    const double x = c1 * x1 + c2 * x2 + sigma_drive * normal(rng);
    x2 = x1;
    x1 = x;
    estimator.Add(x + sigma_noise * normal(rng));
  }
  return estimator.FrequencyHz(excess_noise);
}

TEST(ResonanceFrequency, FindsTheModeInNoise) {
  // The file's mode (65.03 Hz, damping ratio 0.019: reference-vehicle.md)
  // under the gauges' noise (2e-5 rad per arm, sqrt(2) of it in b1 - b2),
  // driven to an excitation of about 5 (the flights: 2.5-6.8, printed by
  // ArmModeScenarios below). Measured over seeds 1-5: up to 0.0093.
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const double f = EstimateOnResonance(65.03, 0.019, 65.03, 2e-6, 2.8e-5, 3.0, seed);
    std::printf("seed %u: mode 65.03 Hz read %.2f Hz\n", seed, f);
    EXPECT_NEAR(f / 65.03 - 1, 0.0, 0.014) << seed;
  }
}

TEST(ResonanceFrequency, NoiseBeyondTheFilesIsTakenOutOfTheFit) {
  // The gauges twice as noisy as the file (issue 36: 5.6e-5 in b1 - b2):
  // the noise pulls the reading towards the band-pass (measured over seeds
  // 1-5: +1.2 % to +2.8 %); with the excess over the file's noise,
  // sqrt(5.6^2 - 2.8^2) 1e-5, taken out of the sums it reads closer to the
  // mode on every seed (measured +0.2 % to +1.9 %).
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const double excess = std::sqrt(5.6e-5 * 5.6e-5 - 2.8e-5 * 2.8e-5);
    const double raw = EstimateOnResonance(65.03, 0.019, 65.03, 2e-6, 5.6e-5, 3.0, seed) / 65.03 - 1;
    const double corrected = EstimateOnResonance(65.03, 0.019, 65.03, 2e-6, 5.6e-5, 3.0, seed, excess) / 65.03 - 1;
    std::printf("seed %u: noise x2 reads %+.4f, corrected %+.4f\n", seed, raw, corrected);
    EXPECT_LT(std::abs(corrected), std::abs(raw)) << seed;
    EXPECT_NEAR(corrected, 0.0, 0.028) << seed;
  }
}

TEST(ResonanceFrequency, ShiftedModeReadsShiftedButPulledToTheCentre) {
  // Tip mass +20 %: 65.03 / sqrt(1.2) = 59.36 Hz seen through the band-pass
  // at 65.03 Hz; -20 %: 72.71 Hz. The band-pass pulls towards its centre but
  // the reading stays beyond the limit (arm_mode_limit 0.040) and short of
  // the true shift (-8.7 %, +11.8 %).
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const double heavy = EstimateOnResonance(59.36, 0.019, 65.03, 2e-6, 2.8e-5, 3.0, seed) / 65.03 - 1;
    const double light = EstimateOnResonance(72.71, 0.019, 65.03, 2e-6, 2.8e-5, 3.0, seed) / 65.03 - 1;
    std::printf("seed %u: +20 %% reads %+.4f, -20 %% reads %+.4f\n", seed, heavy, light);
    EXPECT_LT(heavy, -0.040) << seed;
    EXPECT_GT(heavy, -0.0872) << seed;
    EXPECT_GT(light, 0.040) << seed;
    EXPECT_LT(light, 0.1182) << seed;
  }
}

TEST(ArmMode, NoiseAloneIsNotJudged) {
  // White gauge noise only (no resonance): the fit would read the band-pass
  // (+10 % measured), so the excitation guard (arm_mode_min_excitation 1.5)
  // keeps it from judging; noise alone has an excitation of about 1.
  ModelConsistencyOptions options;
  ArmModeMonitor monitor(options, ArmModeExpectation::At(65.03), 2e-5);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double highest = 0;
  for (int n = 0; n < 5000; ++n) {
    const double d[2] = {-1e-3 + 2e-5 * normal(rng), 1e-3 + 2e-5 * normal(rng)};
    EXPECT_FALSE(monitor.Add(n * 1000, d, true, false));
    highest = std::max(highest, monitor.state().excitation);
  }
  std::printf("noise alone: highest excitation %.2f\n", highest);
  EXPECT_NEAR(highest, 1.0, 0.3);
  EXPECT_TRUE(std::isnan(monitor.state().frequency_hz));
  EXPECT_EQ(monitor.state().peak_abs_error, 0.0);
}

TEST(ArmMode, FileModeFromTheModel) {
  // reference-vehicle.md (/work/shared/spec) and birotor-analyze: 65.03 Hz.
  BirotorParams p = BirotorModelOf(testing_support::ReferenceConfig().vehicle);
  EXPECT_NEAR(SymmetricArmModeHz(p), 65.03, 0.01);
  // The tip mass +20 %: 60.11 Hz (birotor-analyze --params with m_p
  // 0.345744 kg; the body takes part: sqrt(1 / 1.2) alone would be 59.36 Hz).
  p.tip_mass_kg *= 1.2;
  EXPECT_NEAR(SymmetricArmModeHz(p), 60.11, 0.01);
}

// The tabulated model's inverse against a root find on the model itself
// (SymmetricArmModeHz): m_p +20 % reads 60.11 Hz (birotor-analyze).
TEST(TipMassLearning, MapInvertsTheModel) {
  const BirotorParams p = BirotorModelOf(testing_support::ReferenceConfig().vehicle);
  const ArmModeTipMassMap map = ArmModeTipMassMap::Of(p);
  ASSERT_FALSE(map.empty());
  EXPECT_NEAR(std::exp(map.LogHz(1.0)), 65.03, 0.01);
  EXPECT_NEAR(std::exp(map.LogHz(1.2)), 60.11, 0.02);
  for (double hz : {58.0, 60.11, 65.03, 71.79, 75.0}) {
    const double root_kg = TipMassForArmModeHz(p, hz, 0.5 * p.tip_mass_kg, 1.8 * p.tip_mass_kg);
    EXPECT_NEAR(map.RatioAt(hz) * p.tip_mass_kg, root_kg, 2e-4 * p.tip_mass_kg) << hz;
  }
  EXPECT_NEAR(TipMassForArmModeHz(p, 60.11, 0.1, 0.6), 1.2 * p.tip_mass_kg, 0.002 * p.tip_mass_kg);
  EXPECT_NEAR(TipMassForArmModeHz(p, 71.79, 0.1, 0.6), 0.8 * p.tip_mass_kg, 0.002 * p.tip_mass_kg);
}

// Readings of a mode f(1.2) taken with the band-pass centred there (no pull)
// move r from the prior to 1.2; 10 s of readings (10 independent of 1.5 %,
// one per 2 tau = 1 s; slope d ln f / d r -0.38) leave sigma 0.015 / 0.38 / sqrt(10) = 0.0125.
TEST(TipMassLearning, ReadingsOfTheModeLearnTheTipMass) {
  const ArmModeTipMassMap map = ArmModeTipMassMap::Of(BirotorModelOf(testing_support::ReferenceConfig().vehicle));
  TipMassLearner learner(TipMassLearner::Options(), map);
  EXPECT_NEAR(learner.ratio_std(), 0.15, 1e-12);
  const double hz = std::exp(map.LogHz(1.2));
  for (int n = 0; n < 10000; ++n) learner.AddReading(hz, hz, 0.5, 1e-3);
  EXPECT_NEAR(learner.ratio(), 1.2, 0.005);
  EXPECT_NEAR(learner.ratio_std(), 0.015 / 0.38 / std::sqrt(10.0), 0.001);
  // The band-pass's pull is undone: centred on the file's mode, a reading
  // p (f - c) from it is the mode f.
  EXPECT_NEAR(learner.CorrectedHz(65.03 + 0.75 * (hz - 65.03), 65.03), hz, 1e-9);
}

// A bias every reading shares (a mode read on some gauges only) does not
// average away: the same readings learn the same r, and the sigma keeps the
// bias's share, (1 - P / P_prior) 0.01 / 0.38 in quadrature with the
// filter's 0.0125 (above): 0.029, where the filter alone says 0.0125. At the
// prior it adds nothing; a resumed sigma holds it already.
TEST(TipMassLearning, ACommonReadingBiasStaysInTheSigma) {
  const ArmModeTipMassMap map = ArmModeTipMassMap::Of(BirotorModelOf(testing_support::ReferenceConfig().vehicle));
  TipMassLearner::Options biased_options;
  biased_options.reading_bias = 0.01;
  TipMassLearner biased(biased_options, map), unbiased(TipMassLearner::Options(), map);
  EXPECT_NEAR(biased.ratio_std(), 0.15, 1e-12);
  const double hz = std::exp(map.LogHz(1.2));
  for (int n = 0; n < 10000; ++n) {
    biased.AddReading(hz, hz, 0.5, 1e-3);
    unbiased.AddReading(hz, hz, 0.5, 1e-3);
  }
  EXPECT_EQ(biased.ratio(), unbiased.ratio());
  const double bias = 0.01 / std::fabs(map.LogHzSlope(biased.ratio()));
  EXPECT_NEAR(biased.ratio_std(), std::hypot(unbiased.ratio_std(), bias), 0.001);
  EXPECT_GT(biased.ratio_std(), 2.0 * unbiased.ratio_std());
  TipMassLearner resumed(biased_options, map);
  const double file_kg = map.file_tip_mass_kg();
  ASSERT_TRUE(resumed.Resume(biased.tip_mass_kg(), biased.ratio_std() * file_kg));
  EXPECT_NEAR(resumed.ratio_std(), biased.ratio_std(), 0.002);
}

// Resumed from an earlier run (the state file): r and its sigma are the
// persisted ones, and readings refine them from there (towards the mode
// read, to a narrower sigma than a fresh learner's after the same
// readings); nothing is resumed without a model or from a value that is
// not one.
TEST(TipMassLearning, ResumesFromAnEarlierRunsValue) {
  const ArmModeTipMassMap map = ArmModeTipMassMap::Of(BirotorModelOf(testing_support::ReferenceConfig().vehicle));
  const double file_kg = map.file_tip_mass_kg();
  TipMassLearner learner(TipMassLearner::Options(), map);
  EXPECT_FALSE(learner.Resume(NAN, 0.003));
  EXPECT_FALSE(learner.Resume(0.34, 0.0));
  EXPECT_FALSE(TipMassLearner().Resume(0.34, 0.003));  // no model: not learned
  ASSERT_TRUE(learner.Resume(1.19 * file_kg, 0.01 * file_kg));
  EXPECT_NEAR(learner.ratio(), 1.19, 1e-12);
  EXPECT_NEAR(learner.ratio_std(), 0.01, 1e-12);
  EXPECT_EQ(learner.readings(), 0);
  const double hz = std::exp(map.LogHz(1.2));
  TipMassLearner fresh(TipMassLearner::Options(), map);
  for (int n = 0; n < 1000; ++n) {
    learner.AddReading(hz, hz, 0.5, 1e-3);
    fresh.AddReading(hz, hz, 0.5, 1e-3);
  }
  EXPECT_EQ(learner.readings(), 1000);
  EXPECT_GT(learner.ratio(), 1.19);
  EXPECT_LT(learner.ratio(), 1.2);
  EXPECT_LT(learner.ratio_std(), 0.01);
  EXPECT_LT(learner.ratio_std(), fresh.ratio_std());
}

TEST(ArmMode, AGaugeScaleInTheFileWidensWhatTheModeMayBe) {
  // A scale s in the file may be a gauge that reads s (the mode stays) or a
  // stiffness k / s (birotor-identify --learned writes a learned strain
  // scale there): the mode may be anywhere between. Stiffness +20 % learned
  // and deployed as s = 0.896 (tests/tools/learned_deploy_test.cc): the
  // model gives 65.03-68.70 Hz (k / 0.896: +5.6 %, about sqrt(1 / 0.896)).
  BirotorParams p = BirotorModelOf(testing_support::ReferenceConfig().vehicle);
  ArmModeExpectation ideal = ExpectedArmMode(p);
  EXPECT_EQ(ideal.low_hz, ideal.file_hz);
  EXPECT_EQ(ideal.high_hz, ideal.file_hz);
  p.gauge_scale[0] = 0.896;
  const ArmModeExpectation e = ExpectedArmMode(p);
  EXPECT_NEAR(e.file_hz, 65.03, 0.01);
  EXPECT_EQ(e.low_hz, e.file_hz);
  EXPECT_NEAR(e.high_hz, 68.70, 0.01);
}

TEST(ArmMode, LearnedStrainScalesWidenWhatTheModeMayBe) {
  // While the EKF learns strain scales (learn_strain_scale) a learned g_i is
  // a gauge scale or a stiffness k / g_i: within two sigma of g_i the mode
  // may be anywhere between. The model's d ln f / d ln k at the reference
  // file: 0.5000 (the body's coupling hardly moves it from 1/2).
  const ArmModeExpectation file = ExpectedArmMode(BirotorModelOf(testing_support::ReferenceConfig().vehicle));
  std::printf("stiffness exponent %.4f\n", file.stiffness_exponent);
  EXPECT_NEAR(file.stiffness_exponent, 0.5, 0.01);
  const double exact[2] = {0.896, 1.0}, none[2] = {0.0, 0.0};
  const ArmModeExpectation deployed = WithLearnedStrainScales(file, exact, none);
  EXPECT_EQ(deployed.low_hz, file.file_hz);
  EXPECT_NEAR(deployed.high_hz, 68.70, 0.05);  // as the deployed gauge scale 0.896 above
  const double one[2] = {1.0, 1.0}, wide[2] = {0.05, 0.05};
  const ArmModeExpectation unsure = WithLearnedStrainScales(file, one, wide);
  EXPECT_NEAR(unsure.low_hz, file.file_hz * std::pow(1.1, -file.stiffness_exponent), 1e-9);
  EXPECT_NEAR(unsure.high_hz, file.file_hz * std::pow(0.9, -file.stiffness_exponent), 1e-9);
  const double not_learned[2] = {std::nan(""), std::nan("")};
  const ArmModeExpectation same = WithLearnedStrainScales(file, not_learned, wide);
  EXPECT_EQ(same.low_hz, file.low_hz);
  EXPECT_EQ(same.high_hz, file.high_hz);
}

TEST(ArmMode, NoTestOnTheGround) {
  ModelConsistencyOptions options;
  ArmModeMonitor monitor(options, ArmModeExpectation::At(65.03), 2e-5);
  const double b[2] = {-1e-3, 1e-3};
  for (int n = 0; n < 3000; ++n) {
    // A ringing at 55 Hz that would raise in the air.
    const double d[2] = {b[0] + 1e-4 * std::sin(2 * M_PI * 55 * n * kDt), b[1]};
    EXPECT_FALSE(monitor.Add(n * 1000, d, false, false));
  }
  EXPECT_TRUE(std::isnan(monitor.state().frequency_hz));
  // In the air the same ringing raises after settle + time constant + raise_s (0.85 s).
  for (int n = 3000; n < 5000; ++n) {
    const double d[2] = {b[0] + 1e-4 * std::sin(2 * M_PI * 55 * n * kDt), b[1]};
    monitor.Add(n * 1000, d, true, false);
  }
  EXPECT_TRUE(monitor.state().mismatch);
  EXPECT_NEAR(monitor.state().raised_utime * 1e-6, 3.852, 0.002);
  EXPECT_LT(monitor.state().relative_error, -0.040);
}

TEST(ArmMode, RaisesOnADetunedModeAndClearsWhenItIsBack) {
  // 2 s ringing at 55 Hz (-15 %: raised after settle 0.1 + time constant
  // 0.5 + raise 0.25 s), then the file's 65.03 Hz: cleared once within half
  // the limit for arm_mode_clear_s (2 s).
  ArmModeMonitor monitor(ModelConsistencyOptions(), ArmModeExpectation::At(65.03), 2e-5);
  int64_t cleared_us = -1;
  for (int n = 0; n < 8000; ++n) {
    const double hz = n < 2000 ? 55.0 : 65.03;
    const double d[2] = {-1e-3 + 1e-4 * std::sin(2 * M_PI * hz * n * kDt), 1e-3};
    const bool mismatch = monitor.Add(n * 1000, d, true, false);
    if (n == 1999) {
      EXPECT_TRUE(mismatch);
    }
    if (n >= 2000 && !mismatch && cleared_us < 0) cleared_us = n * 1000;
  }
  EXPECT_EQ(monitor.state().raised_count, 1);
  EXPECT_NEAR(monitor.state().raised_utime * 1e-6, 0.851, 0.002);
  // Measured 4.687 s: the weighted fit forgets 55 Hz with its 0.5 s time
  // constant, then 2 s within 0.020.
  std::printf("cleared at %.3f s\n", cleared_us * 1e-6);
  EXPECT_GT(cleared_us * 1e-6, 4.0);
  EXPECT_LT(cleared_us * 1e-6, 5.0);
}

// Feeds 2 s of airborne strain (b1 - b2 ringing at ring_hz with amplitude
// ring_rad, or quiet) and returns, per 1 ms, the published sigma of rotor 1
// and whether VALID stood (the method says VALID and sigma 0.08 N).
struct AwaitRun {
  std::vector<double> sigma_n;
  std::vector<bool> valid;
};
AwaitRun FeedAwaiting(const ModelConsistencyOptions& options, double ring_rad) {
  ArmModeExpectation expected = ArmModeExpectation::At(65.03);
  expected.tip_weight_n = 2.0;  // m_p g [N]
  ModelConsistencyMonitor monitor(options, expected, 2e-5);
  FusionReport report;  // one report with an innovation: the method is judged
  report.source = FusionSource::kStrain;
  report.outcome = FusionOutcome::kFused;
  report.size = 1;
  report.innovation_variance(0) = 1;
  report.nis = 0;
  monitor.Add(report);
  AwaitRun run;
  for (int n = 0; n < 2000; ++n) {
    const double ring = ring_rad * std::sin(2 * M_PI * 65.03 * n * kDt);
    const double d[2] = {-1e-3 + ring, 1e-3};
    monitor.AddStrain(n * 1000, d, true, false);
    ForceEstimate estimate;
    estimate.utime = n * 1000;
    estimate.status = kStatusValid;
    estimate.force_std_n[0] = estimate.force_std_n[1] = 0.08;
    JudgeAndCompose(&monitor, &estimate);
    run.sigma_n.push_back(estimate.force_std_n[0]);
    run.valid.push_back((estimate.status & kStatusValid) != 0);
  }
  return run;
}

TEST(ArmMode, UnconfirmedTipMassWidensSigmaUntilTheModeAgrees) {
  // The file's mode read from 0.6 s (settle 0.1 s + time constant 0.5 s);
  // the readings' mean agrees after a time constant of readings (half an
  // independent reading): agreed at 1.1 s. Until then each sigma carries 15 %
  // of m_p g (2 N): hypot(0.08, 0.30) = 0.310 N. VALID stands throughout by
  // default.
  const AwaitRun run = FeedAwaiting(ModelConsistencyOptions(), 1e-4);
  const double widened = std::hypot(0.08, 0.15 * 2.0);
  // From the run's second interval on (the first sample starts nothing,
  // the second starts the run).
  EXPECT_NEAR(run.sigma_n[0], 0.08, 1e-12);
  EXPECT_NEAR(run.sigma_n[2], widened, 1e-12);
  EXPECT_NEAR(run.sigma_n[1090], widened, 1e-12);
  EXPECT_NEAR(run.sigma_n[1110], 0.08, 1e-12);
  EXPECT_NEAR(run.sigma_n[1999], 0.08, 1e-12);
  for (bool v : run.valid) EXPECT_TRUE(v);
}

TEST(ArmMode, ValidWaitsForTheAgreementWhenAsked) {
  ModelConsistencyOptions options;
  options.arm_mode_valid_needs_reading = true;
  const AwaitRun run = FeedAwaiting(options, 1e-4);
  EXPECT_FALSE(run.valid[2]);
  const size_t first_valid = std::find(run.valid.begin() + 2, run.valid.end(), true) - run.valid.begin();
  // First reading at 0.601 s (the run's first interval at 1 ms), agreed 0.5 s later.
  EXPECT_NEAR(first_valid * 1e-3, 1.101, 0.0015);
  EXPECT_TRUE(std::all_of(run.valid.begin() + first_valid, run.valid.end(), [](bool v) { return v; }));
}

TEST(ArmMode, AQuietModeIsNotWaitedForButConfirmsNothing) {
  // Noise-free and not ringing: nothing to read. The wait ends when the
  // first reading is due (0.6 s): VALID (when asked) from then. The tip
  // mass stays unconfirmed, so each sigma keeps the prior's 15 % of m_p g
  // for the whole flight (a calm hover with the tip mass 20 % off is 0.56 N
  // off on the reference vehicle: within 2 sigma, not VALID and wrong).
  ModelConsistencyOptions options;
  options.arm_mode_valid_needs_reading = true;
  const AwaitRun run = FeedAwaiting(options, 0.0);
  const double widened = std::hypot(0.08, 0.15 * 2.0);
  EXPECT_NEAR(run.sigma_n[590], widened, 1e-12);
  EXPECT_FALSE(run.valid[590]);
  EXPECT_NEAR(run.sigma_n[610], widened, 1e-12);
  EXPECT_NEAR(run.sigma_n[1999], widened, 1e-12);
  EXPECT_TRUE(run.valid[610]);
  EXPECT_TRUE(run.valid[1999]);
}

}  // namespace

namespace testing_support {
namespace {

struct ArmModeFigures {
  double raised_s = -1;  // first MODEL_MISMATCH after the first estimate [s]; -1 never
  int64_t mismatch = 0, valid_after_raise = 0;
  std::string parameter;
  double peak_abs_error = 0;            // the arm-mode test's largest |f / f_file - 1| [1]
  double worst_valid_window_share = 1;  // evaluation/mismatch_metrics.h [1]
};

// The issue-27 test alone: the file's tip mass, judged against the file's mode.
EstimatorConfig NotLearningTipMass() {
  EstimatorConfig config = ReferenceConfig();
  config.model_consistency.arm_mode_learn_tip_mass = false;
  return config;
}

// Learning the tip mass (arm_mode_learn_tip_mass, on by default: the
// shipped file as it is).
EstimatorConfig LearningTipMass() {
  EstimatorConfig config = ReferenceConfig();
  EXPECT_TRUE(config.model_consistency.arm_mode_learn_tip_mass);
  return config;
}

ArmModeFigures FlyScenario(const Scenario& scenario, const std::string& name, const EstimatorConfig& config) {
  const ScenarioRun run = RunScenario(scenario, config);
  ArmModeFigures f;
  const int64_t start = run.forces.front().utime;
  for (const ForceEstimate& e : run.forces) {
    if (e.status & kStatusModelMismatch) {
      if (f.raised_s < 0) f.raised_s = (e.utime - start) * 1e-6;
      ++f.mismatch;
    }
    if (f.raised_s >= 0 && (e.status & kStatusValid)) ++f.valid_after_raise;
  }
  f.parameter = MismatchParameterName(run.health.consistency.parameter);
  f.peak_abs_error = run.health.consistency.arm_mode.peak_abs_error;
  f.worst_valid_window_share = EvaluateMismatch(run.forces, run.truth, MismatchEvalOptions()).worst_valid_window_share;
  std::printf(
      "%s: raised %.3f s, %s, mismatch %lld, VALID after %lld, arm-mode peak |error| %.4f, last %.4f, lowest "
      "excitation %.1f\n",
      name.c_str(), f.raised_s, f.parameter.c_str(), static_cast<long long>(f.mismatch),
      static_cast<long long>(f.valid_after_raise), f.peak_abs_error, run.health.consistency.arm_mode.relative_error,
      run.health.consistency.arm_mode.lowest_excitation);
  return f;
}

ArmModeFigures Fly(const std::string& name, const EstimatorConfig& config = ReferenceConfig()) {
  return FlyScenario(LoadScenario(ScenarioFile(name)), name, config);
}

// Tip mass +10 % (the gentle flight of mismatch_tip_mass_plus20 with both
// tips at 1.1 m_p): its mode reads -3 %, inside the limit, so nothing is
// raised, and the mean of the readings never confirms the file's tip mass:
// the estimates stay VALID 0.28 N off with the prior's 0.42 N in their
// sigma. Measured: worst 2 s VALID share 1.000 (0.072 when a stretch of
// readings within half the limit confirmed the tip mass).
TEST(ArmModeScenarios, TipMassTenPercentHeavierIsNeverConfirmed) {
  Scenario scenario = LoadScenario(ScenarioFile("mismatch_tip_mass_plus20"));
  for (int i = 0; i < scenario.vehicle.arm_count; ++i)
    scenario.vehicle.arms[static_cast<size_t>(i)].tip_mass_kg = 0.316932;
  const ArmModeFigures f = FlyScenario(scenario, "tip mass +10 %", NotLearningTipMass());
  EXPECT_GE(f.worst_valid_window_share, 0.99);
}

// A method whose model has no m_p (the linear KF) cannot fly a learned one:
// the tip mass is not learned there, and the file's is judged (issue 27).
TEST(ArmModeScenarios, AMethodThatDoesNotFlyTheTipMassJudgesTheFiles) {
  EstimatorConfig config = LearningTipMass();
  config.method = "linear_kf";
  const ArmModeFigures f = Fly("mismatch_tip_mass_plus20", config);
  EXPECT_GE(f.raised_s, 0.0);
  EXPECT_LE(f.raised_s, 1.0);
  EXPECT_EQ(f.parameter, "tip_mass");
  EXPECT_GE(f.worst_valid_window_share, 0.80);  // the prior in the sigma before the raise
}

TEST(ArmModeScenarios, TipMassIsRaisedAndNamed) {
  for (const char* name : {"mismatch_tip_mass_plus20", "mismatch_tip_mass_minus20"}) {
    const ArmModeFigures f = Fly(name, NotLearningTipMass());
    EXPECT_GE(f.raised_s, 0.0) << name;
    EXPECT_LE(f.raised_s, 1.0) << name;  // measured 0.852 s; the target: within 1 s
    EXPECT_EQ(f.parameter, "tip_mass") << name;
    EXPECT_EQ(f.valid_after_raise, 0) << name;  // VALID withdrawn from the raise to the end
    // Before the raise the estimates are VALID and 0.56 N off, with sigma
    // widened by the unconfirmed tip mass: measured 1.000 (+20 %) and 0.999
    // (-20 %), 0.990-1.000 on seeds 1-8; the target is 0.80 (birotor-eval,
    // docs/mismatch.md).
    EXPECT_GE(f.worst_valid_window_share, 0.80) << name;
  }
}

// Learning the tip mass (arm_mode_learn_tip_mass): tip mass +-20 % in the gentle
// flight (the shipped scenarios, their seed) is learned, VALID throughout,
// accurate after 5 s with an honest sigma (docs/mismatch.md, "Learning the
// tip mass"; birotor-eval --mismatch-targets seeds 1-5: MAE 0.067-0.091 N,
// share 0.95-0.97).
TEST(ArmModeScenarios, TipMassIsLearned) {
  for (const char* name : {"mismatch_tip_mass_plus20", "mismatch_tip_mass_minus20", "tip mass +10 %"}) {
    const bool ten_percent = std::string(name) == "tip mass +10 %";
    Scenario scenario = LoadScenario(ScenarioFile(ten_percent ? "mismatch_tip_mass_plus20" : name));
    for (int i = 0; ten_percent && i < scenario.vehicle.arm_count; ++i)
      scenario.vehicle.arms[static_cast<size_t>(i)].tip_mass_kg = 0.316932;
    const ScenarioRun run = RunScenario(scenario, LearningTipMass());
    const MismatchEvalResult r = EvaluateMismatch(run.forces, run.truth, MismatchEvalOptions());
    const ArmModeState& arm = run.health.consistency.arm_mode;
    std::printf("%s: m_p %.4f +- %.4f kg, MAE %.3f / %.3f N, share %.3f, VALID %.3f, window %.3f\n", name,
                arm.tip_mass_kg, arm.tip_mass_std_kg, r.mae_after_settle_n[0], r.mae_after_settle_n[1],
                r.share_after_settle, r.valid_share, r.worst_valid_window_share);
    const double truth_kg =
        ten_percent ? 0.316932 : (std::string(name) == "mismatch_tip_mass_plus20" ? 0.345744 : 0.230496);
    EXPECT_TRUE(arm.learning) << name;
    EXPECT_GT(arm.tip_mass_change_probability, 0.999) << name;  // the learned m_p, not the file's
    EXPECT_NEAR(arm.tip_mass_kg, truth_kg, 3.0 * arm.tip_mass_std_kg + 0.005) << name;
    EXPECT_EQ(r.mismatch_estimates, 0) << name;
    EXPECT_GE(r.valid_share, 0.98) << name;
    EXPECT_LE(std::max(r.mae_after_settle_n[0], r.mae_after_settle_n[1]), 0.10) << name;
    EXPECT_GE(r.share_after_settle, 0.90) << name;
    EXPECT_LE(r.share_after_settle, 0.98) << name;
  }
}

// The matching file: the readings confirm the file's m_p, which then takes
// nearly all the weight (P(changed) below arm_mode_tip_mass_file_accepted_below):
// the filter flies the file's m_p and the forces carry no tip-mass sigma, as
// without learning (docs/mismatch.md). Measured: P(changed) 0.0096 / 0.0089 /
// 0.0383, published sigma sqrt(s^2 + (r - 1)^2) 1.2 / 1.1 / 2.5 % of m_p.
TEST(ArmModeScenarios, MatchingFileFliesTheFilesTipMass) {
  for (const char* name : {"gentle", "hover", "aggressive"}) {
    const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile(name)), LearningTipMass());
    const ArmModeState& arm = run.health.consistency.arm_mode;
    std::printf("%s: m_p %.5f +- %.5f kg, P(changed) %.4f\n", name, arm.tip_mass_kg, arm.tip_mass_std_kg,
                arm.tip_mass_change_probability);
    EXPECT_TRUE(arm.file_tip_mass_agreed) << name;
    EXPECT_LT(arm.tip_mass_change_probability, 0.1) << name;
    EXPECT_DOUBLE_EQ(arm.tip_mass_kg, 0.28812) << name;
    EXPECT_EQ(arm.force_tip_mass_std, 0.0) << name;
    EXPECT_GT(arm.tip_mass_std_kg, 0.0) << name;
    EXPECT_LT(arm.tip_mass_std_kg, 0.04 * 0.28812) << name;
  }
}

TEST(ArmModeScenarios, MatchingFileAndOtherParametersNeverRaise) {
  struct Case {
    const char* name;
    double peak_abs_error;  // measured
  };
  // The measured peaks are below the limit (0.040) everywhere; what keeps
  // the test quiet is that none lasts arm_mode_raise_s (0.25 s): with a limit
  // of 0.025 none of the default list raises either (docs/mismatch.md).
  for (const Case& c :
       {Case{"hover", 0.0235}, Case{"gentle", 0.0280}, Case{"aggressive", 0.0246}, Case{"thrust_loss_severe", 0.0328},
        Case{"sensor_faults", 0.0391}, Case{"gauge_offset", 0.0214}, Case{"gauge_vibration", 0.0245},
        Case{"mismatch_thrust_coeff_plus20", 0.0221}, Case{"mismatch_thrust_coeff_minus20", 0.0398},
        Case{"mismatch_motor_lag_plus30", 0.0173}, Case{"mismatch_motor_lag_minus30", 0.0236}}) {
    // The file's mode judged (the peaks), and learning (the default).
    const ArmModeFigures f = Fly(c.name, NotLearningTipMass());
    EXPECT_EQ(f.mismatch, 0) << c.name;
    EXPECT_LE(f.peak_abs_error, 1.5 * c.peak_abs_error) << c.name;
    EXPECT_EQ(Fly(c.name, LearningTipMass()).mismatch, 0) << c.name;
  }
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor

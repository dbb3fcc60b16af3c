// The arm-mode test on any described vehicle (estimator/arm_mode_monitor.h,
// ExpectedArmMode of a VehicleDescription, in MultiArmPipeline): the birotor's
// description gives the birotor's test, the trirotor listens to its 64.6 Hz
// mode (arm 1 against arms 2 and 3), the quadrotor has none (its modes near
// 61 Hz ring alike). Flown by the real N-arm simulator and pipeline
// (evaluation/multi_arm_accuracy.h): a trirotor whose tip masses are 20 %
// off its file is raised MODEL_MISMATCH (tip_mass) for most of the flight,
// where before it was VALID and 0.56-0.90 N off with a 2-sigma share of
// 0.000, and its sigma carries the tip mass's prior until then; a matching
// one never. Figures measured on this commit; bounds at
// most 1.5x from them.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "estimator/arm_mode_monitor.h"
#include "estimator/multi_arm_pipeline.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_pipeline_feed.h"
#include "multi_arm_source_files.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

TEST(MultiArmArmMode, BirotorDescriptionGivesTheBirotorsTest) {
  const ArmModeExpectation birotor = ExpectedArmMode(BirotorParams());
  const ArmModeExpectation described = ExpectedArmMode(Vehicle("birotor"));
  EXPECT_NEAR(described.file_hz, birotor.file_hz, 1e-6);
  EXPECT_NEAR(described.low_hz, birotor.low_hz, 1e-6);
  EXPECT_NEAR(described.high_hz, birotor.high_hz, 1e-6);
  EXPECT_NEAR(described.stiffness_exponent, birotor.stiffness_exponent, 1e-6);
  EXPECT_NEAR(described.tip_weight_n, birotor.tip_weight_n, 1e-12);
  ASSERT_EQ(described.arms, 2);
  EXPECT_NEAR(described.weights[0], 1.0, 1e-9);  // b1 - b2
  EXPECT_NEAR(described.weights[1], -1.0, 1e-9);
  // d f_i / d r of the hover thrusts g (m + 2 r m_p) / 2: m_p g per rotor.
  EXPECT_NEAR(described.rotor_tip_weight_n[0], birotor.tip_weight_n, 1e-3);
  EXPECT_NEAR(described.rotor_tip_weight_n[1], birotor.tip_weight_n, 1e-3);
}

TEST(MultiArmArmMode, TrirotorListensToItsMostReadableMode) {
  const ArmModeExpectation e = ExpectedArmMode(Vehicle("trirotor"));
  EXPECT_NEAR(e.file_hz, 64.632, 0.001);  // birotor-analyze --vehicle config/vehicles/trirotor.yaml, mode 2
  ASSERT_EQ(e.arms, 3);
  EXPECT_NEAR(e.weights[0], 1.0, 1e-9);
  EXPECT_NEAR(e.weights[1], -0.4813, 1e-3);
  EXPECT_NEAR(e.weights[2], -0.4697, 1e-3);
  EXPECT_EQ(e.low_hz, e.file_hz);  // ideal gauges: no range
  EXPECT_GT(e.stiffness_exponent, 0.3);
  EXPECT_LT(e.stiffness_exponent, 0.6);
  // What every tip mass 20 % heavier puts into the hover thrusts, over 0.2:
  // rotor 1 carries part of the other tips' weight (birotor-analyze
  // --vehicle of both files: +0.8965 / +0.5641 / +0.5665 N).
  EXPECT_NEAR(e.rotor_tip_weight_n[0], 0.8965 / 0.2, 0.01);
  EXPECT_NEAR(e.rotor_tip_weight_n[1], 0.5641 / 0.2, 0.01);
  EXPECT_NEAR(e.rotor_tip_weight_n[2], 0.5665 / 0.2, 0.01);
}

// No test where the modes ring alike (the quadrotor) or where the arm the
// mode moves most has no gauge (the trirotor's 64.6 Hz mode without arm 1's);
// what the tip mass puts into each force is there all the same (its prior
// stays in the sigma).
TEST(MultiArmArmMode, NoTestWhereTheModesRingAlikeOrItsArmHasNoGauge) {
  const ArmModeExpectation quadrotor = ExpectedArmMode(Vehicle("quadrotor"));
  EXPECT_EQ(quadrotor.file_hz, 0.0);
  EXPECT_GT(quadrotor.rotor_tip_weight_n[0], 1.0);
  VehicleDescription without_arm_1 = Vehicle("trirotor");
  without_arm_1.arms[0].has_gauge = false;
  const ArmModeExpectation e = ExpectedArmMode(without_arm_1);
  EXPECT_EQ(e.file_hz, 0.0);
  EXPECT_NEAR(e.rotor_tip_weight_n[0], 0.8965 / 0.2, 0.01);
  // One gauge of two nulls no other mode: no test, the prior in the sigma.
  VehicleDescription one_gauge = Vehicle("birotor");
  one_gauge.arms[0].has_gauge = false;
  EXPECT_EQ(ExpectedArmMode(one_gauge).file_hz, 0.0);
  EXPECT_GT(ExpectedArmMode(Vehicle("birotor")).file_hz, 60.0);
}

// Without arm 3's gauge the same mode is read on arms 1 and 2, the 62.7 Hz
// mode (arms 2 and 3 against each other) nulled: no weight on arm 3.
TEST(MultiArmArmMode, TwoGaugesReadTheModeOnTheGaugesThereAre) {
  VehicleDescription two_gauges = Vehicle("trirotor");
  two_gauges.arms[2].has_gauge = false;
  const ArmModeExpectation e = ExpectedArmMode(two_gauges);
  EXPECT_NEAR(e.file_hz, ExpectedArmMode(Vehicle("trirotor")).file_hz, 1e-9);
  EXPECT_EQ(e.weights[2], 0.0);
  EXPECT_NEAR(e.weights[0], 1.0, 1e-9);
  EXPECT_TRUE(e.read_on_some_gauges);  // its readings' common bias is in the learned sigma
  EXPECT_FALSE(ExpectedArmMode(Vehicle("trirotor")).read_on_some_gauges);
}

TEST(MultiArmArmMode, AGaugeScaleInTheDescriptionWidensWhatTheModeMayBe) {
  VehicleDescription scaled = Vehicle("trirotor");
  scaled.arms[0].gauge_scale = 0.8;  // or arm 1 1.25 times stiffer: its mode higher
  const ArmModeExpectation e = ExpectedArmMode(scaled);
  EXPECT_EQ(e.low_hz, e.file_hz);
  EXPECT_GT(e.high_hz, 1.02 * e.file_hz);
  EXPECT_NEAR(e.weights[0], 1.0 / 0.8, 1e-9);  // the raw reading over its scale
}

struct ArmModeFlight {
  MultiArmAccuracy accuracy;
  MismatchParameter parameter = MismatchParameter::kNone;
  double peak_abs_error = 0;  // of the arm mode's readings [1]
};

// 8 s of the trirotor's gentle flight (seed `seed`; or its hover) with every
// tip mass scaled by tip_mass_scale, estimated with the shipped files (which
// learn the tip mass; learn false: the file's, judged against its mode).
ArmModeFlight FlyTrirotor(double tip_mass_scale, int seed, const std::string& kind = "gentle",
                          double turbulence_std = 0.01, bool learn = true) {
  EstimatorConfig config = Config();
  config.vehicle = Vehicle("trirotor");
  config.model_consistency.arm_mode_learn_tip_mass = learn;
  VehicleDescription flown = config.vehicle;
  for (int i = 0; i < flown.arm_count; ++i) flown.arms[static_cast<size_t>(i)].tip_mass_kg *= tip_mass_scale;
  flown.turbulence_std = turbulence_std;
  const Scenario gentle =
      ScenarioFor(kind, {"scenario.duration_s=8", "scenario.seed=" + std::to_string(seed)}, flown.arm_count);
  ArmModeFlight flight;
  flight.accuracy = RunMultiArmAccuracyFlying(flown, gentle, config, EvalOptions());
  MultiArmPipeline pipeline(config);
  MultiArmSimulator simulator(flown, gentle);
  FlyPipeline(&simulator, &pipeline);
  flight.parameter = pipeline.health().consistency.parameter;
  flight.peak_abs_error = pipeline.health().consistency.arm_mode.peak_abs_error;
  return flight;
}

// Measured: tip mass +20 %: MODEL_MISMATCH 0.953, VALID 0.047; -20 %: 0.953 /
// 0.047. The estimates before the raise (VALID, 0.56-0.90 N off) carry the
// tip mass's prior in their sigma: every estimate within 2 sigma (before
// the prior was in the N-arm sigma: 0.000).
TEST(MultiArmArmMode, TrirotorTipMassTwentyPercentOffIsRaisedAndNamed) {
  for (const double scale : {1.2, 0.8}) {
    const ArmModeFlight f = FlyTrirotor(scale, 2, "gentle", 0.01, false);
    std::printf("tip mass x%.1f: MODEL_MISMATCH %.3f, VALID %.3f, peak arm-mode error %.3f\n", scale,
                f.accuracy.mismatch_share, f.accuracy.valid_share, f.peak_abs_error);
    EXPECT_GT(f.accuracy.mismatch_share, 0.8) << scale;
    EXPECT_LT(f.accuracy.valid_share, 0.2) << scale;
    EXPECT_EQ(f.parameter, MismatchParameter::kTipMass) << scale;
    EXPECT_EQ(f.accuracy.nonfinite, 0);
    for (size_t i = 0; i < 3; ++i) EXPECT_GE(f.accuracy.rotor[i].share_within_2sigma, 0.99) << scale << " rotor " << i;
  }
}

// Tip mass +10 % reads -3 % (inside the 4 % limit: raised on part of the
// flight only) and a calm hover (turbulence 0.002) rings the mode below the
// excitation bar: neither is confirmed by the mean of the readings, so every
// estimate keeps the tip mass's prior in its sigma. Measured (8 s, seed 1):
// +10 % gentle VALID 1.000, 0.45 / 0.28 / 0.28 N off, every estimate within
// 2 sigma (0.39-0.40 when a stretch of readings within half the limit
// confirmed it); calm hover +20 % VALID 1.000, 0.89 / 0.56 / 0.56 N off,
// all within 2 sigma (0.014 when an unread mode dropped the prior).
// The +10 % flight with the file's tip mass judged (not learned), the calm
// hover as shipped (learning: a mode too quiet to read teaches nothing).
TEST(MultiArmArmMode, ATipMassTheModeDoesNotConfirmKeepsItsPriorInTheSigma) {
  const ArmModeFlight heavier = FlyTrirotor(1.1, 1, "gentle", 0.01, false);
  const ArmModeFlight calm = FlyTrirotor(1.2, 1, "hover", 0.002);
  for (const ArmModeFlight* f : {&heavier, &calm}) {
    std::printf("MODEL_MISMATCH %.3f, VALID %.3f, MAE %.3f / %.3f / %.3f N, 2-sigma %.3f / %.3f / %.3f\n",
                f->accuracy.mismatch_share, f->accuracy.valid_share, f->accuracy.rotor[0].mae_n,
                f->accuracy.rotor[1].mae_n, f->accuracy.rotor[2].mae_n, f->accuracy.rotor[0].share_within_2sigma,
                f->accuracy.rotor[1].share_within_2sigma, f->accuracy.rotor[2].share_within_2sigma);
    EXPECT_GT(f->accuracy.rotor[0].mae_n, 0.3);  // the error is there: the test is about the sigma
    for (size_t i = 0; i < 3; ++i) EXPECT_GE(f->accuracy.rotor[i].share_within_2sigma, 0.99) << "rotor " << i;
  }
  EXPECT_GT(calm.accuracy.valid_share, 0.9);  // the unread mode is not waited for
}

// The tip masses learned from the arm mode (every arm's r times its own,
// the EKF flying the file's and the learned r averaged): 10 % and 20 % off,
// VALID, never raised, the sigma honest. Measured (8 s, seed 1, learning
// time included): x1.2 0.141 / 0.089 / 0.091 N, 2-sigma 0.992 / 0.991 /
// 0.993; x0.8 0.122 / 0.079 / 0.076 N, 0.954 / 0.960 / 0.975; x1.1 0.151 /
// 0.097 / 0.096 N, 0.983 / 0.979 / 0.986 (the file's m_p flown: 0.45-0.90 N).
TEST(MultiArmArmMode, TrirotorTipMassIsLearned) {
  for (const double scale : {1.2, 0.8, 1.1}) {
    const ArmModeFlight f = FlyTrirotor(scale, 1);
    std::printf(
        "learned tip mass x%.1f: MODEL_MISMATCH %.3f, VALID %.3f, MAE %.3f / %.3f / %.3f N, 2-sigma %.3f / "
        "%.3f / %.3f\n",
        scale, f.accuracy.mismatch_share, f.accuracy.valid_share, f.accuracy.rotor[0].mae_n, f.accuracy.rotor[1].mae_n,
        f.accuracy.rotor[2].mae_n, f.accuracy.rotor[0].share_within_2sigma, f.accuracy.rotor[1].share_within_2sigma,
        f.accuracy.rotor[2].share_within_2sigma);
    EXPECT_EQ(f.accuracy.mismatch_share, 0.0) << scale;
    EXPECT_GE(f.accuracy.valid_share, 0.98) << scale;
    for (size_t i = 0; i < 3; ++i) EXPECT_GE(f.accuracy.rotor[i].share_within_2sigma, 0.90) << scale << " rotor " << i;
    EXPECT_LT(f.accuracy.rotor[0].mae_n, 0.2) << scale;  // the file's m_p flown: 0.45-0.90 N
  }
}

// Measured on seeds 1-3: never raised, peak arm-mode error 0.020 / 0.016 /
// 0.013 (the limit 0.040) against the file's mode; learning, never raised.
TEST(MultiArmArmMode, MatchingTrirotorIsNeverRaised) {
  for (const int seed : {1, 2, 3}) {
    EXPECT_EQ(FlyTrirotor(1.0, seed).accuracy.mismatch_share, 0.0) << seed;
    const ArmModeFlight f = FlyTrirotor(1.0, seed, "gentle", 0.01, false);
    std::printf("seed %d: MODEL_MISMATCH %.3f, VALID %.3f, peak arm-mode error %.3f\n", seed, f.accuracy.mismatch_share,
                f.accuracy.valid_share, f.peak_abs_error);
    EXPECT_EQ(f.accuracy.mismatch_share, 0.0) << seed;
    EXPECT_GE(f.accuracy.valid_share, 0.98) << seed;
    EXPECT_LT(f.peak_abs_error, 0.03) << seed;
  }
}

}  // namespace
}  // namespace birotor

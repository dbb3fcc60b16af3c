// The birotor's gauge features on the N-arm pipeline (issue 38 item 1,
// estimator/multi_arm_pipeline.h): the strain noise learned online
// (NoiseAdaptation in MultiArmEkf) keeps a trirotor with gauges twice
// as noisy as the file VALID with an honest sigma, so does the
// accelerometer's with one 20x as noisy, and the model-consistency
// monitor (ModelConsistencyMonitor on the filter's fusion reports) stays
// quiet on a matching trirotor and raises MODEL_MISMATCH, withdrawing
// VALID, on one whose gauges read 20 % low (as arms 25 % stiffer than the
// file), and on one carrying a payload the file lacks (the offset-departure
// test). Runs of the real N-arm simulator and pipeline
// (evaluation/multi_arm_accuracy.h); figures measured on this commit, bounds
// at most 1.5x from them.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "estimator/multi_arm_pipeline.h"
#include "evaluation/multi_arm_accuracy.h"
#include "multi_arm_pipeline_feed.h"
#include "multi_arm_source_files.h"
#include "simulator/multi_arm_simulator.h"

namespace birotor {
namespace {

// 8 s of the trirotor's gentle flight with the gauges' sigma 4e-5 rad, twice
// the file's ekf.strain_noise_rad (birotor-eval --set
// sensors.strain.noise_rad=4.0e-5), against the same flight with the file's
// noise. The targets of issue 38 item 1: MAE within 15 % of the matching
// flight's, 2-sigma share in [0.93, 0.98], VALID >= 0.98, no MODEL_MISMATCH.
// Measured: MAE 0.0819 / 0.0532 / 0.0554 N against 0.0768 / 0.0500 / 0.0516 N
// (+6.6 / +6.4 / +7.4 %), 2-sigma share 0.953 / 0.968 / 0.968, VALID 1.000.
// Before the adaptation (main 6d6fd52, birotor-eval on the whole 15 s
// gentle flight): MAE +15 to +17 %, 2-sigma share 0.916 / 0.938 / 0.943.
TEST(MultiArmConsistencyTest, TrirotorGaugesTwiceAsNoisyStayValidWithAnHonestSigma) {
  const MultiArmAccuracy matching = RunMultiArmAccuracy(
      Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=8"}, 3), Config(), EvalOptions());
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=8", "sensors.strain.noise_rad=4.0e-5"}, 3),
      Config(), EvalOptions());
  ASSERT_EQ(r.n_rotors, 3);
  EXPECT_EQ(r.nonfinite, 0);
  for (size_t i = 0; i < 3; ++i) {
    std::printf("rotor %zu: MAE %.4f N (matching %.4f N), 2-sigma share %.3f\n", i + 1, r.rotor[i].mae_n,
                matching.rotor[i].mae_n, r.rotor[i].share_within_2sigma);
    EXPECT_LT(r.rotor[i].mae_n, 1.15 * matching.rotor[i].mae_n) << "rotor " << i + 1;
    EXPECT_GE(r.rotor[i].share_within_2sigma, 0.93) << "rotor " << i + 1;
    EXPECT_LE(r.rotor[i].share_within_2sigma, 0.98) << "rotor " << i + 1;
  }
  EXPECT_GE(r.valid_share, 0.98);
  EXPECT_EQ(r.mismatch_share, 0.0);
}

// The scales the pipeline's EKF learned on the same noisy flight (its
// health, as ESTIMATOR_STATUS's service reads it): the variance is 4x the
// file's. Measured 4.024 / 3.816 / 4.062; asserted within [3.0, 5.0].
TEST(MultiArmConsistencyTest, TrirotorLearnsTheGaugesVariance) {
  EstimatorConfig config = Config();
  config.vehicle = Vehicle("trirotor");
  MultiArmPipeline pipeline(config);
  MultiArmSimulator simulator(config.vehicle,
                              ScenarioFor("gentle", {"scenario.duration_s=8", "sensors.strain.noise_rad=4.0e-5"}, 3));
  FlyPipeline(&simulator, &pipeline);
  for (size_t i = 0; i < 3; ++i) {
    const double scale = pipeline.health().strain_noise_scale[i];
    std::printf("gauge %zu: learned variance scale %.3f\n", i + 1, scale);
    EXPECT_GT(scale, 3.0) << "gauge " << i + 1;
    EXPECT_LT(scale, 5.0) << "gauge " << i + 1;
  }
  EXPECT_EQ(pipeline.health().last_status & kStatusModelMismatch, 0);
}

// 8 s of the trirotor's hover with the accelerometer's sigma 1 m/s^2, 20x
// the file's ekf.accel_noise_m_s2 (birotor-eval --vehicle ... --set
// sensors.imu.accel_noise_m_s2=1.0): the noise learned online (a_z and a_x,
// NoiseAdaptation in MultiArmEkf) keeps it VALID, without MODEL_MISMATCH.
// Measured: MAE 0.0940 / 0.0862 / 0.0823 N, 2-sigma share 0.985 / 0.988 /
// 0.992, VALID 1.000; without the adaptation (adapt_accel_noise false)
// MODEL_MISMATCH throughout, VALID 0.000, MAE up to 0.71 N. Seed 3; on
// seed 1 the first second's convergence weighs more in 8 s (rotor 3: MAE
// 0.168 N, 2-sigma share 0.883; over its 20 s 0.106 N, 0.954).
TEST(MultiArmConsistencyTest, TrirotorWithANoisyAccelerometerStaysValid) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"),
      ScenarioFor("hover", {"scenario.duration_s=8", "scenario.seed=3", "sensors.imu.accel_noise_m_s2=1.0"}, 3),
      Config(), EvalOptions());
  ASSERT_EQ(r.n_rotors, 3);
  EXPECT_EQ(r.nonfinite, 0);
  for (size_t i = 0; i < 3; ++i) {
    std::printf("rotor %zu: MAE %.4f N, 2-sigma share %.3f\n", i + 1, r.rotor[i].mae_n, r.rotor[i].share_within_2sigma);
    EXPECT_LT(r.rotor[i].mae_n, 0.14) << "rotor " << i + 1;
    EXPECT_GE(r.rotor[i].share_within_2sigma, 0.93) << "rotor " << i + 1;
  }
  EXPECT_GE(r.valid_share, 0.98);
  EXPECT_EQ(r.mismatch_share, 0.0);
}

// The first 2.5 s of the same hover on the seeds whose start was VALID and
// wrong: the accelerometer's first samples fused at the file's variance
// (before the noise scale could move) left rotors 2 and 3 0.53 N off at a
// 2-sigma share of 0.05 / 0.12 (seed 7), 0.23 / 0.34 N at 0.76 / 0.49
// (seed 10), 0.24 / 0.29 N at 0.86 / 0.66 (seed 12), VALID throughout. At an
// airborne start the accelerometer now waits for accel_noise_min_samples
// learned pairs. Measured: 2-sigma share 0.982-0.999 on every rotor, MAE at
// most 0.134 N, VALID 1.000, no MODEL_MISMATCH.
TEST(MultiArmConsistencyTest, TrirotorWithANoisyAccelerometerStartsHonest) {
  for (const int seed : {7, 10, 12}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const MultiArmAccuracy r = RunMultiArmAccuracy(
        Vehicle("trirotor"),
        ScenarioFor(
            "hover",
            {"scenario.duration_s=2.5", "scenario.seed=" + std::to_string(seed), "sensors.imu.accel_noise_m_s2=1.0"},
            3),
        Config(), EvalOptions());
    ASSERT_EQ(r.n_rotors, 3);
    EXPECT_EQ(r.nonfinite, 0);
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_LT(r.rotor[i].mae_n, 0.16) << "rotor " << i + 1;
      EXPECT_GT(r.rotor[i].share_within_2sigma, 0.95) << "rotor " << i + 1;
    }
    EXPECT_GE(r.valid_share, 0.98);
    EXPECT_EQ(r.mismatch_share, 0.0);
  }
}

// The matching trirotor (4 s of the gentle flight): no MODEL_MISMATCH.
TEST(MultiArmConsistencyTest, MatchingTrirotorRaisesNoMismatch) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=4"}, 3), Config(), EvalOptions());
  EXPECT_EQ(r.mismatch_share, 0.0);
  EXPECT_GT(r.valid_share, 0.99);
}

// Every gauge reads 0.8 of the file's scale (gauge.scale, the simulator's
// true gauges; to the strain the arms look 25 % stiffer). Measured on 4 s of
// the gentle flight: MODEL_MISMATCH on every scored estimate (from 0.5 s),
// VALID on none (birotor-eval on the whole flight: the same, 1.000 and 0.000).
TEST(MultiArmConsistencyTest, TrirotorWithGaugesReadingLowRaisesMismatch) {
  const MultiArmAccuracy r = RunMultiArmAccuracy(
      Vehicle("trirotor"), ScenarioFor("gentle", {"scenario.duration_s=4", "gauge.scale=[0.8, 0.8, 0.8]"}, 3), Config(),
      EvalOptions());
  EXPECT_GT(r.mismatch_share, 0.0);
  EXPECT_LT(r.valid_share, 1.0 - r.mismatch_share + 1e-9);  // VALID withdrawn while raised
}

// The shipped estimator file on the trirotor's description.
EstimatorConfig TrirotorConfig() {
  EstimatorConfig config = Config();
  config.vehicle = Vehicle("trirotor");
  return config;
}

// 4 s of gentle (seed 3) flown by the description with its body mass set to
// body_mass_kg, estimated with config's (the file's) description.
MultiArmAccuracy FlyGentleWithBody(const EstimatorConfig& config, double body_mass_kg) {
  VehicleDescription flown = config.vehicle;
  flown.body_mass_kg = body_mass_kg;
  return RunMultiArmAccuracyFlying(flown, ScenarioFor("gentle", {"scenario.duration_s=4"}, 3), config, EvalOptions());
}

// A payload the description lacks (body 4.4 kg against 4.0; the offset-
// departure test, docs/mismatch.md "Offsets that took a force"): the gauge
// offsets take it and the test raises MODEL_MISMATCH. Measured on the whole
// gentle flight (birotor-sim --vehicle, birotor-replay, seeds 1-3):
// MISMATCH 1.000 of the scored estimates (before: VALID, 2.30 / 1.15 / 1.15
// N off, 2-sigma share 0.000); on 4 s here every scored estimate raised.
TEST(MultiArmConsistencyTest, TrirotorWithAPayloadRaisesMismatch) {
  const EstimatorConfig config = TrirotorConfig();
  VehicleDescription heavier = config.vehicle;
  heavier.body_mass_kg = 4.4;
  const MultiArmAccuracy r = FlyGentleWithBody(config, 4.4);
  EXPECT_GT(r.mismatch_share, 0.99);
  EXPECT_EQ(r.valid_share, 0.0);
  // What a stop persists: not the offsets that took the payload but the
  // anchor they left (the description's, with its sigma).
  MultiArmPipeline pipeline(config);
  MultiArmSimulator simulator(heavier, ScenarioFor("gentle", {"scenario.duration_s=2"}, 3));
  FlyPipeline(&simulator, &pipeline);
  ASSERT_TRUE(pipeline.health().consistency.offsets.departed);
  const MultiArmGaugeState state = pipeline.GaugeState();
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(state.offset_rad[i], config.vehicle.arms[i].gauge_offset_rad) << "gauge " << i + 1;
    EXPECT_EQ(state.offset_std_rad[i], config.vehicle.gauge_offset_std_rad) << "gauge " << i + 1;
  }
}

// Body +5 % on the trirotor, airborne: within the offset-departure limit,
// so VALID and about 1.15 / 0.57 / 0.57 N off, but the departure is in
// each sigma (offset_departure_in_sigma_above): 2-sigma share measured
// 1.000 on every rotor (before: 0.008-0.014).
TEST(MultiArmConsistencyTest, TrirotorPayloadWithinTheLimitIsInTheSigma) {
  const MultiArmAccuracy r = FlyGentleWithBody(TrirotorConfig(), 4.2);
  EXPECT_EQ(r.mismatch_share, 0.0);
  EXPECT_GT(r.valid_share, 0.9);
  for (int i = 0; i < 3; ++i) {
    const MultiArmRotorAccuracy& rotor = r.rotor[static_cast<size_t>(i)];
    std::printf("rotor %d: MAE %.3f N, 2-sigma share %.3f\n", i + 1, rotor.mae_n, rotor.share_within_2sigma);
    EXPECT_GT(rotor.mae_n, 0.3) << "rotor " << i + 1;  // the payload's share: not learned
    EXPECT_GE(rotor.share_within_2sigma, 0.9) << "rotor " << i + 1;
  }
}

}  // namespace
}  // namespace birotor

// Online learning of the strain scale g_i (issue 27 item 2,
// estimator/ekf_parameter_learning.cc, EkfOptions::learn_strain_scale,
// docs/mismatch.md): the mismatch scenarios it fixes, the
// matching-file scenarios it leaves alone, no learning on the ground, and a
// start from a persisted value. Figures measured on the development VM with
// the shipped config/estimator.yaml plus learn_strain_scale (docs/mismatch.md);
// bounds at most 1.5x.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

struct LearningFigures {
  double mae_n[2] = {0, 0};         // after 5 s [N]
  double share[2] = {0, 0};         // 2-sigma share after 5 s
  int64_t mismatch = 0;             // estimates with MODEL_MISMATCH
  int64_t late_mismatch = 0;        // ... of them 2.5 s or more after the first estimate
  double strain_scale[2] = {1, 1};  // learned at the end
};

LearningFigures Fly(const std::string& name, const EstimatorConfig& config,
                    const GaugeCalibration* persisted = nullptr) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile(name)), config, persisted);
  LearningFigures f;
  const int64_t from = run.forces.front().utime + 5000000;
  for (int i = 0; i < 2; ++i) {
    f.mae_n[i] = ForceMae(run, i, from);
    f.share[i] = ShareWithin2Sigma(run, i, from);
    f.strain_scale[i] = run.gauge_offsets.back().strain_scale[i];
  }
  const int64_t late = run.forces.front().utime + 2500000;
  for (const ForceEstimate& e : run.forces) {
    f.mismatch += (e.status & kStatusModelMismatch) ? 1 : 0;
    f.late_mismatch += (e.utime > late && (e.status & kStatusModelMismatch)) ? 1 : 0;
  }
  std::printf("%s: MAE %.4f / %.4f N, share %.3f / %.3f, mismatch %lld, g %.4f / %.4f\n", name.c_str(), f.mae_n[0],
              f.mae_n[1], f.share[0], f.share[1], static_cast<long long>(f.mismatch), f.strain_scale[0],
              f.strain_scale[1]);
  return f;
}

// Without learning these raise MODEL_MISMATCH at 0.5 s with 3.2-4.4 N MAE;
// learning makes them accurate with an honest share. Until the arm mode has
// told the scales apart (about 1 s) the offsets' departure holds
// MODEL_MISMATCH, and the windows clear it 2 s after the raise (docs/mismatch.md
// "What a learned strain scale is"). Measured MAE 0.087 / 0.086 N (the
// stiffer arm: its mode is read as 90 % stiffness, 10 % tip mass on this
// seed; 0.068-0.075 on seeds 1-3), 0.072 / 0.066, 0.064 / 0.067; MODEL_MISMATCH
// on the first 1895-1898 estimates, none after.
TEST(StrainScaleLearning, StiffArmAndGaugeScaleAreLearned) {
  for (const char* name : {"mismatch_stiffness_plus20", "mismatch_gauge_scale_0p7", "mismatch_gauge_scale_1p3"}) {
    const LearningFigures f = Fly(name, StrainScaleLearningConfig());
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(f.mae_n[i], 0.10) << name;  // issue 36's bound for a changed vehicle
      EXPECT_GE(f.share[i], 0.90) << name;  // measured 0.906-0.966; the 0.90-0.98
      EXPECT_LE(f.share[i], 0.98) << name;
    }
    EXPECT_EQ(f.late_mismatch, 0) << name;
    EXPECT_LE(f.mismatch, 2500) << name;
  }
}

// The learned gauge-1 scale of a gauge reading 0.7 of the file: it points
// the right way and arm 2's stays near 1 (measured g1 / g2 at 15 s below).
TEST(StrainScaleLearning, TheLowGaugeIsTheOneThatMoves) {
  const LearningFigures f = Fly("mismatch_gauge_scale_0p7", StrainScaleLearningConfig());
  EXPECT_LT(f.strain_scale[0], 0.85);
  EXPECT_NEAR(f.strain_scale[1], 1.0, 0.05);
}

// Matching file: learning on changes the MAE by at most 3 % (issue 27) and
// raises nothing; gauge_drift starts on the ground, where nothing is
// learned (the tare's rest deflection would otherwise be taken as a scale:
// 0.30 N MAE and a raise before the freeze).
TEST(StrainScaleLearning, MatchingFileUnchanged) {
  for (const char* name : {"gentle", "gauge_drift"}) {
    const LearningFigures off = Fly(name, ReferenceConfig());
    const LearningFigures on = Fly(name, StrainScaleLearningConfig());
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(on.mae_n[i], 1.03 * off.mae_n[i]) << name;
      EXPECT_GE(on.share[i], 0.93) << name;
      EXPECT_LE(on.share[i], 0.98) << name;
      EXPECT_NEAR(on.strain_scale[i], 1.0, 0.03) << name;
    }
    EXPECT_EQ(on.mismatch, 0) << name;
  }
}

TEST(StrainScaleLearning, NothingIsLearnedOnTheGround) {
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile("gauge_drift")), StrainScaleLearningConfig());
  ASSERT_GT(run.liftoff_utime, 0);
  for (const GaugeOffsetSample& s : run.gauge_offsets) {
    if (s.utime >= run.liftoff_utime - 1000000) break;  // rest and spool-up: supported
    ASSERT_EQ(s.strain_scale[0], 1.0) << s.utime;
    ASSERT_EQ(s.strain_scale[1], 1.0) << s.utime;
  }
}

// After a landing the published sigma stays the one learned in the air (what
// a clean stop persists): at rest the deflection is too small to weigh the
// offset by (e_i / b_i would widen it to the 0.5 ceiling). Measured: held
// through the rest; g 0.9964 +- 0.0695 / 1.0010 +- 0.0575 (the gauges'
// real drift is in the offsets, which the widening counts as a possible
// scale: honest, not narrow).
TEST(StrainScaleLearning, ALandingKeepsTheSigmaOfTheFlight) {
  const ScenarioRun run =
      RunScenario(LoadScenario(ScenarioFile("gauge_drift"), {"ground.land=true", "ground.rest_after_s=2"}),
                  StrainScaleLearningConfig());
  const GaugeOffsetSample& last = run.gauge_offsets.back();
  std::printf("after the landing: g %.4f +- %.4f / %.4f +- %.4f\n", last.strain_scale[0], last.strain_scale_std[0],
              last.strain_scale[1], last.strain_scale_std[1]);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(last.strain_scale[i], 1.0, 0.02) << i;  // matching file; measured 0.0036 off
    EXPECT_LT(last.strain_scale_std[i], 0.1) << i;      // 1.5 x the measured 0.069 at most
    EXPECT_EQ(last.strain_scale_std[i], run.gauge_offsets[run.gauge_offsets.size() - 1000].strain_scale_std[i]);
  }
}

// A restart with the state file's strain scale (as birotor-estimator starts
// from it): accurate from the first second instead of after the learning.
TEST(StrainScaleLearning, APersistedScaleIsUsedFromTheStart) {
  const EstimatorConfig config = StrainScaleLearningConfig();
  const Scenario scenario = LoadScenario(ScenarioFile("mismatch_gauge_scale_0p7"));
  const ScenarioRun first = RunScenario(scenario, config);
  GaugeCalibration persisted = GaugeCalibration::FromVehicle(BirotorModelOf(config.vehicle));
  persisted.source = GaugeOffsetSource::kStateFile;
  persisted.has_strain_scale = true;
  for (int i = 0; i < 2; ++i) {
    persisted.strain_scale[i] = first.health.gauge.strain_scale[i];
    persisted.strain_scale_std[i] = first.health.gauge.strain_scale_std[i];
  }
  const ScenarioRun second = RunScenario(scenario, config, &persisted);
  const int64_t from = second.forces.front().utime + 1000000;
  int64_t mismatch = 0;
  for (const ForceEstimate& e : second.forces) mismatch += (e.status & kStatusModelMismatch) ? 1 : 0;
  for (int i = 0; i < 2; ++i) {
    // It starts where the first run ended (the 0.5 ms until the first
    // prediction moves nothing) ...
    EXPECT_EQ(second.gauge_offsets.front().strain_scale[i], persisted.strain_scale[i]);
    const double mae_first = ForceMae(first, i, from), mae_second = ForceMae(second, i, from);
    std::printf("rotor %d from 1 s: first run %.4f N, restarted %.4f N\n", i, mae_first, mae_second);
    // ... and is accurate from 1 s on: the bound (1.15 x the true-file 0.067 N).
    EXPECT_LE(mae_second, 0.077);
  }
  EXPECT_EQ(mismatch, 0);
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor

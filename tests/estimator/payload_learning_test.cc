// Learning the payload (issue 36 items 1 and 3, docs/mismatch.md "Learning
// the payload"): the gentle flight with the body 10 % and 15 % heavier than
// config/reference_vehicle.yaml, airborne from the start and after a ground
// phase, the matching gentle flight and a thrust step, with the shipped
// config/estimator.yaml with learn_body_mass switched on (off by default:
// docs/mismatch.md says why). Seed 1; the
// figures as `birotor-eval --mismatch-targets` scores them
// (evaluation/mismatch_targets.h: from 5 s after the airborne start, 1 s for
// the matching vehicle); bounds at most 1.5x the measured figure.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "evaluation/mismatch_targets.h"
#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace testing_support {
namespace {

struct PayloadFigures {
  MismatchTargetFigures targets;
  double body_mass_kg = 0;      // published at the end [kg]
  double body_mass_std_kg = 0;  // [kg]
};

// The gentle flight (or `scenario`), seed 1 (or `seed`), with overrides; ground: the
// shipped ground phase (rest 3 s, spool-up 1 s) and 19 s, as
// evaluation/mismatch_cases.cc.
PayloadFigures Fly(const std::string& name, std::vector<std::string> overrides, bool ground, bool learn,
                   double settle_s = 5.0, const std::string& scenario = "gentle", int seed = 1) {
  if (ground) overrides.insert(overrides.begin(), {"ground.enabled=true", "scenario.duration_s=19"});
  overrides.push_back("scenario.seed=" + std::to_string(seed));
  EstimatorConfig config = ReferenceConfig();
  config.ekf.learn_body_mass = learn;
  const ScenarioRun run = RunScenario(LoadScenario(ScenarioFile(scenario), overrides), config);
  MismatchTargets targets;
  targets.settle_s = settle_s;
  PayloadFigures f;
  f.targets = EvaluateMismatchTargets(run.forces, run.truth, run.liftoff_utime, targets);
  f.body_mass_kg = run.health.body_mass_kg;
  f.body_mass_std_kg = run.health.body_mass_std_kg;
  std::printf("%s: VALID %.3f, MAE %.4f N, 2-sigma %.3f, worst window %.3f, mass %.4f +- %.4f kg\n", name.c_str(),
              f.targets.valid_share, f.targets.valid_mae_n, f.targets.two_sigma_share, f.targets.worst_window_share,
              f.body_mass_kg, f.body_mass_std_kg);
  return f;
}

// Body +10 % from an airborne start: with the mass fixed the offsets take
// Delta m g / 2 per rotor (1.959 N off, VALID, 2-sigma share 0.000 before the
// offset-departure test; now raised at 0.1 s). Learned:
// VALID 1.000, MAE 0.081 N, 2-sigma share 1.000, worst window 0.999; the
// published mass 4.40 kg.
TEST(PayloadLearning, AirborneTenPercentIsLearned) {
  const PayloadFigures f = Fly("body +10 %, airborne", {"vehicle.body_mass_kg=4.4"}, false, true);
  EXPECT_GE(f.targets.valid_share, 0.80);
  EXPECT_LE(f.targets.valid_mae_n, 0.10);  // issue 36's target (1.23x the measured)
  EXPECT_GE(f.targets.two_sigma_share, 0.90);
  EXPECT_GE(f.targets.worst_window_share, 0.80);
  EXPECT_NEAR(f.body_mass_kg, 4.4, 3.0 * f.body_mass_std_kg + 0.01);
  // With the mass fixed the offsets take it and the offset-departure test
  // raises MODEL_MISMATCH at 0.1 s (offset_departure_test.cc): never VALID.
  const PayloadFigures fixed = Fly("body +10 %, airborne, mass fixed", {"vehicle.body_mass_kg=4.4"}, false, false);
  EXPECT_EQ(fixed.targets.valid_share, 0.0);
}

// Body +15 % airborne: with the mass fixed never VALID (MODEL_MISMATCH at
// 11 ms); learned: VALID 1.000, MAE 0.177 N (NOT the target's 0.10 on this
// seed; 0.112 N over seeds 1-5), 2-sigma share 0.991; the worst 2 s window
// from the start 0.338 (NOT met: the first seconds, while the mass is
// learned, are VALID and off).
TEST(PayloadLearning, AirborneFifteenPercentIsValidAndCovered) {
  const PayloadFigures f = Fly("body +15 %, airborne", {"vehicle.body_mass_kg=4.6"}, false, true);
  EXPECT_GE(f.targets.valid_share, 0.80);
  EXPECT_LE(f.targets.valid_mae_n, 0.26);  // 1.5x the measured 0.177
  EXPECT_GE(f.targets.two_sigma_share, 0.90);
}

// After a ground phase (the gauges tared at rest): learned from the
// lift-off on, with the learned states and offsets held for step_hold_s
// through the lift-off (EkfOptions::step_hold_s), body +10 % is VALID
// 0.081 N off with a 2-sigma share of 0.972 and the mass 4.394 +- 0.012 kg
// (without the hold: 0.485 N and 0.001, the mass learned through the
// lift-off wrong and sure of it; with the mass fixed 1.959 N and 0.000).
TEST(PayloadLearning, GroundStartIsLearnedThroughTheLiftOff) {
  const PayloadFigures f = Fly("body +10 %, ground start", {"vehicle.body_mass_kg=4.4"}, true, true);
  EXPECT_GE(f.targets.valid_share, 0.80);
  EXPECT_LE(f.targets.valid_mae_n, 0.10);  // issue 36's target (1.23x the measured)
  EXPECT_GE(f.targets.two_sigma_share, 0.90);
  EXPECT_GE(f.targets.worst_window_share, 0.80);
  EXPECT_NEAR(f.body_mass_kg, 4.4, 3.0 * f.body_mass_std_kg + 0.01);
}

// A rotor's thrust step on the matching vehicle (thrust_loss seed 3: rotor 2
// at 75 % from 5 s) is not a payload: the learned states and the offsets are
// held while the strain gate rejects and for step_hold_s after it let the
// step in, so the forces' ringing right after the step does not reach the
// mass. MAE 0.081 N, 2-sigma share 0.988, the mass 4.005 +- 0.021 kg
// (without the hold: the mass stepped to 4.15 kg within 10 ms and stayed,
// MAE 0.43 N, 2-sigma share 0.31; seed 1 went through at 0.070 N; seeds
// 1-5: 0.274 N, 0.559).
TEST(PayloadLearning, ThrustStepIsNotAPayload) {
  const PayloadFigures f = Fly("thrust_loss seed 3, learned", {}, false, true, 1.0, "thrust_loss", 3);
  EXPECT_GE(f.targets.valid_share, 0.98);
  EXPECT_LE(f.targets.valid_mae_n, 0.10);
  EXPECT_GE(f.targets.two_sigma_share, 0.93);
  EXPECT_NEAR(f.body_mass_kg, 4.0, 0.03);
}

// The matching vehicle (gentle, seed 1): MAE 0.068 N with the mass learned
// as with it fixed; 2-sigma share 0.970 (0.957 fixed), within issue 36's
// 0.93-0.98.
TEST(PayloadLearning, MatchingVehicleKeepsItsAccuracy) {
  const PayloadFigures learned = Fly("gentle, learned", {}, false, true, 1.0);
  const PayloadFigures fixed = Fly("gentle, mass fixed", {}, false, false, 1.0);
  EXPECT_LE(learned.targets.valid_mae_n, 1.03 * fixed.targets.valid_mae_n);
  EXPECT_GE(learned.targets.valid_share, 0.98);
  EXPECT_GE(learned.targets.two_sigma_share, 0.93);
  EXPECT_LE(learned.targets.two_sigma_share, 0.98);
  EXPECT_NEAR(learned.body_mass_kg, 4.0, 0.02);  // the file's, averaged over both hypotheses
}

}  // namespace
}  // namespace testing_support
}  // namespace birotor
